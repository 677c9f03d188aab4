// SPDX-License-Identifier: GPL-2.0-or-later
// The closed loop: render -> track -> control -> move, step after step, with its log.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>

#include "icgp/servo/pose_estimator.h"
#include "icgp/servo/rgbd_simulator.h"
#include "icgp/servo/scenario.h"

namespace icgp::servo {

/// One step of a run. Errors are translation (metres) and rotation (radians), of the
/// servoed pose: cMo, or in a grasp gMo (the object in the gripper frame).
struct ServoStep {
  double time = 0.0;                  ///< seconds of simulated time at the capture
  vpHomogeneousMatrix cMo_true;       ///< ground truth at the capture
  vpHomogeneousMatrix cMo_estimated;  ///< what the tracker said
  double servo_t = 0.0, servo_r = 0.0;  ///< true servoed pose to the desired pose
  double track_t = 0.0, track_r = 0.0;  ///< estimated servoed pose to the true one
  vpColVector velocity;               ///< applied: camera twist (v, ω) or joint velocities
  double servo_error_norm = 0.0;      ///< |s - s*| of the control law
  bool lost = false;                  ///< the tracker reported lost
  bool safety_stop = false;           ///< the commanded velocity was zeroed
  bool dropped = false;               ///< the sensor lost this frame
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
  double median_track_ms = 0.0;
  double steps_per_s = 0.0;  ///< wall-clock rate of the whole loop (render + track + control)
  int safety_stops = 0;      ///< times the tracker was lost and the robot stopped
  bool recovered = true;     ///< after the last safety stop, tracking resumed (not lost at the end)
  int joint_limit_stops = 0;
  /// A stop was requested (icgp::request_stop, SIGINT) and the run ended at the step it was
  /// seen, before converging or reaching its time limit.
  bool interrupted = false;
  std::vector<ServoStep> steps;
};

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
};

/// Runs `scenario` to convergence or to its time limit: each step captures the RGB-D
/// frame at the robot's pose, tracks it, computes the control law from the estimated pose
/// and moves the robot for one frame period. When the tracker reports lost, the commanded
/// velocity is zero (safety stop) and the tracker restarts at the last pose it did not
/// report lost, until it tracks again. The run converges when the servo
/// error as the tracker estimates it stays within the scenario's thresholds for its settle
/// time, after any target motion has ended. A stop request (icgp::stop_requested()) ends the
/// run after the current step, marked interrupted. Throws ScenarioError when the scenario's
/// run length is out of bounds (check_run_length).
ServoResult run_servo(const Scenario& scenario, const ServoRunOptions& options = {});

/// The start offset of trial `trial` of a batch seeded with `seed`: a translation and a
/// rotation of uniformly random direction and uniformly random size up to the scenario's
/// TrialSpec, applied in the camera frame (initial cMo becomes offset * initial_cMo).
Pose perturbed_start(const TrialSpec& trials, unsigned seed, int trial);

}  // namespace icgp::servo
