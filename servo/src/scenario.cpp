// SPDX-License-Identifier: GPL-2.0-or-later
// Servo scenario files, read through icgp's YAML layer (icgp/io/yaml_reader.h): every
// section is a yaml::Map, which rejects unknown and duplicate keys, and every value's error
// says what was expected and what the file holds: "<file>: <field>: expected <what>, got
// <value>".
#include "icgp/servo/scenario.h"

#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "icgp/base/resource_limits.h"
#include "icgp/io/model_reference.h"
#include "icgp/io/yaml_reader.h"
#include "icgp/modality/cue_kind.h"
#include "icgp/servo/scenario_profile.h"
#include "icgp/tracker/cue_registry.h"

namespace icgp::servo {
namespace {

namespace fs = std::filesystem;

using yaml::any;
using yaml::convert;
using yaml::Location;
using yaml::Interval;
using yaml::kBool;
using yaml::kNonEmptyString;
using yaml::kString;
using yaml::numbers;
using yaml::pose;
using yaml::Map;
using yaml::Rule;
using yaml::Value;

// The range of every number of a scenario (docs/servo.md, "Limits"). They are far beyond any
// real setup: their job is to refuse values that would exhaust memory or time (a camera of
// 10^5 px a side, a rate of 10^9 Hz), overflow the arithmetic of a run, or make the
// simulation meaningless (a velocity of 10^300 m/s), naming the field, before anything runs.
constexpr Interval kCoordinate = yaml::kPoseCoordinate;  ///< m: pose translations, occluder placement
using yaml::kAngleDeg;                                  ///< deg: θu components, joint angles
constexpr Interval kObjectVelocity{-10.0, 10.0};        ///< m/s, per axis
constexpr Interval kOccluderVelocity{-100.0, 100.0};    ///< m/s, per axis
constexpr Interval kOccluderSize{0.0, 100.0};           ///< m, per edge
constexpr Interval kSimulatedTime{0.0, 86400.0};        ///< s: motion and occluder times, settle time
constexpr Interval kMaxTime{0.0, 86400.0, true};        ///< s: stop.max_time (a day; steps bound it further)
constexpr Interval kRateHz{0.0, 1000.0, true};          ///< camera frames per second
constexpr Interval kFocalPx{0.0, 100000.0, true};       ///< px
constexpr Interval kPrincipalPointPx{-kMaxImageSide, 2.0 * kMaxImageSide};  ///< px, may lie outside the image
constexpr Interval kBackgroundDistance{0.0, 100.0};    ///< m
constexpr Interval kLightDirection{-1000.0, 1000.0};    ///< per axis; normalised, only its direction counts
constexpr Interval kFraction{0.0, 1.0};
constexpr Interval kLightTurnRateDeg{-3600.0, 3600.0};  ///< deg/s
constexpr Interval kFlickerHz{0.0, 10000.0};            ///< Hz
constexpr Interval kTimeConstantS{0.0, 60.0, true};     ///< s: auto-exposure
constexpr Interval kProbability{0.0, 1.0, false, true};  ///< [0, 1): 1 would drop every frame or pixel
constexpr Interval kColorSigma{0.0, 255.0};             ///< 8-bit levels
constexpr Interval kDepthSigmaAt1m{0.0, 1.0};           ///< m
constexpr Interval kGrazingAngleDeg{0.0, 90.0, true};
constexpr long long kMaxEdgeDropoutPx = 100;            ///< a (2r+1)² dilation per frame
constexpr Interval kGain{0.0, 1000.0, true};            ///< 1/s
constexpr Interval kGainSlope{0.0, 100000.0, true};
constexpr Interval kLinearVelocity{0.0, 10.0, true};    ///< m/s
constexpr Interval kAngularVelocityDeg{0.0, 3600.0, true};  ///< deg/s
constexpr Interval kThresholdMm{0.0, 1000.0};           ///< convergence thresholds and trial offsets
constexpr Interval kThresholdDeg{0.0, 180.0};
constexpr Interval kFocalErrorPercent{0.0, 50.0};     ///< %: of the focal length
constexpr Interval kScaleErrorPercent{-50.0, 50.0};   ///< %: of the object's size
constexpr Interval kRadialDistortion{-0.5, 0.5};      ///< k1, normalised coordinates
constexpr Interval kVertexNoiseMm{0.0, 100.0};        ///< mm
constexpr Interval kPrincipalPointErrorPx{0.0, 1000.0};  ///< px
constexpr Interval kDelayMs{0.0, 86400e3};              ///< ms: latency (a run checks it against max_time)
constexpr Interval kSpreadMs{0.0, 1e4};                 ///< ms: jitter, lag, compute time
constexpr Interval kLinearAcceleration{0.0, 1e6, true};  ///< m/s²
constexpr Interval kAngularAccelerationDeg{0.0, 1e8, true};  ///< deg/s²
constexpr long long kMaxCyclesSamples = 4096;           ///< paths per pixel
constexpr long long kMaxLightBounces = 128;
constexpr long long kMaxRenderThreads = 1024;
constexpr Interval kRenderTimeoutS{0.0, 86400.0, true};  ///< s: one Blender request

/// A camera-object pose: the object must be in front of the camera.
Pose object_pose(const Value& v) {
  const Pose cMo = pose(v);
  if (!(cMo.translation().z() > 0.0)) {
    const Value t = Map(v, {"t", "r_deg"}).required("t");
    t.at.fail("the object must be in front of the camera (z > 0), got " + yaml::describe(t.node));
  }
  return cMo;
}

/// {width, height, focal} or {fu, fv, pu, pv, width, height}. Keys not given keep the value
/// of `base`, except the principal point, which is the image centre unless given. The image
/// is bounded per side and in pixels (icgp/base/resource_limits.h), so that no frame the
/// simulator allocates can exhaust memory.
Intrinsics intrinsics(const Value& v, const Intrinsics& base) {
  const Map s(v, {"width", "height", "focal", "fu", "fv", "pu", "pv"});
  Intrinsics k = base;
  if (auto x = s.get("width")) k.width = static_cast<int>(x->integer_in(1, kMaxImageSide));
  if (auto x = s.get("height")) k.height = static_cast<int>(x->integer_in(1, kMaxImageSide));
  const long long pixels = static_cast<long long>(k.width) * k.height;
  if (pixels > kMaxImagePixels)
    v.at.fail(std::to_string(k.width) + " x " + std::to_string(k.height) + " = " + std::to_string(pixels) +
              " pixels, more than the " + std::to_string(kMaxImagePixels) + " (" + std::to_string(kMaxImageSide) +
              " x " + std::to_string(kMaxImagePixels / kMaxImageSide) + ") an image may have");
  if (auto x = s.get("focal")) {
    if (s.get("fu") || s.get("fv")) x->at.fail("give either focal or fu and fv, not both");
    k.fu = k.fv = x->number_in(kFocalPx);
  }
  if (auto x = s.get("fu")) k.fu = x->number_in(kFocalPx);
  if (auto x = s.get("fv")) k.fv = x->number_in(kFocalPx);
  const Intrinsics centred = Intrinsics::centred(k.width, k.height, 1.0);
  k.pu = s.get("pu") ? s.get("pu")->number_in(kPrincipalPointPx) : centred.pu;
  k.pv = s.get("pv") ? s.get("pv")->number_in(kPrincipalPointPx) : centred.pv;
  return k;
}

/// A file named relative to the scenario's folder (or absolute) that must exist.
std::string existing_file(const Value& v, const fs::path& scenario_dir) {
  const std::string reference = v.as(kNonEmptyString);
  const fs::path file = (scenario_dir / reference).lexically_normal();
  std::error_code error;
  if (!fs::is_regular_file(file, error)) v.expected("an existing file (tried " + file.string() + ")");
  return file.string();
}

// ---- Sections ---------------------------------------------------------------------------

std::string robot_name(RobotKind robot) { return name_of(robot, robot_names()); }

void read_arm(const Value& v, ArmSpec& arm) {
  const Map s(v, {"initial_joints_deg", "eMo"});
  if (auto x = s.get("initial_joints_deg")) arm.initial_joints = numbers<6>(*x, kAngleDeg) * kDegree;
  if (auto x = s.get("eMo")) arm.eMo = pose(*x);
}

/// The grasp keys of a scenario: gripper {model, eMg}, start_gMo and desired_gMo, all
/// required for a viper850_grasp robot and refused for the others (which would ignore them).
/// `document` locates the keys the file leaves out.
std::optional<GraspSpec> read_grasp(const Map& s, const Value& document, RobotKind robot, const std::string& scenario_dir,
                                    const std::string& models_dir) {
  const std::vector<std::string> keys = {"gripper", "start_gMo", "desired_gMo"};
  if (robot != RobotKind::kViper850Grasp) {
    for (const std::string& key : keys)
      if (auto x = s.get(key))
        x->at.fail("only a viper850_grasp scenario has a gripper (robot is " + robot_name(robot) + ")");
    return std::nullopt;
  }
  if (auto x = s.get("desired"))
    x->at.fail("a viper850_grasp scenario servoes the gripper to the object: give desired_gMo, not desired");
  for (const std::string& key : keys)
    if (!s.get(key)) document.at.child(key).fail("required when robot is viper850_grasp");
  GraspSpec grasp;
  const Map gripper(*s.get("gripper"), {"model", "eMg"});
  grasp.gripper_model = model_file(gripper.required("model"), scenario_dir, models_dir);
  if (auto x = gripper.get("eMg")) grasp.eMg = pose(*x);
  grasp.start_gMo = pose(*s.get("start_gMo"));
  grasp.desired_gMo = pose(*s.get("desired_gMo"));
  return grasp;
}

void read_object(const Value& v, ObjectSpec& object, const std::string& scenario_dir, const std::string& models_dir) {
  const Map s(v, {"model", "regions", "motion", "removed", "true_model", "scale_error_percent", "vertex_noise_mm"});
  object.model = model_file(s.required("model"), scenario_dir, models_dir);
  if (auto x = s.get("true_model")) object.true_model = model_file(*x, scenario_dir, models_dir);
  if (auto x = s.get("scale_error_percent")) object.scale_error = x->number_in(kScaleErrorPercent) * 1e-2;
  if (auto x = s.get("vertex_noise_mm")) object.vertex_noise = x->number_in(kVertexNoiseMm) * 1e-3;
  if (auto x = s.get("regions"))
    for (const Value& region : x->elements("a list of region meshes"))
      object.regions.push_back(model_file(region, scenario_dir, models_dir));
  if (auto x = s.get("motion")) {
    const Map motion(*x, {"velocity", "start", "duration"});
    if (auto y = motion.get("velocity")) object.linear_velocity = numbers<3>(*y, kObjectVelocity);
    if (auto y = motion.get("start")) object.motion_start = y->number_in(kSimulatedTime);
    if (auto y = motion.get("duration")) object.motion_duration = y->number_in(kSimulatedTime);
  }
  if (auto x = s.get("removed")) {
    const Map removed(*x, {"at", "for", "back"});
    object.removed_at = removed.required("at").number_in(kSimulatedTime);
    object.removed_for = removed.required("for").number_in(kSimulatedTime);
    if (auto y = removed.get("back")) object.put_back = pose(*y);
  }
}

OccluderSpec read_occluder(const Value& v) {
  const Map s(v, {"size", "start_position", "velocity", "start"});
  OccluderSpec occluder;
  if (auto x = s.get("size")) occluder.size = numbers<3>(*x, kOccluderSize);
  if (auto x = s.get("start_position")) occluder.start_position_in_camera = numbers<3>(*x, kCoordinate);
  if (auto x = s.get("velocity")) occluder.velocity_in_camera = numbers<3>(*x, kOccluderVelocity);
  if (auto x = s.get("start")) occluder.start = x->number_in(kSimulatedTime);
  return occluder;
}

void read_background(const Value& v, BackgroundSpec& background, const fs::path& scenario_dir) {
  const Map s(v, {"enabled", "texture", "distance"});
  if (auto x = s.get("enabled")) background.enabled = x->as(kBool);
  if (auto x = s.get("texture"))
    if (!x->node.IsNull()) background.texture = existing_file(*x, scenario_dir);
  if (auto x = s.get("distance")) background.distance = x->number_in(kBackgroundDistance);
}

void read_lighting(const Value& v, LightingSpec& lighting) {
  const Map s(v, {"direction", "ambient", "diffuse", "lamps", "motion", "flicker"});
  if (auto x = s.get("direction")) {
    lighting.direction_in_camera = numbers<3>(*x, kLightDirection);
    if (!(lighting.direction_in_camera.norm() > 0.0)) x->expected("a non-zero direction");
  }
  if (auto x = s.get("ambient")) lighting.ambient = x->number_in(kFraction);
  if (auto x = s.get("diffuse")) lighting.diffuse = x->number_in(kFraction);
  if (auto x = s.get("lamps")) {
    const std::vector<Value> lamps = x->elements("a list of lamps, each {direction, strength}");
    if (lamps.size() > static_cast<std::size_t>(kMaxSceneLamps))
      x->expected("at most " + std::to_string(kMaxSceneLamps) + " lamps (the camera's makes the renderers' four)");
    for (const Value& lamp : lamps) {
      const Map l(lamp, {"direction", "strength"});
      SceneLampSpec spec;
      const Value direction = l.required("direction");
      spec.direction_in_start_camera = numbers<3>(direction, kLightDirection);
      if (!(spec.direction_in_start_camera.norm() > 0.0)) direction.expected("a non-zero direction");
      spec.strength = l.required("strength").number_in(kFraction);
      lighting.scene_lamps.push_back(spec);
    }
  }
  double strongest = std::max(lighting.ambient, lighting.diffuse);
  for (const SceneLampSpec& lamp : lighting.scene_lamps) strongest = std::max(strongest, lamp.strength);
  if (strongest == 0.0)
    v.expected("a light: ambient, diffuse and every lamp's strength are 0, and the camera would see black");
  if (auto x = s.get("motion")) {
    const Map motion(*x, {"axis", "deg_per_s"});
    if (auto y = motion.get("axis")) {
      lighting.motion_axis = numbers<3>(*y, kLightDirection);
      if (!(lighting.motion_axis.norm() > 0.0)) y->expected("a non-zero axis");
    }
    lighting.motion_rate = motion.required("deg_per_s").number_in(kLightTurnRateDeg) * kDegree;
  }
  if (auto x = s.get("flicker")) {
    const Map flicker(*x, {"amplitude", "hz"});
    lighting.flicker_amplitude = flicker.required("amplitude").number_in(kFraction);
    lighting.flicker_hz = flicker.required("hz").number_in(kFlickerHz);
  }
}

void read_noise(const Value& v, NoiseSpec& noise) {
  const Map s(v, {"color_sigma", "depth_sigma_at_1m", "depth_dropout", "grazing_angle_deg", "edge_dropout_px",
                  "motion_blur", "frame_drop"});
  if (auto x = s.get("color_sigma")) noise.color_sigma = x->number_in(kColorSigma);
  if (auto x = s.get("depth_sigma_at_1m")) noise.depth_sigma_at_1m = x->number_in(kDepthSigmaAt1m);
  if (auto x = s.get("depth_dropout")) noise.depth_dropout = x->number_in(kProbability);
  if (auto x = s.get("grazing_angle_deg")) noise.grazing_angle_deg = x->number_in(kGrazingAngleDeg);
  if (auto x = s.get("edge_dropout_px")) noise.depth_edge_holes_px = static_cast<int>(x->integer_in(0, kMaxEdgeDropoutPx));
  if (auto x = s.get("motion_blur")) noise.motion_blur = x->number_in(kFraction);
  if (auto x = s.get("frame_drop")) noise.frame_drop = x->number_in(kProbability);
}

void read_jitter(const Value& v, JitterSpec& jitter) {
  const Map s(v, {"distribution", "ms"});
  jitter.distribution = s.required("distribution")
                            .choice<JitterSpec::Distribution>({{"none", JitterSpec::Distribution::kNone},
                                                               {"uniform", JitterSpec::Distribution::kUniform},
                                                               {"normal", JitterSpec::Distribution::kNormal}});
  if (auto x = s.get("ms")) jitter.spread = x->number_in(kSpreadMs) * 1e-3;
}

void read_cycles(const Value& v, CyclesSpec& cycles) {
  const Map s(v, {"samples", "light_bounces", "threads", "timeout_s"});
  if (auto x = s.get("samples")) cycles.samples = static_cast<int>(x->integer_in(1, kMaxCyclesSamples));
  if (auto x = s.get("light_bounces")) cycles.light_bounces = static_cast<int>(x->integer_in(0, kMaxLightBounces));
  if (auto x = s.get("threads")) cycles.threads = static_cast<int>(x->integer_in(0, kMaxRenderThreads));
  if (auto x = s.get("timeout_s")) cycles.timeout_s = x->number_in(kRenderTimeoutS);
}

void read_camera(const Value& v, CameraSpec& camera) {
  const Map s(v, {"renderer", "cycles", "color", "depth", "depth_T_color", "rate_hz", "noise", "vignetting",
                  "auto_exposure", "latency_ms", "jitter"});
  if (auto x = s.get("renderer"))
    camera.renderer = x->choice<RendererKind>(renderer_names());
  if (auto x = s.get("cycles")) read_cycles(*x, camera.cycles);
  if (auto x = s.get("color")) camera.color = intrinsics(*x, camera.color);
  camera.depth = camera.color;
  if (auto x = s.get("depth")) camera.depth = intrinsics(*x, camera.color);
  if (auto x = s.get("depth_T_color")) camera.depth_T_color = pose(*x);
  if (auto x = s.get("rate_hz")) camera.rate_hz = x->number_in(kRateHz);
  if (auto x = s.get("noise")) read_noise(*x, camera.noise);
  if (auto x = s.get("vignetting")) camera.vignetting = x->number_in(kFraction);
  if (auto x = s.get("auto_exposure")) {
    const Map exposure(*x, {"target", "time_constant_s"});
    camera.auto_exposure.target = exposure.required("target").number_in(kFraction);
    if (auto y = exposure.get("time_constant_s")) camera.auto_exposure.time_constant = y->number_in(kTimeConstantS);
  }
  if (auto x = s.get("latency_ms")) camera.latency = x->number_in(kDelayMs) * 1e-3;
  if (auto x = s.get("jitter")) read_jitter(*x, camera.jitter);
}

void read_calibration_error(const Value& v, CalibrationErrorSpec& error, RobotKind robot) {
  const Map s(v, {"focal_percent", "principal_point_px", "k1", "depth_T_color", "hand_eye", "joint_offsets_deg"});
  if (auto x = s.get("focal_percent")) error.focal = x->number_in(kFocalErrorPercent) * 1e-2;
  if (auto x = s.get("principal_point_px")) error.principal_point = x->number_in(kPrincipalPointErrorPx);
  if (auto x = s.get("k1")) error.k1 = x->number_in(kRadialDistortion);
  const auto read_pose_error = [](const Value& v, double& translation, double& rotation) {
    const Map p(v, {"translation_mm", "rotation_deg"});
    if (auto x = p.get("translation_mm")) translation = x->number_in(kThresholdMm) * 1e-3;
    if (auto x = p.get("rotation_deg")) rotation = x->number_in(kThresholdDeg) * kDegree;
  };
  if (auto x = s.get("depth_T_color"))
    read_pose_error(*x, error.depth_T_color_translation, error.depth_T_color_rotation);
  if (auto x = s.get("hand_eye")) {
    if (robot == RobotKind::kFreeFlyingCamera)
      x->at.fail("a free-flying camera has no hand-eye calibration (robot is " + robot_name(robot) + ")");
    read_pose_error(*x, error.hand_eye_translation, error.hand_eye_rotation);
  }
  if (auto x = s.get("joint_offsets_deg")) {
    if (robot == RobotKind::kFreeFlyingCamera)
      x->at.fail("a free-flying camera has no joints (robot is " + robot_name(robot) + ")");
    error.joint_offset = x->number_in(kThresholdDeg) * kDegree;
  }
}

void read_robot_response(const Value& v, ResponseSpec& response) {
  const Map s(v, {"lag_ms", "max_linear_acceleration", "max_angular_acceleration_deg", "max_joint_acceleration_deg"});
  if (auto x = s.get("lag_ms")) response.lag = x->number_in(kSpreadMs) * 1e-3;
  if (auto x = s.get("max_linear_acceleration")) response.max_linear_acceleration = x->number_in(kLinearAcceleration);
  if (auto x = s.get("max_angular_acceleration_deg"))
    response.max_angular_acceleration = x->number_in(kAngularAccelerationDeg) * kDegree;
  if (auto x = s.get("max_joint_acceleration_deg"))
    response.max_joint_acceleration = x->number_in(kAngularAccelerationDeg) * kDegree;
}

void read_tracker(const Value& v, TrackerSpec& tracker, const fs::path& scenario_dir) {
  const Map s(v, {"type", "modalities", "config", "visp_configuration", "init", "timing", "compute_ms"});
  if (auto x = s.get("type"))
    tracker.kind = x->choice<TrackerKind>(tracker_names());
  if (auto x = s.get("modalities"))
    tracker.modalities = parse_cue_list(x->as(Rule<std::vector<std::string>>{cue_list_expected(), valid_cue_list}));
  if (auto x = s.get("config"))
    if (!x->node.IsNull()) tracker.config = existing_file(*x, scenario_dir);
  if (auto x = s.get("visp_configuration")) {
    const std::vector<std::string> names = {"edge + dense depth", "KLT + dense depth", "edge + KLT + dense depth",
                                            "edge + KLT (no depth)"};
    std::vector<std::pair<std::string, std::string>> options;
    for (const std::string& name : names) options.emplace_back(name, name);
    tracker.visp_configuration = x->choice(options);
  }
  if (auto x = s.get("init"))
    tracker.init_by_detection = x->choice<bool>({{"detect", true}, {"truth", false}});
  if (auto x = s.get("timing")) tracker.real_timing = x->choice<bool>({{"ideal", false}, {"real", true}});
  if (auto x = s.get("compute_ms")) {
    if (!tracker.real_timing) x->at.fail("a compute time counts only with timing: real");
    tracker.compute_time = x->number_in(kSpreadMs) * 1e-3;
  }
}

void read_gain(const Value& v, GainSpec& gain) {
  if (v.node.IsScalar()) {
    gain.at_zero = gain.at_infinity = v.number_in(kGain);
    return;
  }
  if (!v.node.IsMap()) v.expected("a number in " + kGain.text() + " or a map with the keys at_zero, at_infinity, slope_at_zero");
  const Map s(v, {"at_zero", "at_infinity", "slope_at_zero"});
  if (auto x = s.get("at_zero")) gain.at_zero = x->number_in(kGain);
  if (auto x = s.get("at_infinity")) gain.at_infinity = x->number_in(kGain);
  if (auto x = s.get("slope_at_zero")) gain.slope_at_zero = x->number_in(kGainSlope);
}

void read_control(const Value& v, ControlSpec& control, RobotKind robot) {
  const Map s(v, {"law", "gain", "max_linear_velocity", "max_angular_velocity_deg", "max_joint_velocity_deg", "teach"});
  if (auto x = s.get("law")) {
    control.law = x->choice<ControlLawKind>(control_law_names());
    // IBVS features are image points of a camera that moves; a grasp's camera stands still.
    if (robot == RobotKind::kViper850Grasp && control.law == ControlLawKind::kIbvs)
      x->expected("pbvs (a viper850_grasp scenario servoes the gripper's pose gMo)");
  }
  if (auto x = s.get("gain")) read_gain(*x, control.gain);
  if (auto x = s.get("max_linear_velocity")) control.max_linear_velocity = x->number_in(kLinearVelocity);
  if (auto x = s.get("max_angular_velocity_deg")) control.max_angular_velocity = x->number_in(kAngularVelocityDeg) * kDegree;
  if (auto x = s.get("max_joint_velocity_deg")) control.max_joint_velocity = x->number_in(kAngularVelocityDeg) * kDegree;
  if (auto x = s.get("teach")) {
    control.taught_by_showing = x->choice<bool>({{"pose", false}, {"showing", true}});
    // The gripper would have to be shown at the goal; a grasp's goal is given in its frame.
    if (control.taught_by_showing && robot == RobotKind::kViper850Grasp)
      x->expected("pose (a viper850_grasp scenario gives its goal as desired_gMo)");
  }
}

void read_stop(const Value& v, StopSpec& stop) {
  const Map s(v, {"translation_mm", "rotation_deg", "settle_time", "max_time"});
  if (auto x = s.get("translation_mm")) stop.converged_translation = x->number_in(kThresholdMm) * 1e-3;
  if (auto x = s.get("rotation_deg")) stop.converged_rotation = x->number_in(kThresholdDeg) * kDegree;
  if (auto x = s.get("settle_time")) stop.settle_time = x->number_in(kSimulatedTime);
  if (auto x = s.get("max_time")) stop.max_time = x->number_in(kMaxTime);
}

void read_trials(const Value& v, TrialSpec& trials) {
  const Map s(v, {"translation_mm", "rotation_deg"});
  if (auto x = s.get("translation_mm")) trials.translation = x->number_in(kThresholdMm) * 1e-3;
  if (auto x = s.get("rotation_deg")) trials.rotation = x->number_in(kThresholdDeg) * kDegree;
}

}  // namespace

double simulated_steps(double max_time, double rate_hz) {
  const double dt = 1.0 / rate_hz;
  return std::ceil(max_time / dt) + 1.0;
}

void check_run_length(const Scenario& scenario) {
  const double steps = simulated_steps(scenario.stop.max_time, scenario.camera.rate_hz);
  if (steps >= 1.0 && steps <= kMaxSimulatedSteps) return;
  // A scenario built in code has no file to name.
  const std::string where = scenario.file.empty() ? "scenario '" + scenario.name + "'" : scenario.file;
  throw ScenarioError(where + ": stop.max_time: " + yaml::plain_number(scenario.stop.max_time) +
                      " s at camera.rate_hz " + yaml::plain_number(scenario.camera.rate_hz) + " Hz is " +
                      yaml::plain_number(steps) + " simulated steps, outside the [1, " +
                      yaml::plain_number(kMaxSimulatedSteps) + "] a run may take (lower max_time or rate_hz)");
}

std::string resolve_model_path(const std::string& reference, const std::string& scenario_dir,
                               const std::string& models_dir) {
  if (reference.empty()) throw ScenarioError("empty model reference");
  const std::vector<std::string> candidates = model_candidates(reference, scenario_dir, models_dir);
  if (std::optional<std::string> file = find_model(candidates)) return *file;
  throw ScenarioError("'" + reference + "': no such model (" + tried(candidates) + ")");
}

const std::vector<std::pair<std::string, RobotKind>>& robot_names() {
  static const std::vector<std::pair<std::string, RobotKind>> names = {
      {"free_flying", RobotKind::kFreeFlyingCamera},
      {"viper850_eye_in_hand", RobotKind::kViper850EyeInHand},
      {"viper850_eye_to_hand", RobotKind::kViper850EyeToHand},
      {"viper850_grasp", RobotKind::kViper850Grasp}};
  return names;
}

const std::vector<std::pair<std::string, ControlLawKind>>& control_law_names() {
  static const std::vector<std::pair<std::string, ControlLawKind>> names = {{"pbvs", ControlLawKind::kPbvs},
                                                                            {"ibvs", ControlLawKind::kIbvs}};
  return names;
}

const std::vector<std::pair<std::string, TrackerKind>>& tracker_names() {
  static const std::vector<std::pair<std::string, TrackerKind>> names = {
      {"icgp", TrackerKind::kIcgp},
      {"visp", TrackerKind::kVisp},
      {"oracle", TrackerKind::kOracle},
      {"image_oracle", TrackerKind::kImageOracle}};
  return names;
}

const std::vector<std::pair<std::string, RendererKind>>& renderer_names() {
  static const std::vector<std::pair<std::string, RendererKind>> names = {{"opengl", RendererKind::kOpenGl},
                                                                          {"cycles", RendererKind::kCycles}};
  return names;
}

namespace {

/// The keys of a dotted key path ("camera.jitter.ms").
std::vector<std::string> keys_of(const std::string& field) {
  std::vector<std::string> keys;
  std::string::size_type begin = 0;
  for (std::string::size_type dot; (dot = field.find('.', begin)) != std::string::npos; begin = dot + 1)
    keys.push_back(field.substr(begin, dot - begin));
  keys.push_back(field.substr(begin));
  return keys;
}

/// The node at the dotted key path `field` of `document`, and where it is, creating the
/// sections on the way; refuses a path through a value that is not a section.
std::pair<YAML::Node, Location> field_node(const Value& document, const std::string& field) {
  YAML::Node node = document.node;
  Location at = document.at;
  const std::vector<std::string> keys = keys_of(field);
  for (std::size_t i = 0;; ++i) {
    if (keys[i].empty()) at.fail("'" + field + "' is not a field (an empty key)");
    if (!node.IsMap() && !node.IsNull()) at.fail("is not a section, so '" + field + "' is not a field");
    at = at.child(keys[i]);
    YAML::Node child = node[keys[i]];
    if (i + 1 == keys.size()) return {child, at};
    if (!child.IsDefined() || child.IsNull()) child = YAML::Node(YAML::NodeType::Map);
    node.reset(child);
  }
}

/// What the file holds at `field`: set (a value), absent (nothing there yet), or blocked (a
/// section on the way holds something else, which the reader will refuse in its own words).
enum class FieldState { kSet, kAbsent, kBlocked };
FieldState field_state(const YAML::Node& document, const std::string& field) {
  YAML::Node node = document;
  for (const std::string& key : keys_of(field)) {
    if (node.IsNull()) return FieldState::kAbsent;
    if (!node.IsMap()) return FieldState::kBlocked;
    const YAML::Node child = node[key];
    if (!child.IsDefined()) return FieldState::kAbsent;
    node.reset(child);
  }
  return node.IsNull() ? FieldState::kAbsent : FieldState::kSet;
}

/// Writes `override.value` at its dotted key path in `document`; refuses a field that holds
/// something other than a number.
void write_field(const Value& document, const FieldValue& override) {
  auto [node, at] = field_node(document, override.field);
  if (node.IsDefined() && !node.IsNull() && !(node.IsScalar() && convert<double>(node)))
    at.fail("holds " + yaml::describe(node) + ", not a number: only a numeric field can be set to " +
            yaml::plain_number(override.value));
  node = override.value;
}

/// The profile the file names (`profile`), realistic unless it says ideal.
Profile profile_of(const Value& document) {
  if (!document.node.IsMap() || !document.node["profile"].IsDefined()) return Profile::kRealistic;
  return Value{document.node["profile"], document.at.child("profile")}.choice<Profile>(profile_names());
}

/// Writes every value under `section` into `document` at the same key path below `prefix`.
void merge_fields(const Value& document, const Value& section, const std::string& prefix) {
  if (!section.node.IsMap()) {
    field_node(document, prefix).first = YAML::Clone(section.node);
    return;
  }
  for_each_entry(section, [&](const std::string& key, const Value& value) {
    merge_fields(document, value, prefix.empty() ? key : prefix + "." + key);
  });
}

/// The file's own values for one profile (`profiles: {ideal: {stop: …}}`: what the cell
/// decides, such as how closely a run can be judged) over its other fields, for the profile
/// in use; the sections of the other profiles are only checked to name a profile.
void merge_profile_section(const Value& document, Profile profile) {
  if (!document.node.IsMap() || !document.node["profiles"].IsDefined()) return;
  const Value profiles{document.node["profiles"], document.at.child("profiles")};
  std::vector<std::string> names;
  for (const auto& [name, option] : profile_names()) names.push_back(name);
  const Map sections(profiles, names);
  for (const auto& [name, option] : profile_names()) {
    const std::optional<Value> section = sections.get(name);
    if (!section) continue;
    if (!section->node.IsMap() && !section->node.IsNull()) section->expected("a section of scenario fields");
    if (option == profile) merge_fields(document, *section, "");
  }
}

/// The profile's fields where the file (with its section for the profile and the command
/// line's values) gives none: the document then reads as if the file gave them.
void fill_profile_fields(const Value& document, Profile profile) {
  if (!document.node.IsMap()) return;  // the reader's error names what the file holds
  RobotKind robot = RobotKind::kFreeFlyingCamera;
  if (document.node["robot"].IsDefined())
    robot = Value{document.node["robot"], document.at.child("robot")}.choice<RobotKind>(robot_names());
  // Chosen against the file alone, before any is written: `unless_set` means the file's.
  std::vector<ProfileField> missing;
  for (const ProfileField& given : profile_fields(profile, robot)) {
    // Not into a missing object: the reader's error says the file lacks the whole section.
    if (given.field.rfind("object.", 0) == 0 && field_state(document.node, "object") != FieldState::kSet) continue;
    if (field_state(document.node, given.field) != FieldState::kAbsent) continue;
    if (!given.unless_set.empty() && field_state(document.node, given.unless_set) == FieldState::kSet) continue;
    missing.push_back(given);
  }
  for (const ProfileField& given : missing) field_node(document, given.field).first = YAML::Load(given.value);
}

}  // namespace

Scenario load_scenario(const std::string& path, const std::string& models_dir) {
  return load_scenario(path, models_dir, {});
}

Scenario load_scenario(const std::string& path, const std::string& models_dir,
                       const std::vector<FieldValue>& overrides) try {
  const Value document = yaml::load_file(path, {"scenario file"});
  const Profile profile = profile_of(document);
  merge_profile_section(document, profile);
  for (const FieldValue& override : overrides) write_field(document, override);
  fill_profile_fields(document, profile);
  const Map s(document, {"name", "description", "profile", "profiles", "robot", "arm", "gripper", "object", "occluder",
                         "background", "lighting", "camera", "start", "desired", "start_gMo", "desired_gMo", "tracker",
                         "control", "stop", "trials", "seed", "robot_response", "calibration_error"});
  const fs::path folder = fs::path(path).parent_path();
  Scenario scenario;
  scenario.file = path;
  scenario.overrides = overrides;
  scenario.profile = profile;
  scenario.name = fs::path(path).stem().string();
  if (auto x = s.get("name")) scenario.name = x->as(kNonEmptyString);
  if (auto x = s.get("description")) scenario.description = x->as(kString);
  if (auto x = s.get("robot")) scenario.robot = x->choice<RobotKind>(robot_names());
  if (auto x = s.get("arm")) read_arm(*x, scenario.arm);
  if (auto x = s.get("robot_response")) read_robot_response(*x, scenario.robot_response);
  scenario.grasp = read_grasp(s, document, scenario.robot, folder.string(), models_dir);
  read_object(s.required("object"), scenario.object, folder.string(), models_dir);
  if (auto x = s.get("occluder")) scenario.occluder = read_occluder(*x);
  if (auto x = s.get("background")) read_background(*x, scenario.background, folder);
  if (auto x = s.get("lighting")) read_lighting(*x, scenario.lighting);
  if (auto x = s.get("camera")) read_camera(*x, scenario.camera);
  if (auto x = s.get("calibration_error")) read_calibration_error(*x, scenario.calibration_error, scenario.robot);
  scenario.initial_cMo = object_pose(s.required("start"));
  if (!scenario.grasp) scenario.desired_cMo = object_pose(s.required("desired"));
  if (auto x = s.get("tracker")) read_tracker(*x, scenario.tracker, folder);
  if (auto x = s.get("control")) read_control(*x, scenario.control, scenario.robot);
  if (auto x = s.get("stop")) read_stop(*x, scenario.stop);
  if (auto x = s.get("trials")) read_trials(*x, scenario.trials);
  check_run_length(scenario);
  // A command that arrives after the run has ended would be simulated as never sent.
  if (scenario.camera.latency >= scenario.stop.max_time)
    s.required("camera").at.child("latency_ms").fail(
        "expected less than stop.max_time (" + yaml::plain_number(1e3 * scenario.stop.max_time) + " ms), got " +
        yaml::plain_number(1e3 * scenario.camera.latency));
  if (auto x = s.get("seed")) scenario.seed = x->as(Rule<unsigned>{"a non-negative integer", any<unsigned>});
  return scenario;
} catch (const yaml::Error& e) {
  throw ScenarioError(e.what());
}

}  // namespace icgp::servo
