// SPDX-License-Identifier: GPL-2.0-or-later
// The values of the realistic profile and where they come from (docs/servo.md, "Profiles",
// gives the references in full).
#include "icgp/servo/scenario_profile.h"

namespace icgp::servo {

const std::vector<std::pair<std::string, Profile>>& profile_names() {
  static const std::vector<std::pair<std::string, Profile>> names = {{"realistic", Profile::kRealistic},
                                                                     {"ideal", Profile::kIdeal}};
  return names;
}

std::vector<ProfileField> profile_fields(Profile profile, RobotKind robot) {
  if (profile == Profile::kIdeal) {
    // The exact world: every error source at zero (the scenario's defaults), and success
    // judged as closely as a perfect cell allows.
    return {{"stop.translation_mm", "1", ""}, {"stop.rotation_deg", "0.1", ""}};
  }
  std::vector<ProfileField> fields = {
      // Two frame periods at 30 Hz from exposure to the robot's interface (readout, USB
      // transfer, the control computation), with a few ms of scheduling jitter.
      {"camera.latency_ms", "67", ""},
      {"camera.jitter.distribution", "normal", "camera.jitter"},
      {"camera.jitter.ms", "5", "camera.jitter"},
      // The tracker's time counts. A fixed time keeps batches reproducible on any machine:
      // 10 ms, a third of a frame period (icgp measures 2-3 ms per frame on the default
      // scenario here, detection aside).
      {"tracker.timing", "real", ""},
      {"tracker.compute_ms", "10", "tracker.timing"},
      // A velocity interface that smooths the command over 30 ms (UR's servoj lookahead is
      // 0.03-0.2 s).
      {"robot_response.lag_ms", "30", ""},
      // Intrinsics from a checkerboard calibration or a sensor's factory values: 0.5 % focal
      // length, 1.5 px principal point; the depth camera's extrinsics within 1 mm, 0.2 deg.
      {"calibration_error.focal_percent", "0.5", ""},
      {"calibration_error.principal_point_px", "1.5", ""},
      {"calibration_error.depth_T_color.translation_mm", "1", ""},
      {"calibration_error.depth_T_color.rotation_deg", "0.2", ""},
      // Half of a simple lens's cos⁴ falloff: 26 % darker in the corners of the default
      // 640 x 480 image at 600 px focal length, as compact RGB-D colour lenses show.
      {"camera.vignetting", "0.5", ""},
      // The object is half a percent larger than its CAD model (manufacturing, a scan).
      {"object.scale_error_percent", "0.5", ""},
      // A cell cannot be judged more closely than it knows itself: 5 mm and 1 deg hold the
      // sum of the errors above at a working distance of 0.3-0.5 m (docs/servo.md).
      {"stop.translation_mm", "5", ""},
      {"stop.rotation_deg", "1", ""},
  };
  if (robot == RobotKind::kFreeFlyingCamera) {
    // libfranka's Cartesian limits (rate_limiting.h): 13 m/s², 25 rad/s².
    fields.push_back({"robot_response.max_linear_acceleration", "13", ""});
    fields.push_back({"robot_response.max_angular_acceleration_deg", "1432", ""});
  } else {
    // libfranka's lowest joint acceleration limit, 7.5 rad/s²; a hand-eye calibration within
    // 1.5 mm and 0.3 deg; joint zero offsets of a calibrated arm.
    fields.push_back({"robot_response.max_joint_acceleration_deg", "430", ""});
    fields.push_back({"calibration_error.hand_eye.translation_mm", "1.5", ""});
    fields.push_back({"calibration_error.hand_eye.rotation_deg", "0.3", ""});
    fields.push_back({"calibration_error.joint_offsets_deg", "0.02", ""});
  }
  return fields;
}

}  // namespace icgp::servo
