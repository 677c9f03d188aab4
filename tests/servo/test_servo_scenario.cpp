// SPDX-License-Identifier: GPL-2.0-or-later
// Servo scenario files: a full file read into the struct with its unit conversions, the
// defaults, model resolution, and errors that name the file and the field.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "../unit/test_temp_dir.h"
#include "icgp/servo/scenario.h"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using icgp::Pose;
using icgp::kPi;
using icgp::servo::kDegree;
using icgp::servo::load_scenario;
using icgp::servo::resolve_model_path;
using icgp::servo::Scenario;
using icgp::servo::ScenarioError;
using icgp::test::TempDir;

namespace {

/// The smallest valid scenario: the required keys only.
const std::string kMinimal =
    "object: {model: textured_box}\n"
    "start: {t: [0, 0, 0.45], r_deg: [0, 0, 0]}\n"
    "desired: {t: [0, 0, 0.35], r_deg: [0, 0, 0]}\n";

/// The message of the ScenarioError that loading `text` (saved as `name`) throws; "" if none.
std::string error_of(const TempDir& dir, const std::string& text, const std::string& name = "bad.yaml") {
  const std::string file = dir.write(name, text);
  try {
    load_scenario(file, ICGP_MODELS_DIR);
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}

/// Each case's YAML, added to the minimal scenario and saved as bad.yaml, is refused with
/// the case's message after the file's name.
void check_refusals(const TempDir& dir, const std::vector<std::pair<std::string, std::string>>& cases) {
  const std::string file = (dir.path() / "bad.yaml").string();
  for (const auto& [yaml, message] : cases) {
    INFO(yaml);
    CHECK_THAT(error_of(dir, kMinimal + yaml + "\n"), Contains(file + ": " + message));
  }
}

bool same_file(const std::string& a, const std::string& b) { return fs::equivalent(a, b); }

/// The rotation angle of R (radians).
double angle(const Eigen::Matrix3d& R) { return icgp::rotation_angle_between<double>(Eigen::Matrix3d::Identity(), R); }

}  // namespace

TEST_CASE("a full scenario file is read with its units converted") {
  TempDir dir("icgp-scenario");
  dir.write("a.obj", "v 0 0 0\n");
  fs::create_directory(dir.path() / "meshes");
  dir.write("meshes/b.obj", "v 0 0 0\n");
  dir.write("bg.png", "not really an image");
  dir.write("icgp.yaml", "modalities: [region]\n");
  const std::string file = dir.write("full.yaml", R"(
name: textured-box PBVS
description: one line
robot: viper850_eye_to_hand
arm:
  initial_joints_deg: [0, 20, 80, 0, 80, -90]
  eMo: {t: [0, 0.01, 0.1], r_deg: [90, 0, 0]}
object:
  model: textured_box
  regions: [a.obj, meshes/b.obj]
  motion: {velocity: [0.05, 0, -0.01], start: 0.5, duration: 2.0}
occluder:
  size: [0.04, 0.2, 0.02]
  start_position: [-0.3, 0.01, 0.25]
  velocity: [0.2, 0, 0]
  start: 1.5
background: {enabled: false, texture: bg.png, distance: 0.4}
camera:
  color: {width: 320, height: 240, focal: 300}
  depth: {fu: 280, fv: 281, pu: 160.5, pv: 119, width: 330, height: 250}
  depth_T_color: {t: [-0.025, 0, 0], r_deg: [0, 1, 0]}
  rate_hz: 15
  noise: {color_sigma: 2, depth_sigma_at_1m: 0.001, depth_dropout: 0.05, grazing_angle_deg: 75,
          edge_dropout_px: 2, motion_blur: 0.5, frame_drop: 0.1}
start: {t: [0.02, -0.01, 0.45], r_deg: [5, -10, 3]}
desired: {t: [0, 0, 0.35], r_deg: [0, 0, 0]}
tracker:
  type: visp
  modalities: [region, depth]
  config: icgp.yaml
  visp_configuration: edge + dense depth
control:
  law: ibvs
  gain: {at_zero: 2, at_infinity: 0.4, slope_at_zero: 20}
  max_linear_velocity: 0.2
  max_angular_velocity_deg: 30
  max_joint_velocity_deg: 60
stop: {translation_mm: 2, rotation_deg: 0.5, settle_time: 0.3, max_time: 12}
trials: {translation_mm: 20, rotation_deg: 15}
seed: 7
)");
  const Scenario s = load_scenario(file, ICGP_MODELS_DIR);

  CHECK((s.file == file && s.name == "textured-box PBVS" && s.description == "one line"));
  CHECK(s.robot == icgp::servo::RobotKind::kViper850EyeToHand);
  CHECK(s.arm.initial_joints[1] == Approx(20 * kPi / 180));
  CHECK(s.arm.initial_joints[2] == Approx(1.3962634015954636));  // 80 deg
  CHECK(s.arm.initial_joints[5] == Approx(-kPi / 2));
  CHECK(s.arm.eMo.translation().isApprox(Eigen::Vector3d(0, 0.01, 0.1)));
  // 90 deg about x: y goes to z.
  CHECK((s.arm.eMo.rotation() * Eigen::Vector3d::UnitY()).isApprox(Eigen::Vector3d::UnitZ(), 1e-12));

  CHECK(same_file(s.object.model, ICGP_MODELS_DIR "/textured_box/textured_box.obj"));
  REQUIRE(s.object.regions.size() == 2);
  CHECK(same_file(s.object.regions[0], (dir.path() / "a.obj").string()));
  CHECK(same_file(s.object.regions[1], (dir.path() / "meshes/b.obj").string()));
  CHECK(s.object.linear_velocity.isApprox(Eigen::Vector3d(0.05, 0, -0.01)));
  CHECK((s.object.motion_start == 0.5 && s.object.motion_duration == 2.0));

  REQUIRE(s.occluder);
  CHECK(s.occluder->size.isApprox(Eigen::Vector3d(0.04, 0.2, 0.02)));
  CHECK(s.occluder->start_position_in_camera.isApprox(Eigen::Vector3d(-0.3, 0.01, 0.25)));
  CHECK(s.occluder->velocity_in_camera.isApprox(Eigen::Vector3d(0.2, 0, 0)));
  CHECK(s.occluder->start == 1.5);

  CHECK_FALSE(s.background.enabled);
  CHECK(same_file(s.background.texture, (dir.path() / "bg.png").string()));
  CHECK(s.background.distance == 0.4);

  const icgp::Intrinsics& c = s.camera.color;
  CHECK((c.width == 320 && c.height == 240 && c.fu == 300 && c.fv == 300));
  CHECK((c.pu == 159.5 && c.pv == 119.5));  // centre in the pixel-centre convention
  const icgp::Intrinsics& d = s.camera.depth;
  CHECK((d.width == 330 && d.height == 250 && d.fu == 280 && d.fv == 281 && d.pu == 160.5 && d.pv == 119));
  CHECK(s.camera.depth_T_color.translation().isApprox(Eigen::Vector3d(-0.025, 0, 0)));
  CHECK(angle(s.camera.depth_T_color.rotation()) == Approx(kPi / 180));
  CHECK(s.camera.rate_hz == 15);
  const icgp::servo::NoiseSpec& n = s.camera.noise;
  CHECK((n.color_sigma == 2 && n.depth_sigma_at_1m == 0.001 && n.depth_dropout == 0.05));
  CHECK((n.grazing_angle_deg == 75 && n.depth_edge_holes_px == 2 && n.motion_blur == 0.5 && n.frame_drop == 0.1));

  // start: θu = (5, -10, 3) degrees; its angle is |θu|.
  const Eigen::Vector3d theta_u = Eigen::Vector3d(5, -10, 3) * kPi / 180;
  const Pose expected = Pose::from_rotation_vector(theta_u, Eigen::Vector3d(0.02, -0.01, 0.45));
  CHECK(s.initial_cMo.matrix().isApprox(expected.matrix(), 1e-12));
  CHECK(angle(s.initial_cMo.rotation()) == Approx(std::sqrt(25.0 + 100.0 + 9.0) * kPi / 180));
  CHECK(s.desired_cMo.matrix().isApprox(Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 0.35)).matrix()));

  CHECK(s.tracker.kind == icgp::servo::TrackerKind::kVisp);
  CHECK(s.tracker.modalities == std::vector<std::string>{icgp::cue::kRegion, icgp::cue::kDepth});
  CHECK(same_file(s.tracker.config, (dir.path() / "icgp.yaml").string()));
  CHECK(s.tracker.visp_configuration == "edge + dense depth");

  CHECK(s.control.law == icgp::servo::ControlLawKind::kIbvs);
  CHECK((s.control.gain.at_zero == 2 && s.control.gain.at_infinity == 0.4 && s.control.gain.slope_at_zero == 20));
  CHECK(s.control.gain.adaptive());
  CHECK(s.control.max_linear_velocity == 0.2);
  CHECK(s.control.max_angular_velocity == Approx(kPi / 6));
  CHECK(s.control.max_joint_velocity == Approx(kPi / 3));
  CHECK(s.stop.converged_translation == Approx(0.002));
  CHECK(s.stop.converged_rotation == Approx(0.5 * kPi / 180));
  CHECK((s.stop.settle_time == 0.3 && s.stop.max_time == 12));
  CHECK(s.trials.translation == Approx(0.02));
  CHECK(s.trials.rotation == Approx(kPi / 12));
  CHECK(s.seed == 7);
}

TEST_CASE("keys left out of an ideal scenario take their defaults") {
  TempDir dir("icgp-scenario");
  const Scenario s =
      load_scenario(dir.write("pbvs-box.yaml", "profile: ideal\n" + kMinimal + "control: {gain: 0.8}\n"), ICGP_MODELS_DIR);
  CHECK(s.profile == icgp::servo::Profile::kIdeal);
  CHECK((s.name == "pbvs-box" && s.description.empty()));
  CHECK(s.robot == icgp::servo::RobotKind::kFreeFlyingCamera);
  CHECK(s.arm.initial_joints[1] == Approx(-60 * icgp::servo::kDegree));
  CHECK(s.arm.eMo.translation().isApprox(Eigen::Vector3d(0, 0, 0.1)));
  CHECK((s.object.regions.empty() && s.object.linear_velocity.isZero() && s.object.motion_duration == 0.0));
  CHECK_FALSE(s.occluder);
  CHECK((s.background.enabled && s.background.texture.empty() && s.background.distance == 0.3));
  CHECK((s.camera.color.width == 640 && s.camera.color.height == 480 && s.camera.color.fu == 600));
  CHECK((s.camera.color.pu == 319.5 && s.camera.color.pv == 239.5));
  CHECK((s.camera.depth.width == 640 && s.camera.depth.fv == 600 && s.camera.depth.pv == 239.5));
  CHECK(s.camera.depth_T_color.matrix().isIdentity());
  CHECK(s.camera.rate_hz == 30);
  CHECK((s.camera.noise.color_sigma == 0 && s.camera.noise.depth_dropout == 0 && s.camera.noise.frame_drop == 0));
  CHECK((s.camera.noise.grazing_angle_deg == 90 && s.camera.noise.depth_edge_holes_px == 0));
  CHECK(s.tracker.kind == icgp::servo::TrackerKind::kIcgp);
  CHECK((s.tracker.modalities.empty() && s.tracker.config.empty()));
  CHECK(s.tracker.visp_configuration == "edge + KLT + dense depth");
  CHECK(s.tracker.init_by_detection);  // no true pose enters the loop unless asked for
  CHECK(s.object.removed_for == 0.0);
  CHECK(s.control.law == icgp::servo::ControlLawKind::kPbvs);
  CHECK((s.control.gain.at_zero == 0.8 && s.control.gain.at_infinity == 0.8));  // a number: constant gain
  CHECK_FALSE(s.control.gain.adaptive());
  CHECK((s.control.max_linear_velocity == 0.1 && s.control.max_angular_velocity == 0.5));
  CHECK(s.stop.converged_translation == Approx(0.001));
  CHECK(s.stop.converged_rotation == Approx(0.1 * kDegree));
  CHECK((s.stop.max_time == 20 && s.stop.settle_time == 0.2 && s.seed == 1));
  CHECK(s.trials.translation == Approx(0.02));
  CHECK(s.trials.rotation == Approx(10 * kDegree));
  // The ideal loop: no latency, no jitter, the tracker takes no time, the robot follows at once.
  CHECK((s.camera.latency == 0.0 && s.camera.jitter.spread == 0.0));
  CHECK(s.camera.jitter.distribution == icgp::servo::JitterSpec::Distribution::kNone);
  CHECK((!s.tracker.real_timing && !s.tracker.compute_time));
  CHECK(s.robot_response.immediate());
  CHECK((s.calibration_error.focal == 0.0 && s.calibration_error.principal_point == 0.0));
  CHECK((s.calibration_error.depth_T_color_translation == 0.0 && s.calibration_error.depth_T_color_rotation == 0.0));
  CHECK(s.object.scale_error == 0.0);

  // The depth camera defaults to the colour camera as the file gives it; `occluder:` alone
  // places the default occluder.
  const Scenario t = load_scenario(
      dir.write("b.yaml", "profile: ideal\n" + kMinimal + "occluder:\ncamera: {color: {width: 100, height: 80, focal: 90}}\n"),
      ICGP_MODELS_DIR);
  CHECK((t.camera.depth.width == 100 && t.camera.depth.fu == 90 && t.camera.depth.pu == 49.5));
  REQUIRE(t.occluder);
  CHECK(t.occluder->size.isApprox(Eigen::Vector3d(0.03, 0.3, 0.03)));
}

TEST_CASE("a scenario without a profile is a realistic cell, each of whose fields the file may set") {
  TempDir dir("icgp-scenario");
  const Scenario s = load_scenario(dir.write("cell.yaml", kMinimal), ICGP_MODELS_DIR);
  CHECK(s.profile == icgp::servo::Profile::kRealistic);
  // docs/servo.md, "Profiles": two frames at 30 Hz plus the tracker's time, a 30 ms lag, a
  // calibrated camera's errors, an object half a percent off its model, and success judged
  // as closely as such a cell knows itself.
  CHECK(s.camera.latency == Approx(0.067));
  CHECK((s.camera.jitter.distribution == icgp::servo::JitterSpec::Distribution::kNormal &&
         s.camera.jitter.spread == Approx(0.005)));
  CHECK(s.tracker.real_timing);
  REQUIRE(s.tracker.compute_time);
  CHECK(*s.tracker.compute_time == Approx(0.010));
  CHECK(s.robot_response.lag == Approx(0.030));
  CHECK(s.robot_response.max_linear_acceleration == Approx(13.0));
  CHECK(s.robot_response.max_angular_acceleration == Approx(1432 * kDegree));
  CHECK(s.calibration_error.focal == Approx(0.005));
  CHECK(s.calibration_error.principal_point == Approx(1.5));
  CHECK((s.calibration_error.depth_T_color_translation == Approx(0.001) &&
         s.calibration_error.depth_T_color_rotation == Approx(0.2 * kDegree)));
  CHECK((s.calibration_error.hand_eye_translation == 0.0 && s.calibration_error.joint_offset == 0.0));  // no arm
  CHECK(s.object.scale_error == Approx(0.005));
  CHECK((s.stop.converged_translation == Approx(0.005) && s.stop.converged_rotation == Approx(kDegree)));

  // An arm gets joint accelerations, a hand-eye error and joint offsets instead of Cartesian limits.
  const Scenario arm =
      load_scenario(dir.write("arm.yaml", "robot: viper850_eye_in_hand\n" + kMinimal), ICGP_MODELS_DIR);
  CHECK(arm.robot_response.max_joint_acceleration == Approx(430 * kDegree));
  CHECK(arm.robot_response.max_linear_acceleration == icgp::servo::ResponseSpec::kUnlimited);
  CHECK((arm.calibration_error.hand_eye_translation == Approx(0.0015) &&
         arm.calibration_error.hand_eye_rotation == Approx(0.3 * kDegree)));
  CHECK(arm.calibration_error.joint_offset == Approx(0.02 * kDegree));

  // The file's own values win, a sweep's override too; a timing the file sets takes the
  // profile's compute time with it, and a jitter the file gives is the file's whole.
  const Scenario own = load_scenario(
      dir.write("own.yaml", kMinimal + "camera: {latency_ms: 0, jitter: {distribution: uniform}}\n"
                                       "tracker: {timing: ideal}\nstop: {translation_mm: 2}\n"),
      ICGP_MODELS_DIR, {{"calibration_error.focal_percent", 2.0}});
  CHECK(own.camera.latency == 0.0);
  CHECK((own.camera.jitter.distribution == icgp::servo::JitterSpec::Distribution::kUniform &&
         own.camera.jitter.spread == 0.0));
  CHECK((!own.tracker.real_timing && !own.tracker.compute_time));
  CHECK(own.calibration_error.focal == Approx(0.02));
  CHECK(own.stop.converged_translation == Approx(0.002));
  CHECK(own.stop.converged_rotation == Approx(kDegree));  // the profile's, beside the file's translation

  const std::string bad = (dir.path() / "bad.yaml").string();
  CHECK_THAT(error_of(dir, "profile: exact\n" + kMinimal), Contains(bad + ": profile: expected one of realistic, ideal"));
  // A section that is no section is the reader's error, not the profile's.
  CHECK_THAT(error_of(dir, kMinimal + "camera: 5\n"), Contains(bad + ": camera: expected"));
}

TEST_CASE("a scenario's section for one profile applies in that profile only, over the file's other fields") {
  TempDir dir("icgp-scenario");
  // noisy_depth.yaml's case: its sensor is judged more loosely than the exact world's 1 mm and
  // 0.1 deg, and by the realistic cell's own thresholds there.
  const std::string sections = "stop: {settle_time: 0.3}\n"
                               "profiles:\n"
                               "  ideal: {stop: {translation_mm: 2, rotation_deg: 1}, camera: {latency_ms: 10}}\n"
                               "  realistic: {stop: {settle_time: 0.5}}\n";
  const Scenario ideal = load_scenario(dir.write("ideal.yaml", "profile: ideal\n" + kMinimal + sections), ICGP_MODELS_DIR);
  CHECK((ideal.stop.converged_translation == Approx(0.002) && ideal.stop.converged_rotation == Approx(kDegree)));
  CHECK(ideal.camera.latency == Approx(0.010));
  CHECK(ideal.stop.settle_time == Approx(0.3));  // the file's, the realistic section aside

  const Scenario realistic = load_scenario(dir.write("realistic.yaml", kMinimal + sections), ICGP_MODELS_DIR);
  CHECK((realistic.stop.converged_translation == Approx(0.005) && realistic.stop.converged_rotation == Approx(kDegree)));
  CHECK(realistic.camera.latency == Approx(0.067));
  CHECK(realistic.stop.settle_time == Approx(0.5));  // the section's, over the file's

  // The command line's values win over the section's.
  const Scenario swept = load_scenario(dir.write("swept.yaml", "profile: ideal\n" + kMinimal + sections),
                                       ICGP_MODELS_DIR, {{"camera.latency_ms", 20.0}});
  CHECK(swept.camera.latency == Approx(0.020));

  const std::string bad = (dir.path() / "bad.yaml").string();
  CHECK_THAT(error_of(dir, kMinimal + "profiles: {exact: {stop: {translation_mm: 2}}}\n"),
             Contains(bad + ": profiles.exact: unknown key (expected one of realistic, ideal)"));
  CHECK_THAT(error_of(dir, kMinimal + "profiles: {ideal: 5}\n"),
             Contains(bad + ": profiles.ideal: expected a section of scenario fields, got 5"));
  CHECK_THAT(error_of(dir, kMinimal + "profiles: 5\n"), Contains(bad + ": profiles: expected a map"));
  // A field a section names is checked as the file's own would be.
  CHECK_THAT(error_of(dir, kMinimal + "profiles: {realistic: {stop: {translation_mm: -1}}}\n"),
             Contains(bad + ": stop.translation_mm: expected"));
}

TEST_CASE("a scenario sets how the tracker starts and when the object is taken away") {
  TempDir dir("icgp-scenario");
  const Scenario s = load_scenario(
      dir.write("removed.yaml", "object:\n  model: textured_box\n"
                                "  removed: {at: 1.0, for: 1.5, back: {t: [0.03, 0, 0.025], r_deg: [0, 15, 0]}}\n"
                                "start: {t: [0, 0, 0.5], r_deg: [180, 0, 0]}\ndesired: {t: [0, 0, 0.35], r_deg: [180, 0, 0]}\n"
                                "tracker: {type: icgp, init: truth}\n"),
      ICGP_MODELS_DIR);
  CHECK_FALSE(s.tracker.init_by_detection);
  CHECK((s.object.removed_at == 1.0 && s.object.removed_for == 1.5));
  CHECK(s.object.put_back.translation().isApprox(Eigen::Vector3d(0.03, 0, 0.025)));
  CHECK(s.object.settled_time() == 2.5);
  const std::string bad = dir.write("bad.yaml", kMinimal + "tracker: {init: guess}\n");
  CHECK_THROWS_WITH(load_scenario(bad, ICGP_MODELS_DIR),
                    Contains(bad + ": tracker.init: expected one of detect, truth"));
}

TEST_CASE("a scenario sets the loop's timing and the robot's response, each bounded") {
  TempDir dir("icgp-scenario");
  const Scenario s = load_scenario(
      dir.write("timed.yaml", kMinimal + "camera: {latency_ms: 66.7, jitter: {distribution: normal, ms: 4}}\n"
                                         "tracker: {timing: real, compute_ms: 12}\n"
                                         "robot_response: {lag_ms: 30, max_linear_acceleration: 2, "
                                         "max_angular_acceleration_deg: 90, max_joint_acceleration_deg: 180}\n"),
      ICGP_MODELS_DIR);
  CHECK(s.camera.latency == Approx(0.0667));
  CHECK(s.camera.jitter.distribution == icgp::servo::JitterSpec::Distribution::kNormal);
  CHECK(s.camera.jitter.spread == Approx(0.004));
  CHECK(s.tracker.real_timing);
  REQUIRE(s.tracker.compute_time);
  CHECK(*s.tracker.compute_time == Approx(0.012));
  CHECK(s.robot_response.lag == Approx(0.03));
  CHECK(s.robot_response.max_linear_acceleration == 2.0);
  CHECK(s.robot_response.max_angular_acceleration == Approx(90 * kDegree));
  CHECK(s.robot_response.max_joint_acceleration == Approx(180 * kDegree));
  CHECK_FALSE(s.robot_response.immediate());
  // Measured compute time: timing real without compute_ms.
  CHECK_FALSE(load_scenario(dir.write("measured.yaml", kMinimal + "tracker: {timing: real}\n"), ICGP_MODELS_DIR)
                  .tracker.compute_time);

  const std::vector<std::pair<std::string, std::string>> cases = {
      {"camera: {latency_ms: -5}", "camera.latency_ms: expected a number in [0, 86400000], got -5"},
      {"camera: {latency_ms: 20000}", "camera.latency_ms: expected less than stop.max_time (20000 ms), got 20000"},
      {"camera: {jitter: {distribution: gamma, ms: 3}}", "camera.jitter.distribution: expected one of none, uniform, normal"},
      {"camera: {jitter: {distribution: uniform, ms: -1}}", "camera.jitter.ms: expected a number in [0, 10000], got -1"},
      {"tracker: {timing: fast}", "tracker.timing: expected one of ideal, real"},
      {"tracker: {timing: ideal, compute_ms: 10}", "tracker.compute_ms: a compute time counts only with timing: real"},
      {"robot_response: {lag_ms: -30}", "robot_response.lag_ms: expected a number in [0, 10000], got -30"},
      {"robot_response: {max_linear_acceleration: 0}",
       "robot_response.max_linear_acceleration: expected a number in (0, 1000000], got 0"},
  };
  check_refusals(dir, cases);
}

TEST_CASE("a scenario gives its calibration errors (an arm's alone for hand-eye and joints) and the object's mismatch") {
  TempDir dir("icgp-scenario");
  const std::string arm = "robot: viper850_eye_in_hand\n";
  const Scenario s = load_scenario(
      dir.write("calibrated.yaml", kMinimal + arm +
                                       "calibration_error: {focal_percent: 1, principal_point_px: 2, k1: -0.05, "
                                       "depth_T_color: {translation_mm: 1, rotation_deg: 0.2}, "
                                       "hand_eye: {translation_mm: 2, rotation_deg: 0.5}, joint_offsets_deg: 0.1}\n"),
      ICGP_MODELS_DIR);
  const icgp::servo::CalibrationErrorSpec& e = s.calibration_error;
  CHECK(e.focal == Approx(0.01));
  CHECK(e.principal_point == 2.0);
  CHECK(e.k1 == -0.05);
  CHECK((e.depth_T_color_translation == Approx(0.001) && e.depth_T_color_rotation == Approx(0.2 * kDegree)));
  CHECK((e.hand_eye_translation == Approx(0.002) && e.hand_eye_rotation == Approx(0.5 * kDegree)));
  CHECK(e.joint_offset == Approx(0.1 * kDegree));

  const Scenario m = load_scenario(
      dir.write("mismatch.yaml", "object: {model: textured_box, true_model: textured_box, scale_error_percent: -0.5, "
                                 "vertex_noise_mm: 0.2}\n" + kMinimal.substr(kMinimal.find("start"))),
      ICGP_MODELS_DIR);
  CHECK(same_file(m.object.true_model, m.object.model));
  CHECK(m.object.scale_error == Approx(-0.005));
  CHECK(m.object.vertex_noise == Approx(0.0002));

  const std::string file = (dir.path() / "bad.yaml").string();
  CHECK_THAT(error_of(dir, "object: {model: textured_box, scale_error_percent: 60}\n" +
                               kMinimal.substr(kMinimal.find("start"))),
             Contains(file + ": object.scale_error_percent: expected a number in [-50, 50], got 60"));
  CHECK_THAT(error_of(dir, "object: {model: textured_box, true_model: no_such_mesh}\n" +
                               kMinimal.substr(kMinimal.find("start"))),
             Contains(file + ": object.true_model"));
  CHECK_THAT(error_of(dir, kMinimal + "calibration_error: {focal_percent: -100}\n"),
             Contains(file + ": calibration_error.focal_percent: expected a number in [0, 50], got -100"));
  CHECK_THAT(error_of(dir, kMinimal + "calibration_error: {hand_eye: {translation_mm: 2}}\n"),
             Contains(file + ": calibration_error.hand_eye: a free-flying camera has no hand-eye calibration"));
  CHECK_THAT(error_of(dir, kMinimal + "calibration_error: {joint_offsets_deg: 0.1}\n"),
             Contains(file + ": calibration_error.joint_offsets_deg: a free-flying camera has no joints"));
  CHECK_THAT(error_of(dir, kMinimal + arm + "calibration_error: {hand_eye: {translation: 2}}\n"),
             Contains(file + ": calibration_error.hand_eye"));
}

TEST_CASE("model references resolve to a folder of models/ or a file next to the scenario") {
  TempDir dir("icgp-scenario");
  const std::string models = ICGP_MODELS_DIR;
  CHECK(same_file(resolve_model_path("textured_box", dir.path().string(), models),
                  models + "/textured_box/textured_box.obj"));
  CHECK(same_file(resolve_model_path("two_region", dir.path().string(), models), models + "/two_region/object.obj"));
  dir.write("mine.obj", "v 0 0 0\n");
  CHECK(same_file(resolve_model_path("mine.obj", dir.path().string(), models), (dir.path() / "mine.obj").string()));
  CHECK(same_file(resolve_model_path((dir.path() / "mine.obj").string(), "/nonexistent", models),
                  (dir.path() / "mine.obj").string()));
  CHECK_THROWS_WITH(resolve_model_path("no_such_model", dir.path().string(), models),
                    Contains("no_such_model") && Contains(models + "/no_such_model/object.obj") &&
                        Contains((dir.path() / "no_such_model").string()));

  const Scenario s = load_scenario(
      dir.write("two.yaml", "object: {model: two_region, regions: [mine.obj]}\n"
                            "start: {t: [0, 0, 0.4], r_deg: [0, 0, 0]}\ndesired: {t: [0, 0, 0.3], r_deg: [0, 0, 0]}\n"),
      models);
  CHECK(same_file(s.object.model, models + "/two_region/object.obj"));
  REQUIRE(s.object.regions.size() == 1);
  CHECK(same_file(s.object.regions[0], (dir.path() / "mine.obj").string()));
}

TEST_CASE("scenario errors name the file and the field") {
  TempDir dir("icgp-scenario");
  const auto error = [&](const std::string& text) { return error_of(dir, text); };
  const std::string file = (dir.path() / "bad.yaml").string();

  SECTION("missing scenario file") {
    const std::string missing = (dir.path() / "missing.yaml").string();
    CHECK_THROWS_WITH(load_scenario(missing, ICGP_MODELS_DIR), missing + ": no such scenario file");
  }
  SECTION("YAML syntax error") {
    CHECK_THAT(error(kMinimal + "control: {gain: [0.5\n"), Contains(file + ": line ") && Contains("column"));
  }
  SECTION("unknown keys, at the top and nested") {
    CHECK_THAT(error(kMinimal + "speed: 3\n"), Contains(file + ": speed: unknown key (expected one of name,"));
    CHECK_THAT(error(kMinimal + "control: {gian: 0.5}\n"),
               Contains(file + ": control.gian: unknown key (expected one of law, gain, max_linear_velocity"));
    CHECK_THAT(error(kMinimal + "camera: {noise: {depth_drop: 0.1}}\n"), Contains(file + ": camera.noise.depth_drop"));
  }
  SECTION("wrong types") {
    CHECK(error(kMinimal + "control: {gain: fast}\n") ==
          file + ": control.gain: expected a number in (0, 1000], got 'fast'");
    CHECK_THAT(error(kMinimal + "camera: {rate_hz: [30]}\n"),
               Contains(file + ": camera.rate_hz: expected a number in (0, 1000], got [30]"));
    CHECK_THAT(error(kMinimal + "camera: {color: {width: 640.5}}\n"),
               Contains(file + ": camera.color.width: expected an integer in [1, 8192], got 640.5"));
    CHECK_THAT(error(kMinimal + "occluder: {size: [1, 2]}\n"),
               Contains(file + ": occluder.size: expected a list of 3 numbers in [0, 100], got [1, 2]"));
    CHECK_THAT(error(kMinimal + "background: {enabled: maybe}\n"),
               Contains(file + ": background.enabled: expected true or false, got 'maybe'"));
    CHECK_THAT(error(kMinimal + "control: [pbvs]\n"), Contains(file + ": control: expected a map with the keys law"));
  }
  SECTION("out of range") {
    CHECK(error(kMinimal + "camera: {noise: {depth_dropout: 1.5}}\n") ==
          file + ": camera.noise.depth_dropout: expected a number in [0, 1), got 1.5");
    CHECK_THAT(error(kMinimal + "camera: {noise: {grazing_angle_deg: 0}}\n"),
               Contains(file + ": camera.noise.grazing_angle_deg: expected a number in (0, 90], got 0"));
    CHECK_THAT(error(kMinimal + "camera: {noise: {motion_blur: 1.01}}\n"),
               Contains(file + ": camera.noise.motion_blur: expected a number in [0, 1]"));
    CHECK_THAT(error(kMinimal + "camera: {noise: {edge_dropout_px: -1}}\n"),
               Contains(file + ": camera.noise.edge_dropout_px: expected an integer in [0, 100], got -1"));
    CHECK_THAT(error(kMinimal + "control: {gain: {at_zero: 0}}\n"),
               Contains(file + ": control.gain.at_zero: expected a number in (0, 1000], got 0"));
    CHECK_THAT(error(kMinimal + "control: {max_angular_velocity_deg: -30}\n"),
               Contains(file + ": control.max_angular_velocity_deg: expected a number in (0, 3600], got -30"));
    CHECK_THAT(error(kMinimal + "stop: {max_time: 0}\n"), Contains(file + ": stop.max_time: expected a number in (0, 86400], got 0"));
    CHECK_THAT(error(kMinimal + "seed: -1\n"), Contains(file + ": seed: expected a non-negative integer, got -1"));
    CHECK_THAT(error("object: {model: textured_box}\nstart: {t: [0, 0, -0.4], r_deg: [0, 0, 0]}\n"
                     "desired: {t: [0, 0, 0.35], r_deg: [0, 0, 0]}\n"),
               Contains(file + ": start.t: the object must be in front of the camera (z > 0), got [0, 0, -0.4]"));
  }
  SECTION("bad enums and modalities") {
    CHECK(error(kMinimal + "robot: ur5\n") ==
          file + ": robot: expected one of free_flying, viper850_eye_in_hand, viper850_eye_to_hand, viper850_grasp, "
                 "got 'ur5'");
    CHECK_THAT(error(kMinimal + "control: {law: vvs}\n"), Contains(file + ": control.law: expected one of pbvs, ibvs"));
    CHECK_THAT(error(kMinimal + "tracker: {visp_configuration: edge}\n"),
               Contains(file + ": tracker.visp_configuration: expected one of edge + dense depth, KLT + dense depth"));
    CHECK_THAT(error(kMinimal + "tracker: {modalities: [region, edges]}\n"),
               Contains(file + ": tracker.modalities: expected a non-empty list") &&
                   Contains("got ['region', 'edges']"));
    CHECK_THAT(error(kMinimal + "tracker: {modalities: []}\n"), Contains(file + ": tracker.modalities: expected"));
  }
  SECTION("missing required keys") {
    CHECK(error("start: {t: [0, 0, 0.4], r_deg: [0, 0, 0]}\n") == file + ": object: required");
    CHECK(error("object: {model: textured_box}\nstart: {t: [0, 0, 0.4], r_deg: [0, 0, 0]}\n") ==
          file + ": desired: required");
    CHECK_THAT(error("object: {model: textured_box}\nstart: {t: [0, 0, 0.4]}\n"
                     "desired: {t: [0, 0, 0.4], r_deg: [0, 0, 0]}\n"),
               Contains(file + ": start.r_deg: required"));
    CHECK_THAT(error("object: {regions: []}\n"), Contains(file + ": object.model: required"));
  }
  SECTION("references to files that do not exist") {
    CHECK_THAT(error("object: {model: no_such_model}\n"),
               Contains(file + ": object.model: expected a model folder of") && Contains("'no_such_model'") &&
                   Contains(std::string(ICGP_MODELS_DIR) + "/no_such_model/no_such_model.obj") &&
                   Contains((dir.path() / "no_such_model").string()));
    CHECK_THAT(error("object: {model: textured_box, regions: [missing.obj]}\n"),
               Contains(file + ": object.regions[0]: ") && Contains((dir.path() / "missing.obj").string()));
    CHECK_THAT(error(kMinimal + "background: {texture: bg.png}\n"),
               Contains(file + ": background.texture: expected an existing file") &&
                   Contains((dir.path() / "bg.png").string()));
    CHECK_THAT(error(kMinimal + "tracker: {config: icgp.yaml}\n"),
               Contains(file + ": tracker.config: ") && Contains((dir.path() / "icgp.yaml").string()));
  }
}

namespace {

/// The smallest valid grasp scenario: the required keys only.
const std::string kMinimalGrasp =
    "robot: viper850_grasp\n"
    "object: {model: textured_box}\n"
    "gripper: {model: gripper}\n"
    "start: {t: [0, 0, 0.6], r_deg: [0, 0, 0]}\n"
    "start_gMo: {t: [0, 0, 0.25], r_deg: [0, 0, 0]}\n"
    "desired_gMo: {t: [0, 0, 0.15], r_deg: [0, 0, 0]}\n";

/// `text` without the line that starts with `key`.
std::string without(const std::string& text, const std::string& key) {
  const std::size_t at = text.find(key);
  return text.substr(0, at) + text.substr(text.find('\n', at) + 1);
}

}  // namespace

TEST_CASE("a grasp scenario: gripper, start_gMo and desired_gMo read with their units") {
  TempDir dir("icgp-scenario");
  const Scenario s = load_scenario(
      dir.write("grasp.yaml", without(kMinimalGrasp, "gripper:") +
                                  "gripper: {model: gripper, eMg: {t: [0, 0, 0.01], r_deg: [0, 0, 90]}}\n"),
      ICGP_MODELS_DIR);
  CHECK(s.robot == icgp::servo::RobotKind::kViper850Grasp);
  REQUIRE(s.grasp);
  CHECK(same_file(s.grasp->gripper_model, std::string(ICGP_MODELS_DIR) + "/gripper/gripper.obj"));
  CHECK(s.grasp->eMg.translation().isApprox(Eigen::Vector3d(0, 0, 0.01)));
  CHECK(angle(s.grasp->eMg.rotation()) == Approx(kPi / 2));
  CHECK(s.grasp->start_gMo.translation().isApprox(Eigen::Vector3d(0, 0, 0.25)));
  CHECK(s.grasp->desired_gMo.translation().isApprox(Eigen::Vector3d(0, 0, 0.15)));
  // eMg defaults to the identity: the gripper's mount on the flange.
  const Scenario t = load_scenario(dir.write("plain.yaml", kMinimalGrasp), ICGP_MODELS_DIR);
  REQUIRE(t.grasp);
  CHECK(t.grasp->eMg.matrix().isIdentity());
  // Other robots have none.
  CHECK_FALSE(load_scenario(dir.write("camera.yaml", kMinimal), ICGP_MODELS_DIR).grasp);
}

TEST_CASE("grasp keys: required for a grasp, refused elsewhere, bounded, each error naming the file and the field") {
  TempDir dir("icgp-scenario");
  const auto error = [&](const std::string& text) { return error_of(dir, text); };
  const std::string file = (dir.path() / "bad.yaml").string();
  for (const std::string key : {"gripper", "start_gMo", "desired_gMo"}) {
    INFO(key);
    CHECK(error(without(kMinimalGrasp, key + ":")) == file + ": " + key + ": required when robot is viper850_grasp");
    CHECK(error(kMinimal + key + ": {t: [0, 0, 0.1], r_deg: [0, 0, 0]}\n") ==
          file + ": " + key + ": only a viper850_grasp scenario has a gripper (robot is free_flying)");
  }
  CHECK(error(kMinimalGrasp + "desired: {t: [0, 0, 0.35], r_deg: [0, 0, 0]}\n") ==
        file + ": desired: a viper850_grasp scenario servoes the gripper to the object: give desired_gMo, not desired");
  CHECK(error(kMinimalGrasp + "control: {law: ibvs}\n") ==
        file + ": control.law: expected pbvs (a viper850_grasp scenario servoes the gripper's pose gMo), got 'ibvs'");
  CHECK(error(without(kMinimalGrasp, "gripper:") + "gripper: {eMg: {t: [0, 0, 0], r_deg: [0, 0, 0]}}\n") ==
        file + ": gripper.model: required");
  CHECK_THAT(error(without(kMinimalGrasp, "gripper:") + "gripper: {model: no_such_gripper}\n"),
             Contains(file + ": gripper.model: expected a model folder of") && Contains("'no_such_gripper'"));
  CHECK_THAT(error(without(kMinimalGrasp, "gripper:") + "gripper: {model: gripper, mount: 1}\n"),
             Contains(file + ": gripper.mount: unknown key (expected one of model, eMg)"));
  CHECK(error(without(kMinimalGrasp, "gripper:") + "gripper: {model: gripper, eMg: {t: [0, 0, 1e3], r_deg: [0, 0, 0]}}\n") ==
        file + ": gripper.eMg.t: expected a list of 3 numbers in [-100, 100], got [0, 0, 1e3]");
  CHECK(error(without(kMinimalGrasp, "start_gMo:") + "start_gMo: {t: [0, 0, 0.25], r_deg: [400, 0, 0]}\n") ==
        file + ": start_gMo.r_deg: expected a list of 3 numbers in [-360, 360], got [400, 0, 0]");
  CHECK(error(without(kMinimalGrasp, "desired_gMo:") + "desired_gMo: {t: [0, 0, 0.15]}\n") ==
        file + ": desired_gMo.r_deg: required");
}

TEST_CASE("every number of a scenario is bounded, and a refusal names the field, the value and the range") {
  TempDir dir("icgp-scenario");
  const std::string file = (dir.path() / "bad.yaml").string();
  // Each: a scenario with one value out of its range, and the whole message it must give.
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"camera: {color: {width: 100000}}", "camera.color.width: expected an integer in [1, 8192], got 100000"},
      {"camera: {color: {height: 0}}", "camera.color.height: expected an integer in [1, 8192], got 0"},
      {"camera: {depth: {width: 30000000000}}",
       "camera.depth.width: expected an integer in [1, 8192], got 30000000000"},
      {"camera: {color: {focal: 1e9}}", "camera.color.focal: expected a number in (0, 100000], got 1e9"},
      {"camera: {color: {pu: -1e6}}", "camera.color.pu: expected a number in [-8192, 16384], got -1e6"},
      {"camera: {rate_hz: 1e12}", "camera.rate_hz: expected a number in (0, 1000], got 1e12"},
      {"camera: {rate_hz: .nan}", "camera.rate_hz: expected a number in (0, 1000], got .nan"},
      {"camera: {noise: {color_sigma: 1000}}", "camera.noise.color_sigma: expected a number in [0, 255], got 1000"},
      {"camera: {noise: {depth_sigma_at_1m: 2}}",
       "camera.noise.depth_sigma_at_1m: expected a number in [0, 1], got 2"},
      {"camera: {noise: {edge_dropout_px: 1000000}}",
       "camera.noise.edge_dropout_px: expected an integer in [0, 100], got 1000000"},
      {"stop: {max_time: 1e300}", "stop.max_time: expected a number in (0, 86400], got 1e300"},
      {"stop: {max_time: .inf}", "stop.max_time: expected a number in (0, 86400], got .inf"},
      {"stop: {settle_time: 1e9}", "stop.settle_time: expected a number in [0, 86400], got 1e9"},
      {"stop: {translation_mm: 5000}", "stop.translation_mm: expected a number in [0, 1000], got 5000"},
      {"stop: {rotation_deg: 181}", "stop.rotation_deg: expected a number in [0, 180], got 181"},
      {"trials: {translation_mm: 1e6}", "trials.translation_mm: expected a number in [0, 1000], got 1e6"},
      {"trials: {rotation_deg: -1}", "trials.rotation_deg: expected a number in [0, 180], got -1"},
      {"control: {gain: 1e9}", "control.gain: expected a number in (0, 1000], got 1e9"},
      {"control: {gain: {slope_at_zero: 1e9}}",
       "control.gain.slope_at_zero: expected a number in (0, 100000], got 1e9"},
      {"control: {max_linear_velocity: 1e300}",
       "control.max_linear_velocity: expected a number in (0, 10], got 1e300"},
      {"control: {max_joint_velocity_deg: 1e5}",
       "control.max_joint_velocity_deg: expected a number in (0, 3600], got 1e5"},
      {"arm: {initial_joints_deg: [0, 0, 1000, 0, 0, 0]}",
       "arm.initial_joints_deg: expected a list of 6 numbers in [-360, 360], got [0, 0, 1000, 0, 0, 0]"},
      {"arm: {eMo: {t: [0, 0, 1e10], r_deg: [0, 0, 0]}}",
       "arm.eMo.t: expected a list of 3 numbers in [-100, 100], got [0, 0, 1e10]"},
      {"object: {model: textured_box, motion: {velocity: [1e3, 0, 0]}}",
       "object.motion.velocity: expected a list of 3 numbers in [-10, 10], got [1e3, 0, 0]"},
      {"object: {model: textured_box, motion: {duration: 1e20}}",
       "object.motion.duration: expected a number in [0, 86400], got 1e20"},
      {"occluder: {velocity: [1e300, 0, 0]}",
       "occluder.velocity: expected a list of 3 numbers in [-100, 100], got [1e300, 0, 0]"},
      {"occluder: {start: -1}", "occluder.start: expected a number in [0, 86400], got -1"},
      {"background: {distance: 1e6}", "background.distance: expected a number in [0, 100], got 1e6"},
      {"lighting: {direction: [0, 0, 1e308]}",
       "lighting.direction: expected a list of 3 numbers in [-1000, 1000], got [0, 0, 1e308]"},
  };
  for (const auto& [yaml, message] : cases) {
    INFO(yaml);
    // `object:` given here replaces the minimal scenario's (a key may not come twice).
    const bool has_object = yaml.rfind("object:", 0) == 0;
    const std::string text = has_object ? yaml + "\nstart: {t: [0, 0, 0.45], r_deg: [0, 0, 0]}\n"
                                                 "desired: {t: [0, 0, 0.35], r_deg: [0, 0, 0]}\n"
                                          : kMinimal + yaml + "\n";
    CHECK(error_of(dir, text) == file + ": " + message);
  }
  CHECK(error_of(dir, "object: {model: textured_box}\nstart: {t: [0, 0, 1e300], r_deg: [0, 0, 0]}\n"
                      "desired: {t: [0, 0, 0.35], r_deg: [0, 0, 0]}\n") ==
        file + ": start.t: expected a list of 3 numbers in [-100, 100], got [0, 0, 1e300]");
  CHECK(error_of(dir, kMinimal.substr(0, kMinimal.find("desired")) + "desired: {t: [0, 0, 0.35], r_deg: [0, 720, 0]}\n") ==
        file + ": desired.r_deg: expected a list of 3 numbers in [-360, 360], got [0, 720, 0]");
}

TEST_CASE("a scenario camera is bounded in pixels, not only per side") {
  TempDir dir("icgp-scenario");
  const std::string file = (dir.path() / "bad.yaml").string();
  // 8192 x 4096 = 33554432 pixels is the most: 8K UHD fits, a square of the longest side does not.
  const Scenario largest =
      load_scenario(dir.write("largest.yaml", kMinimal + "camera: {color: {width: 8192, height: 4096}}\n"), ICGP_MODELS_DIR);
  CHECK((largest.camera.color.width == 8192 && largest.camera.color.height == 4096));
  CHECK(error_of(dir, kMinimal + "camera: {color: {width: 8192, height: 8192}}\n") ==
        file + ": camera.color: 8192 x 8192 = 67108864 pixels, more than the 33554432 (8192 x 4096) an image may have");
  CHECK(error_of(dir, kMinimal + "camera: {depth: {width: 4097, height: 8192}}\n") ==
        file + ": camera.depth: 4097 x 8192 = 33562624 pixels, more than the 33554432 (8192 x 4096) an image may have");
}

TEST_CASE("a scenario run is bounded in simulated steps (stop.max_time x camera.rate_hz)") {
  TempDir dir("icgp-scenario");
  const std::string file = (dir.path() / "bad.yaml").string();
  // At 16 Hz (a period of 1/16 s, exact in binary), max_time T takes 16 T periods plus the
  // capture at t = 0: 62499.9375 s is exactly 1000000 steps, the most a run may take.
  const Scenario longest = load_scenario(
      dir.write("longest.yaml", kMinimal + "camera: {rate_hz: 16}\nstop: {max_time: 62499.9375}\n"), ICGP_MODELS_DIR);
  CHECK(icgp::servo::simulated_steps(longest.stop.max_time, longest.camera.rate_hz) == 1000000.0);
  CHECK(error_of(dir, kMinimal + "camera: {rate_hz: 16}\nstop: {max_time: 62500}\n") ==
        file + ": stop.max_time: 62500 s at camera.rate_hz 16 Hz is 1000001 simulated steps, outside the [1, 1000000] "
               "a run may take (lower max_time or rate_hz)");
  CHECK_THAT(error_of(dir, kMinimal + "camera: {rate_hz: 1000}\nstop: {max_time: 86400}\n"),
             Contains("stop.max_time: 86400 s at camera.rate_hz 1000 Hz is 86400001 simulated steps"));
  CHECK(icgp::servo::simulated_steps(10.0, 30.0) == 301.0);
  CHECK(icgp::servo::simulated_steps(0.01, 30.0) == 2.0);
}

TEST_CASE("every scenario shipped in scenarios/ and its folders loads") {
  namespace fs = std::filesystem;
  int count = 0;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(ICGP_MODELS_DIR "/../scenarios")) {
    if (entry.path().extension() != ".yaml") continue;
    INFO(entry.path());
    CHECK_NOTHROW(load_scenario(entry.path().string(), ICGP_MODELS_DIR));
    ++count;
  }
  CHECK(count >= 15);  // the 13 scenarios and the two of scenarios/textbook
}

TEST_CASE("lighting: a light on the camera, its direction must not be zero") {
  TempDir dir("icgp-scenario");
  const Scenario s = load_scenario(
      dir.write("lit.yaml", kMinimal + "lighting: {direction: [0, 1, 1], ambient: 0.2, diffuse: 0.8}\n"), ICGP_MODELS_DIR);
  CHECK(s.lighting.direction_in_camera.isApprox(Eigen::Vector3d(0, 1, 1)));
  CHECK((s.lighting.ambient == 0.2 && s.lighting.diffuse == 0.8));
  const Scenario defaults = load_scenario(dir.write("plain.yaml", kMinimal), ICGP_MODELS_DIR);
  CHECK(defaults.lighting.direction_in_camera.isApprox(Eigen::Vector3d(0, 0, 1)));
  CHECK_THROWS_WITH(load_scenario(dir.write("dark.yaml", kMinimal + "lighting: {direction: [0, 0, 0]}\n"), ICGP_MODELS_DIR),
                    Contains("dark.yaml") && Contains("lighting.direction: expected a non-zero direction"));
  CHECK_THROWS_WITH(load_scenario(dir.write("bright.yaml", kMinimal + "lighting: {ambient: 1.5}\n"), ICGP_MODELS_DIR),
                    Contains("lighting.ambient: expected a number in [0, 1]"));

  const Scenario changing = load_scenario(
      dir.write("changing.yaml", kMinimal + "lighting: {motion: {axis: [1, 0, 0], deg_per_s: -20}, "
                                            "flicker: {amplitude: 0.1, hz: 100}}\n"),
      ICGP_MODELS_DIR);
  CHECK(changing.lighting.motion_axis.isApprox(Eigen::Vector3d(1, 0, 0)));
  CHECK(changing.lighting.motion_rate == Approx(-20 * kDegree));
  CHECK((changing.lighting.flicker_amplitude == 0.1 && changing.lighting.flicker_hz == 100.0));
  CHECK((defaults.lighting.motion_rate == 0.0 && defaults.lighting.flicker_amplitude == 0.0));
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"lighting: {motion: {axis: [0, 0, 0], deg_per_s: 10}}", "lighting.motion.axis: expected a non-zero axis"},
      {"lighting: {motion: {axis: [0, 1, 0]}}", "lighting.motion.deg_per_s: required"},
      {"lighting: {motion: {deg_per_s: 5000}}", "lighting.motion.deg_per_s: expected a number in [-3600, 3600], got 5000"},
      {"lighting: {flicker: {amplitude: 1.5, hz: 100}}", "lighting.flicker.amplitude: expected a number in [0, 1], got 1.5"},
      {"lighting: {flicker: {amplitude: 0.1}}", "lighting.flicker.hz: required"},
  };
  check_refusals(dir, cases);
}

TEST_CASE("lighting: lamps fixed in the scene, and some light somewhere; the camera's vignetting and auto-exposure") {
  TempDir dir("icgp-scenario");
  const Scenario s = load_scenario(
      dir.write("lamps.yaml", kMinimal + "lighting: {lamps: [{direction: [0, 2, 0], strength: 0.4}, "
                                         "{direction: [1, 0, 1], strength: 0}]}\n"),
      ICGP_MODELS_DIR);
  REQUIRE(s.lighting.scene_lamps.size() == 2);
  CHECK(s.lighting.scene_lamps[0].direction_in_start_camera.isApprox(Eigen::Vector3d(0, 2, 0)));
  CHECK(s.lighting.scene_lamps[0].strength == 0.4);
  CHECK(s.lighting.scene_lamps[1].strength == 0.0);
  const Scenario only_lamp = load_scenario(
      dir.write("only_lamp.yaml",
                kMinimal + "lighting: {ambient: 0, diffuse: 0, lamps: [{direction: [0, 1, 0], strength: 0.1}]}\n"),
      ICGP_MODELS_DIR);
  CHECK(only_lamp.lighting.scene_lamps.size() == 1);
  const Scenario exposed = load_scenario(
      dir.write("exposed.yaml", kMinimal + "camera: {vignetting: 0.4, auto_exposure: {target: 0.3, time_constant_s: 0.5}}\n"),
      ICGP_MODELS_DIR);
  CHECK((exposed.camera.vignetting == 0.4 && exposed.camera.auto_exposure.target == 0.3 &&
         exposed.camera.auto_exposure.time_constant == 0.5));
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"lighting: {ambient: 0, diffuse: 0}",
       "lighting: expected a light: ambient, diffuse and every lamp's strength are 0, and the camera would see black"},
      {"lighting: {ambient: 0, diffuse: 0, lamps: [{direction: [0, 1, 0], strength: 0}]}",
       "lighting: expected a light: ambient, diffuse and every lamp's strength are 0"},
      {"lighting: {lamps: [{direction: [0, 0, 0], strength: 0.5}]}",
       "lighting.lamps[0].direction: expected a non-zero direction"},
      {"lighting: {lamps: [{direction: [0, 1, 0]}]}", "lighting.lamps[0].strength: required"},
      {"lighting: {lamps: [{direction: [0, 1, 0], strength: 2}]}",
       "lighting.lamps[0].strength: expected a number in [0, 1], got 2"},
      {"lighting: {lamps: {direction: [0, 1, 0], strength: 0.5}}",
       "lighting.lamps: expected a list of lamps, each {direction, strength}"},
      {"lighting: {lamps: [{direction: [0, 1, 0], strength: 0.1}, {direction: [0, 1, 0], strength: 0.1}, "
       "{direction: [0, 1, 0], strength: 0.1}, {direction: [0, 1, 0], strength: 0.1}]}",
       "lighting.lamps: expected at most 3 lamps"},
      {"camera: {vignetting: 1.5}", "camera.vignetting: expected a number in [0, 1], got 1.5"},
      {"camera: {auto_exposure: {time_constant_s: 0.5}}", "camera.auto_exposure.target: required"},
      {"camera: {auto_exposure: {target: 0.4, time_constant_s: 0}}",
       "camera.auto_exposure.time_constant_s: expected a number in (0, 60], got 0"},
  };
  check_refusals(dir, cases);
}

TEST_CASE("a scenario's camera renders with OpenGL unless it asks for Cycles, whose settings are bounded") {
  TempDir dir("icgp-scenario");
  const Scenario opengl = load_scenario(dir.write("opengl.yaml", kMinimal), ICGP_MODELS_DIR);
  CHECK(opengl.camera.renderer == icgp::servo::RendererKind::kOpenGl);
  const Scenario cycles = load_scenario(
      dir.write("cycles.yaml", kMinimal + "camera: {renderer: cycles, cycles: {samples: 64, light_bounces: 2, "
                                          "threads: 1, timeout_s: 30}}\n"),
      ICGP_MODELS_DIR);
  CHECK(cycles.camera.renderer == icgp::servo::RendererKind::kCycles);
  CHECK(cycles.camera.cycles.samples == 64);
  CHECK(cycles.camera.cycles.light_bounces == 2);
  CHECK(cycles.camera.cycles.threads == 1);
  CHECK(cycles.camera.cycles.timeout_s == 30.0);

  const std::vector<std::pair<std::string, std::string>> cases = {
      {"camera: {renderer: raytracer}", "camera.renderer: expected one of opengl, cycles"},
      {"camera: {cycles: {samples: 0}}", "camera.cycles.samples: expected an integer in [1, 4096], got 0"},
      {"camera: {cycles: {light_bounces: -1}}", "camera.cycles.light_bounces: expected an integer in [0, 128], got -1"},
      {"camera: {cycles: {timeout_s: 0}}", "camera.cycles.timeout_s: expected a number in (0, 86400], got 0"},
      {"camera: {cycles: {denoise: true}}", "camera.cycles.denoise"},
  };
  check_refusals(dir, cases);
}
