// SPDX-License-Identifier: GPL-2.0-or-later
// The robot's low-level controller: the velocity a robot follows, answering the commanded one.
#pragma once

#include <utility>
#include <visp3/core/vpColVector.h>

#include "icgp/servo/scenario.h"
#include "icgp/servo/simulated_robot.h"

namespace icgp::servo {

/// Follows commanded velocities the way a robot's own controller does (ResponseSpec): the
/// followed velocity approaches the command, saturated to the robot's velocity limits,
/// through a first-order lag, and changes no faster than the acceleration limits allow.
/// Integrated in steps of at most a millisecond, each moving the robot at the step's mean
/// velocity (exact for the lag alone and for a constant acceleration). An immediate response
/// moves the robot at the command itself, in one move: the ideal robot.
class RobotResponse {
 public:
  /// A robot of `kind` at rest, taking velocities of velocity_size(kind) values.
  RobotResponse(const ResponseSpec& spec, RobotKind kind);

  /// Moves `robot` for `duration` seconds while `command` is held. Returns the velocity the
  /// robot follows at the end (an immediate response: what the robot applied).
  vpColVector follow(SimulatedRobot& robot, const vpColVector& command, double duration);

 private:
  /// The followed velocity `step` seconds on from `from`, towards `target`, and the mean
  /// velocity over that step. The acceleration limits hold for the linear and angular parts
  /// of a camera twist each as a vector, and for each joint of an arm.
  std::pair<vpColVector, vpColVector> advance(const vpColVector& from, const vpColVector& target, double step) const;

  ResponseSpec spec_;
  RobotKind kind_;
  vpColVector velocity_;  ///< followed now
};

}  // namespace icgp::servo
