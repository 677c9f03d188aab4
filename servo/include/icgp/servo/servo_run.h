// SPDX-License-Identifier: GPL-2.0-or-later
// The closed loop: render -> track -> control -> move, step after step, with its log.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMatrix.h>

#include "icgp/servo/pose_estimator.h"
#include "icgp/servo/rgbd_simulator.h"
#include "icgp/servo/scenario.h"

namespace icgp::servo {

/// One step of a run. Errors are translation (metres) and rotation (radians), of the
/// servoed pose: cMo, or in a grasp gMo (the object in the gripper frame).
struct ServoStep {
  double time = 0.0;                  ///< seconds of simulated time at the capture
  /// Where the colour camera truly was in the world at the capture (also for a frame the
  /// sensor dropped or the tracker skipped): the camera path that replay_camera_path
  /// renders again.
  vpHomogeneousMatrix wMc_true;
  vpHomogeneousMatrix cMo_true;       ///< ground truth at the capture
  vpHomogeneousMatrix cMo_estimated;  ///< what the tracker said
  double servo_t = 0.0, servo_r = 0.0;  ///< true servoed pose to the desired pose
  /// Estimated servoed pose to the true one; NaN while the object is out of the scene
  /// (ObjectSpec::removed_for), as the servo error, and before the tracker first found it.
  double track_t = 0.0, track_r = 0.0;
  /// Followed by the robot at the end of the step's frame period: camera twist (v, ω) or
  /// joint velocities.
  vpColVector velocity;
  /// |s - s*| of the scenario's control law (vpServo); NaN when a control law given in code
  /// (ServoRunOptions::control_law) computed the velocity, as it has no features s; 0 at a
  /// safety stop, where no law runs.
  double servo_error_norm = 0.0;
  bool lost = false;                  ///< the tracker reported lost
  bool safety_stop = false;           ///< the commanded velocity was zeroed
  bool dropped = false;               ///< the sensor lost this frame
  bool skipped = false;  ///< the frame came while the tracker was busy (TrackerSpec::real_timing)
  /// Seconds from the frame's exposure to the arrival at the robot of the command computed
  /// from it; NaN when none was (a skipped frame).
  double command_delay = 0.0;
  double render_ms = 0.0, track_ms = 0.0, control_ms = 0.0;  ///< wall time of each part
};

/// The outcome of one run.
struct ServoResult {
  std::string scenario;
  std::string tracker;
  unsigned seed = 0;
  bool converged = false;       ///< the estimated servo error settled below the thresholds
  int converged_step = -1;      ///< first step of the settled stretch, -1 when never
  double converged_time = -1.0;  ///< its simulated time, seconds
  double final_t = 0.0, final_r = 0.0;  ///< true pose to the desired pose at the end
  double mean_track_t = 0.0, max_track_t = 0.0;  ///< tracker error over the run, metres
  double mean_track_r = 0.0, max_track_r = 0.0;  ///< radians
  /// The largest tracker error on the frames the tracker took and vouched for (not lost):
  /// a far-off pose here is one the loop would have servoed on. The overall maximum also
  /// counts what a lost tracker holds while the object moves on.
  double max_vouched_track_t = 0.0, max_vouched_track_r = 0.0;
  double median_track_ms = 0.0;
  double steps_per_s = 0.0;  ///< wall-clock rate of the whole loop (render + track + control)
  int safety_stops = 0;      ///< times the tracker was lost and the robot stopped
  bool recovered = true;     ///< after the last safety stop, tracking resumed (not lost at the end)
  /// Lost at the end: the tracker's last reason (why the object was never found, say);
  /// empty otherwise, or when the tracker gave none.
  std::string lost_reason;
  int joint_limit_stops = 0;  ///< frame periods in which an arm joint was stopped at its limit
  /// A stop was requested (icgp::request_stop, SIGINT) and the run ended at the step it was
  /// seen, before converging or reaching its time limit.
  bool interrupted = false;
  std::vector<ServoStep> steps;
};

/// What a control law given in code (ServoRunOptions::control_law) is told at a step.
struct ControlState {
  double time = 0.0;  ///< simulated seconds at the step's capture
  /// The servoed pose as the tracker estimates it: cMo (the object in the camera frame), or
  /// in a grasp gMo (the object in the gripper frame), metres.
  vpHomogeneousMatrix pose;
  vpHomogeneousMatrix desired;  ///< where the law must bring `pose`: desired_cMo, or desired_gMo
  RobotKind robot = RobotKind::kFreeFlyingCamera;
  /// How many values the law returns (velocity_size(robot)).
  unsigned velocity_size = 6;
  /// 6 x velocity_size: the twist (v, ω) the returned velocity gives the frame the law
  /// drives, at the current configuration: the identity for the free-flying camera (its
  /// own twist); cVe·eJe for the eye-in-hand arm (the camera's twist in its frame); gVe·eJe
  /// in a grasp (the gripper's twist in its frame); cVf·fVe·eJe eye-to-hand (the end
  /// effector's twist, which moves the object, in the fixed camera's frame). A law that
  /// computes a twist ξ for a Viper 850 returns J⁺ξ (eye-to-hand: of the object's relative
  /// motion, see vpServo::EYETOHAND_L_cVf_fVe_eJe).
  vpMatrix jacobian;
};

/// A control law given in code: the velocity the robot takes (see velocity_size), from the
/// step's state. It replaces the scenario's vpServo law at every step where the tracker did
/// not report lost; the robot saturates its output as it does vpServo's.
using ControlLaw = std::function<vpColVector(const ControlState&)>;

/// The number of velocity values `robot` takes, the same as vpServo's output for it:
/// * free-flying camera: 6, the camera twist (v, ω) in the current camera frame (m/s,
///   rad/s), applied as wMc <- wMc exp([v, ω] dt); scaled down uniformly when |v| or |ω|
///   exceeds control.max_linear_velocity or max_angular_velocity;
/// * Viper 850 (eye-in-hand, eye-to-hand, grasp): 6, the joint velocities q̇1..q̇6 (rad/s),
///   scaled down uniformly when one exceeds control.max_joint_velocity; a joint stops at
///   its limit.
unsigned velocity_size(RobotKind robot);

struct ServoRunOptions {
  /// Moves the scenario's start (batch trials): the run starts at start_offset * initial_cMo,
  /// or in a grasp at start_offset * start_gMo (the camera and the object stay, the gripper
  /// starts elsewhere).
  Pose start_offset;
  unsigned seed = 1;
  bool progress = true;  ///< a progress line on stderr
  /// Called after every step with the capture the tracker saw (overlay video, display).
  std::function<void(const RgbdCapture&, const ServoStep&)> on_step;
  /// Replaces the scenario's tracker (tests: a tracker that fails on purpose).
  std::function<std::unique_ptr<PoseEstimator>(const RgbdSimulator&)> make_estimator;
  /// Replaces the scenario's control law (empty: the scenario's vpServo law). It is not
  /// called at a safety stop: the velocity is zero then, whatever the law. A velocity of
  /// another size than velocity_size(robot), or not finite, ends the run with
  /// std::invalid_argument.
  ControlLaw control_law;
};

/// Runs `scenario` to convergence or to its time limit: each step captures the RGB-D
/// frame at the robot's pose, tracks it, computes the control law (the scenario's, or
/// options.control_law) from the estimated pose and moves the robot for one frame period.
/// The command reaches the robot after the scenario's latency (and jitter, and the tracker's
/// time with real timing; a frame that comes while the tracker is busy is skipped), the
/// robot follows it through its response (ResponseSpec), and the cell's true calibration is
/// drawn from options.seed (draw_true_calibration); the defaults are the ideal loop. When
/// the tracker reports lost, the commanded
/// velocity is zero (safety stop) and the tracker restarts at the last pose it did not
/// report lost, until it tracks again. The run converges when the servo
/// error as the tracker estimates it stays within the scenario's thresholds for its settle
/// time, after any target motion has ended. A stop request (icgp::stop_requested()) ends the
/// run after the current step, marked interrupted. Throws ScenarioError when the scenario's
/// run length is out of bounds (check_run_length). Exceptions of options.on_step and
/// options.control_law end the run and go on to the caller as they were thrown.
ServoResult run_servo(const Scenario& scenario, const ServoRunOptions& options = {});

/// The start offset of trial `trial` of a batch seeded with `seed`: a translation and a
/// rotation of uniformly random direction and uniformly random size up to the scenario's
/// TrialSpec, applied in the camera frame (initial cMo becomes offset * initial_cMo).
Pose perturbed_start(const TrialSpec& trials, unsigned seed, int trial);

}  // namespace icgp::servo
