// SPDX-License-Identifier: GPL-2.0-or-later
// The tracker's side of a servo step, shared by the closed loop (run_servo) and the
// open-loop replay of its camera path (replay_camera_path), so that both feed a tracker the
// same calls on the same frames.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <visp3/core/vpHomogeneousMatrix.h>

#include "icgp/servo/pose_estimator.h"
#include "icgp/servo/rgbd_simulator.h"
#include "icgp/servo/scenario.h"
#include "icgp/servo/simulated_robot.h"

namespace icgp::servo {

/// The pose the control law drives: the camera's to the object (cMo), or in a grasp the
/// gripper's to the object, gMo = cMg^-1 cMo.
vpHomogeneousMatrix servoed_pose(const vpHomogeneousMatrix& cMo, const std::optional<vpHomogeneousMatrix>& cMg);

/// The goal as the cell's own camera and tracker see it (ControlSpec::taught_by_showing):
/// the camera (or, eye-to-hand, the object the arm holds) put at the scenario's desired
/// pose `desired_cMo` at time 0, and the pose the tracker measures there. A tracker that
/// detects finds the object itself; the others start at the truth, as they do in the loop.
/// It takes a capture of `simulator`, as the loop's first. Throws std::runtime_error when
/// detection finds nothing there.
vpHomogeneousMatrix shown_goal(const SimulatedRobot& robot, RgbdSimulator& simulator, PoseEstimator& estimator,
                               const vpHomogeneousMatrix& desired_cMo, bool by_detection);

/// A tracker fed frame after frame: it finds the object by detection (TrackerSpec::
/// init_by_detection, for a tracker that detects) or starts at the true pose, tracks, and
/// after a loss restarts at the last pose it did not report lost, unless it searches again
/// itself (PoseEstimator::recovers).
class TrackerInLoop {
 public:
  /// In a grasp, the gripper's pose the arm's kinematics give, for a tracker that does not
  /// follow the gripper; empty elsewhere.
  using KinematicGripper = std::function<std::optional<vpHomogeneousMatrix>()>;

  /// `goal`: the servoed pose the loop works toward; of a symmetric object's equivalent
  /// detections, the one nearest to it is taken.
  TrackerInLoop(PoseEstimator& estimator, const TrackerSpec& spec, const vpHomogeneousMatrix& goal,
                KinematicGripper kinematic_cMg);

  /// Whether the tracker starts at the truth on a capture of its own (start_at_truth)
  /// before the loop, rather than by detecting in the loop's frames.
  bool starts_from_truth() const { return started_; }
  /// Starts the tracker at `first`'s true poses (starts_from_truth()).
  void start_at_truth(const RgbdCapture& first);

  /// Gives the tracker a frame it is free to take (not dropped, not skipped): a detection
  /// until the object is found, then tracking. Returns the estimate, as estimate() does.
  const PoseEstimate& take(const RgbdCapture& capture);

  /// What the tracker said on the last frame it took (a default estimate before the first).
  const PoseEstimate& estimate() const { return estimate_; }
  /// The object has been found (or the tracker started at the truth).
  bool started() const { return started_; }
  /// The tracker's last reason for a loss, empty when it gave none.
  const std::string& last_why_lost() const { return last_why_lost_; }

 private:
  void detect(const RgbdCapture& capture);
  void track(const RgbdCapture& capture);
  std::optional<vpHomogeneousMatrix> kinematic_cMg() const;

  PoseEstimator& estimator_;
  vpHomogeneousMatrix goal_;
  KinematicGripper kinematic_cMg_;
  bool started_;
  PoseEstimate estimate_;
  vpHomogeneousMatrix trusted_cMo_;                 ///< the last pose the tracker did not report lost
  std::optional<vpHomogeneousMatrix> trusted_cMg_;  ///< the same for the gripper (grasp)
  std::string last_why_lost_;
};

}  // namespace icgp::servo
