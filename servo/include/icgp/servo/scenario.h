// SPDX-License-Identifier: GPL-2.0-or-later
// A servo scenario: the scene, the sensor, the robot, the tracker and the control law of one
// closed-loop run, as read from a YAML file in scenarios/.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"
#include "icgp/modality/cue_kind.h"
#include "icgp/render/sensor_effects.h"

namespace icgp::servo {

constexpr double kDegree = kPi / 180.0;

/// A scenario file that cannot be used. The message names the file and the field
/// ("scenarios/x.yaml: control.gain: expected a number in (0, 1000], got 'fast'").
class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What moves the camera (or the object) in answer to the control law.
enum class RobotKind {
  kFreeFlyingCamera,    ///< ViSP's vpSimulatorCamera: the camera follows the commanded twist
  kViper850EyeInHand,   ///< camera on the flange of a Viper 850 arm, joint velocities
  kViper850EyeToHand,   ///< fixed camera watching the object held by a Viper 850 arm
  /// Fixed camera watching a Viper 850 whose flange carries a gripper, and the object
  /// standing still: the arm brings the gripper to a pre-grasp pose (GraspSpec).
  kViper850Grasp,
};

enum class ControlLawKind {
  kPbvs,  ///< position-based: s = (t(cdMc), θu(cdRc)), s* = 0
  kIbvs,  ///< image-based: projected bounding-box corners (x, y) against their desired positions
};

/// The cell a scenario runs in unless its file says otherwise (top-level key `profile`;
/// scenario_profile.h gives the fields of each).
enum class Profile {
  kRealistic,  ///< a real cell's latency, robot response, calibration and object errors (the default)
  kIdeal,      ///< the exact world: no latency, an exact robot, calibration and object
};

enum class TrackerKind {
  kIcgp,    ///< vpMbIcgTracker
  kVisp,    ///< vpMbGenericTracker
  kOracle,  ///< the ground-truth pose
  /// A perfect feature tracker: the bounding-box corners measured exactly where the true
  /// camera images them, read through the nominal calibration, the pose from them by vpPose.
  /// What the calibration does to a pose computed from an image, without a tracker's errors.
  kImageOracle,
};

/// The names scenario files give them (robot:, control.law:, tracker.type:), which
/// `icgp servo --tracker` and the Python package use too, in declaration order.
const std::vector<std::pair<std::string, RobotKind>>& robot_names();
const std::vector<std::pair<std::string, ControlLawKind>>& control_law_names();
const std::vector<std::pair<std::string, TrackerKind>>& tracker_names();
/// The name of `kind` in its list above.
template <typename Kind>
std::string name_of(Kind kind, const std::vector<std::pair<std::string, Kind>>& names) {
  for (const auto& [name, k] : names)
    if (k == kind) return name;
  return "?";
}
/// The kind named `name` in its list above, if any.
template <typename Kind>
std::optional<Kind> kind_named(const std::string& name, const std::vector<std::pair<std::string, Kind>>& names) {
  for (const auto& [known, kind] : names)
    if (known == name) return kind;
  return std::nullopt;
}
/// The names of a list above, in its order.
template <typename Kind>
std::vector<std::string> names_in(const std::vector<std::pair<std::string, Kind>>& names) {
  std::vector<std::string> list;
  for (const auto& [name, kind] : names) list.push_back(name);
  return list;
}

/// The tracked object. Its world placement follows from the robot's start and the initial
/// camera-object pose (Scenario::initial_cMo), so scenarios state what the camera sees.
struct ObjectSpec {
  /// The mesh file. In YAML: a folder of models/ ("textured_box":
  /// models/textured_box/textured_box.obj or object.obj) or a path relative to the scenario
  /// file; load_scenario stores the resolved path.
  std::string model;
  /// Meshes of the object's colour regions (multi-region tracking), resolved the same way.
  std::vector<std::string> regions;
  /// The object is not its model: what the scene shows, while the tracker loads `model`.
  /// Another mesh of the same object (YAML true_model, resolved as `model`; empty: `model`),
  /// scaled about its origin by (1 + scale_error) (YAML scale_error_percent, signed), its
  /// vertices moved by normal noise of this standard deviation (metres; YAML
  /// vertex_noise_mm), the same at coincident vertices so that the surface stays closed.
  std::string true_model;
  double scale_error = 0.0;
  double vertex_noise = 0.0;
  /// Moving target: constant linear velocity (m/s, world frame) during [start, start +
  /// duration] seconds of simulated time. Zero: static.
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();
  double motion_start = 0.0;
  double motion_duration = 0.0;
  /// Taken out of the scene at `removed_at` seconds for `removed_for` seconds, then put
  /// back moved by `put_back` (object_T_new, about the object's own origin; YAML
  /// `removed: {at, for, back: {t, r_deg}}`). Zero `removed_for`: never.
  double removed_at = 0.0;
  double removed_for = 0.0;
  Pose put_back;
  /// When the object stops changing: the end of its motion and of its removal.
  double settled_time() const { return std::max(motion_start + motion_duration, removed_at + removed_for); }
};

/// A box that crosses the scene at constant velocity (a passing occluder).
struct OccluderSpec {
  Eigen::Vector3d size{0.03, 0.3, 0.03};  ///< metres, box edges along its x, y, z
  /// Where it is at time `start`, in the initial camera frame (x right, y down, z forward).
  Eigen::Vector3d start_position_in_camera{-0.2, 0.0, 0.3};
  Eigen::Vector3d velocity_in_camera{0.1, 0.0, 0.0};  ///< m/s, in the initial camera frame
  double start = 0.0;                                   ///< seconds
};

/// What stands behind the object.
struct BackgroundSpec {
  bool enabled = true;
  std::string texture;    ///< image file (resolved; YAML: relative to the scenario); empty = procedural clutter
  double distance = 0.3;  ///< metres behind the object's origin, along the initial optical axis
};

/// Lamps a scene may have besides the camera's: the renderers take four in all.
inline constexpr int kMaxSceneLamps = 3;

/// A lamp fixed in the scene (YAML lighting.lamps: [{direction, strength}]).
struct SceneLampSpec {
  /// The direction its light travels, in the frame of the camera at its start (x right,
  /// y down, z forward), as the scenario's other placements are.
  Eigen::Vector3d direction_in_start_camera{0.0, 1.0, 0.0};
  double strength = 0.5;  ///< what a white Lambertian surface facing it reads
};

/// How the scene is lit: a lamp fixed to the colour camera (a ring light), lamps fixed in
/// the scene, and a uniform ambient environment, which may change over time as a real
/// cell's light does. Zero everywhere is refused: the camera would see black.
struct LightingSpec {
  Eigen::Vector3d direction_in_camera{0.0, 0.0, 1.0};  ///< direction the light travels, at time 0
  double ambient = 0.35;
  double diffuse = 0.65;  ///< the camera's lamp's strength
  std::vector<SceneLampSpec> scene_lamps;  ///< at most kMaxSceneLamps
  /// A moving light (YAML motion: {axis, deg_per_s}): the camera lamp's direction turns about this
  /// camera-frame axis at this rate (rad/s). 0: it stays.
  Eigen::Vector3d motion_axis{0.0, 1.0, 0.0};
  double motion_rate = 0.0;
  /// Flicker (YAML flicker: {amplitude, hz}): every lamp's strength times
  /// 1 + amplitude sin(2π hz t), as mains-powered lamps flicker at twice the mains
  /// frequency. 0: steady.
  double flicker_amplitude = 0.0;
  double flicker_hz = 0.0;
};

/// The simulated sensor's imperfections: those sequences are rendered with (SensorNoise,
/// file key edge_dropout_px for its depth_edge_holes_px), plus motion blur and lost frames.
/// Zero (and 90 deg) = exact renders.
struct NoiseSpec : SensorNoise {
  /// Exposure as a fraction of the frame period: the colour image averages renders over the
  /// last `motion_blur` of the camera's motion between frames. 0 = sharp.
  double motion_blur = 0.0;
  double frame_drop = 0.0;  ///< probability that a frame is lost (the tracker gets nothing new)
};

/// How a frame's latency varies from frame to frame (YAML camera.jitter: {distribution, ms}).
struct JitterSpec {
  enum class Distribution { kNone, kUniform, kNormal };
  Distribution distribution = Distribution::kNone;
  /// Seconds (YAML ms): the half-width of a uniform distribution, the standard deviation of
  /// a normal one.
  double spread = 0.0;
};

/// What renders the camera's images (YAML camera.renderer).
enum class RendererKind {
  kOpenGl,  ///< "opengl": icgp's rasteriser, fast: a run at tens of steps per second
  kCycles,  ///< "cycles": Blender's Cycles path tracer, slow: about a second a frame (docs/servo.md)
};
/// The names of camera.renderer, which `icgp servo --renderer` takes too, in declaration order.
const std::vector<std::pair<std::string, RendererKind>>& renderer_names();

/// The Cycles backend's settings (YAML camera.cycles).
struct CyclesSpec {
  /// Paths per pixel. Debian's Blender has no denoiser: what noise is left stays in the
  /// image, as a sensor's would.
  int samples = 16;
  int light_bounces = 4;  ///< the longest light path, in bounces
  int threads = 0;        ///< Cycles' threads; 0: one per core
  /// Seconds Blender may take for one request before the trial fails with its last messages.
  double timeout_s = 300.0;
};

/// The colour camera's auto-exposure (YAML camera.auto_exposure: {target, time_constant_s}):
/// it scales each image so that its mean linear light approaches `target`, correcting from
/// the images it has taken with this time constant, so that it lags behind a change of light
/// as a camera's control loop does. Target 0: a fixed exposure.
struct AutoExposureSpec {
  double target = 0.0;
  double time_constant = 0.2;  ///< seconds
};

/// The RGB-D sensor.
struct CameraSpec {
  RendererKind renderer = RendererKind::kOpenGl;
  CyclesSpec cycles;
  Intrinsics color = Intrinsics::centred(640, 480, 600.0);
  Intrinsics depth = Intrinsics::centred(640, 480, 600.0);
  Pose depth_T_color;  ///< colour camera -> depth camera (ViSP's depth_M_color)
  double rate_hz = 30.0;
  NoiseSpec noise;
  /// The colour lens's vignetting: brightness (in linear light) times 1 - v (1 - cos⁴θ) at
  /// the angle θ off the optical axis; 1: a simple lens's whole cos⁴ law, 0: none.
  double vignetting = 0.0;
  AutoExposureSpec auto_exposure;
  /// Seconds from a frame's exposure to the command computed from it reaching the robot
  /// (YAML latency_ms): readout, transport, the control computation, the robot's interface.
  /// The tracker's own time comes on top when TrackerSpec::real_timing says so.
  double latency = 0.0;
  JitterSpec jitter;  ///< added to `latency` frame by frame (a negative total counts as 0)
};

struct TrackerSpec {
  TrackerKind kind = TrackerKind::kIcgp;
  /// icgp: modalities ("region", "depth", "texture"); empty = the configuration's.
  std::vector<std::string> modalities;
  /// icgp: tracker configuration YAML (resolved; YAML: relative to the scenario); empty =
  /// reference defaults.
  std::string config;
  /// visp: one of icgp::visp_reference_configurations() ("edge + KLT + dense depth", ...).
  std::string visp_configuration = "edge + KLT + dense depth";
  /// icgp: how the tracker gets its first pose (YAML `init`): found in the images
  /// ("detect", the default: no true pose enters the loop after the scene is made), or the
  /// true pose ("truth", for comparison). ViSP's tracker and the oracle always start from
  /// the truth.
  bool init_by_detection = true;
  /// Whether the tracker's time counts (YAML timing: ideal | real). Ideal: a frame is
  /// tracked in no time. Real: its compute time delays the frame's command, and a frame
  /// that comes while the tracker is still busy is skipped, as a real-time pipeline must.
  bool real_timing = false;
  /// Real timing: the compute time of every frame, seconds (YAML compute_ms), so that a
  /// batch does not depend on the machine; unset: the time measured on each frame.
  std::optional<double> compute_time;
};

/// vpAdaptiveGain(at_zero, at_infinity, slope_at_zero); a constant gain when at_zero ==
/// at_infinity.
struct GainSpec {
  double at_zero = 0.5;
  double at_infinity = 0.5;
  double slope_at_zero = 30.0;
  bool adaptive() const { return at_zero != at_infinity; }
};

struct ControlSpec {
  ControlLawKind law = ControlLawKind::kPbvs;
  GainSpec gain;
  double max_linear_velocity = 0.1;   ///< m/s, free-flying camera saturation
  double max_angular_velocity = 0.5;  ///< rad/s (YAML: deg/s), free-flying camera saturation
  double max_joint_velocity = 1.0;    ///< rad/s, arms only (YAML: deg/s)
  /// Where the goal comes from (YAML teach: pose | showing). Pose: the scenario's desired
  /// pose, as given. Showing: the robot is first put at that pose and the goal is what the
  /// cell's own camera and tracker measure there (the desired image recorded with the same,
  /// maybe miscalibrated, camera), as a user teaches an IBVS task.
  bool taught_by_showing = false;
};

/// The robot's low-level controller (YAML robot_response): how the velocity the robot
/// follows answers the commanded one. The defaults follow it at once, as an ideal robot.
struct ResponseSpec {
  double lag = 0.0;  ///< first-order time constant, seconds (YAML lag_ms)
  /// Acceleration limits (YAML max_linear_acceleration in m/s², max_angular_acceleration_deg
  /// and max_joint_acceleration_deg in deg/s²), +inf when not given: of the free-flying
  /// camera's linear and angular velocity (norms, so that the motion keeps its direction),
  /// and of each joint of an arm.
  double max_linear_acceleration = kUnlimited;   ///< m/s²
  double max_angular_acceleration = kUnlimited;  ///< rad/s²
  double max_joint_acceleration = kUnlimited;    ///< rad/s²
  static constexpr double kUnlimited = std::numeric_limits<double>::infinity();
  /// Follows every command at once.
  bool immediate() const {
    return lag == 0.0 && max_linear_acceleration == kUnlimited && max_angular_acceleration == kUnlimited &&
           max_joint_acceleration == kUnlimited;
  }
};

/// How far the cell's calibration is from the truth (YAML calibration_error). The tracker and
/// the control law get the scenario's values, the nominal calibration; the simulator renders
/// and moves with values this far from them, drawn per run from its seed
/// (draw_calibration_errors): each size is given, its sign or direction is drawn. Zero: exact.
struct CalibrationErrorSpec {
  double focal = 0.0;            ///< relative error of fu and fv, both cameras (YAML focal_percent)
  double principal_point = 0.0;  ///< pixels, both cameras (YAML principal_point_px)
  /// The colour lens's radial distortion, x_d = x (1 + k1 r²) in normalised coordinates
  /// (signed, not drawn; negative: barrel), which the nominal calibration leaves out. The
  /// depth image stays undistorted, as an RGB-D sensor rectifies its depth.
  double k1 = 0.0;
  /// The depth camera's extrinsics (YAML depth_T_color: {translation_mm, rotation_deg}).
  double depth_T_color_translation = 0.0;  ///< metres
  double depth_T_color_rotation = 0.0;     ///< radians
  /// Hand-eye (YAML hand_eye: {translation_mm, rotation_deg}): the camera on the flange of an
  /// eye-in-hand arm, or the fixed camera's pose in the arm's base frame.
  double hand_eye_translation = 0.0;  ///< metres
  double hand_eye_rotation = 0.0;     ///< radians
  double joint_offset = 0.0;  ///< radians, each joint of an arm (YAML joint_offsets_deg)
};

/// When a run ends, and what counts as success.
struct StopSpec {
  /// Success: the true final pose is this close to the desired pose.
  double converged_translation = 0.001;  ///< metres (YAML: mm)
  double converged_rotation = 0.1 * kDegree;  ///< radians (YAML: deg)
  /// The run stops when the servo error as the tracker estimates it has stayed below half
  /// the thresholds this long: the other half is left to the tracker's own error.
  double settle_time = 0.2;  ///< seconds
  double max_time = 20.0;    ///< seconds of simulated time
};

/// Batch trials: the initial pose is the scenario's, moved by a random translation and
/// rotation of at most these sizes (uniform direction and size).
struct TrialSpec {
  double translation = 0.02;                               ///< metres (YAML: mm)
  double rotation = 10.0 * kDegree;  ///< radians (YAML: deg)
};

/// Viper 850 settings (arm scenarios).
struct ArmSpec {
  /// Joint angles at the start, radians (YAML: deg). Eye-in-hand: the object is placed so
  /// that the camera sees it at initial_cMo. Eye-to-hand: the fixed camera is placed so
  /// that it sees the held object at initial_cMo.
  /// The default, (0, -60, 170, 0, 70, 0) deg, keeps the elbow well away from the Viper's
  /// singularity at q3 ~ 102 deg, the camera looking down 0.7 m in front of the base.
  Eigen::Matrix<double, 6, 1> initial_joints =
      (Eigen::Matrix<double, 6, 1>() << 0, -60 * kDegree, 170 * kDegree, 0, 70 * kDegree, 0).finished();
  /// Eye-to-hand: the object in the end-effector frame (how it is held).
  Pose eMo = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.0, 0.1));
};

/// Grasp scenarios (RobotKind::kViper850Grasp): the gripper on the arm's flange, and the
/// object's pose in the gripper frame where the run starts and where the servo must bring it.
/// PBVS servoes gMo = cMg^-1 cMo onto desired_gMo; the camera stays where it sees the object
/// at Scenario::initial_cMo.
struct GraspSpec {
  /// The gripper's mesh, resolved like ObjectSpec::model (YAML: gripper.model).
  std::string gripper_model;
  Pose eMg;          ///< the gripper in the flange frame (YAML: gripper.eMg)
  /// Where the object stands in the gripper frame with the arm at its initial joints (YAML:
  /// start_gMo): with initial_cMo, it places the object and the camera in the world. Batch
  /// trials move it (the gripper starts elsewhere; the final view is the same).
  Pose start_gMo;
  Pose desired_gMo;  ///< the pre-grasp pose (YAML: desired_gMo)
};

/// A numeric field of a scenario file by its dotted key path ("camera.latency_ms",
/// "control.gain"), set to `value` (icgp servo --sweep).
struct FieldValue {
  std::string field;
  double value = 0.0;
};

struct Scenario {
  std::string name;         ///< from the file name unless given
  std::string description;  ///< one line for the summary
  std::string file;         ///< where it was read from
  /// The fields set over the file's (load_scenario with overrides): reading `file` with them
  /// gives this scenario again (another process does, for a trial of a sweep).
  std::vector<FieldValue> overrides;
  /// The profile load_scenario applied (the file's; realistic unless it says ideal). The
  /// values of a Scenario built in code are the ideal ones.
  Profile profile = Profile::kIdeal;
  RobotKind robot = RobotKind::kFreeFlyingCamera;
  ResponseSpec robot_response;
  ArmSpec arm;
  ObjectSpec object;
  std::optional<OccluderSpec> occluder;
  BackgroundSpec background;
  LightingSpec lighting;
  CameraSpec camera;
  CalibrationErrorSpec calibration_error;
  /// Camera-object poses (ViSP cMo): where the run starts, and where the servo must bring it.
  /// A grasp has no desired_cMo (its camera and object stand still): it servoes
  /// grasp->desired_gMo.
  Pose initial_cMo;
  Pose desired_cMo;
  std::optional<GraspSpec> grasp;  ///< set exactly when robot is kViper850Grasp
  TrackerSpec tracker;
  ControlSpec control;
  StopSpec stop;
  TrialSpec trials;
  unsigned seed = 1;  ///< noise and randomised starts
};

/// The most steps one run may take (stop.max_time x camera.rate_hz): a million, about
/// 9 hours at the 30 steps/s of a 640x480 run here, and the per-step log of a run
/// (ServoResult::steps) stays under a gigabyte. docs/servo.md lists every bound.
inline constexpr double kMaxSimulatedSteps = 1e6;

/// The steps of a run that reaches `max_time` seconds at `rate_hz` frames per second: the
/// capture at t = 0 and one per frame period up to max_time (run_servo's loop). A double,
/// so that no rate or time can overflow it; +inf or NaN for nonsense, never below 1 for
/// positive inputs.
double simulated_steps(double max_time, double rate_hz);

/// Throws ScenarioError naming the file and stop.max_time unless a run of `scenario` takes
/// 1 to kMaxSimulatedSteps steps. Each step renders and tracks a frame and keeps a line of
/// log, so the bound keeps a run within hours and its log in memory. load_scenario checks
/// it (only a max_time the file gives can exceed it: the default 20 s at the highest rate is
/// 20001 steps), and run_servo again for scenarios built in code.
void check_run_length(const Scenario& scenario);

/// Reads and validates a scenario: its profile's fields (profile_fields) first, then the
/// file's over them. Relative paths in it are resolved against the file's
/// folder, model names against `models_dir`. Throws ScenarioError naming the file and the
/// field for anything missing, unknown, of the wrong type or out of range, with the range:
/// every number is bounded (docs/servo.md, "Limits"), image sizes by
/// icgp/base/resource_limits.h and the length of a run by kMaxSimulatedSteps.
Scenario load_scenario(const std::string& path, const std::string& models_dir);

/// load_scenario with `overrides` written into the file's document first, as if the file
/// said so: each is then read and checked as the file's own values are (an unknown key or a
/// value out of range is the reader's error, naming the field). Throws ScenarioError naming
/// the field when it holds a list, a section or text rather than a number, or when a key on
/// its path is not a section.
Scenario load_scenario(const std::string& path, const std::string& models_dir, const std::vector<FieldValue>& overrides);

/// The mesh file of a model reference of the scenario (ObjectSpec::model, regions): a
/// folder name of models_dir or a path relative to the scenario's folder. Throws
/// ScenarioError when it does not exist.
std::string resolve_model_path(const std::string& reference, const std::string& scenario_dir,
                               const std::string& models_dir);

}  // namespace icgp::servo
