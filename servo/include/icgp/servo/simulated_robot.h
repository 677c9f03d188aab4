// SPDX-License-Identifier: GPL-2.0-or-later
// The robots of the servo simulator: what moves when the control law commands a velocity.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/vs/vpServo.h>

#include "icgp/servo/calibration_errors.h"
#include "icgp/servo/scenario.h"

namespace icgp::servo {

/// A simulated robot carrying the camera (eye-in-hand) or the object (eye-to-hand). Moves
/// are integrated exactly over the step (no real-time threads): the same commands give the
/// same trajectory.
class SimulatedRobot {
 public:
  virtual ~SimulatedRobot() = default;

  /// The camera's pose in the world (wMc).
  virtual vpHomogeneousMatrix world_T_camera() const = 0;
  /// Eye-to-hand: the held object's pose in the world (wMo); nullopt for eye-in-hand robots.
  virtual std::optional<vpHomogeneousMatrix> world_T_held_object() const { return std::nullopt; }
  /// Grasp: the gripper's pose in the world (wMg = fMe(q) eMg) as the arm's kinematics give
  /// it; nullopt for robots without a gripper.
  virtual std::optional<vpHomogeneousMatrix> world_T_gripper() const { return std::nullopt; }
  /// Grasp: the gripper in the camera frame as the robot knows it, from its joint encoders,
  /// its kinematics and the camera's calibrated pose (cMg = cMf fMe(q) eMg, nominal); nullopt
  /// for robots without a gripper.
  virtual std::optional<vpHomogeneousMatrix> kinematic_camera_T_gripper() const { return std::nullopt; }

  /// The vpServo interaction type this robot is controlled with (vpServo::setServo).
  virtual vpServo::vpServoType servo_type() const = 0;
  /// Gives `task` the robot's Jacobians at the current configuration (set_cVe/set_eJe or
  /// set_cVf/set_fVe/set_eJe), before vpServo::computeControlLaw.
  virtual void update_jacobians(vpServo& task) const = 0;

  /// `velocity` (what vpServo::computeControlLaw returned: the camera twist for a
  /// free-flying camera, joint velocities for an arm) scaled down uniformly to the robot's
  /// velocity limits, when it exceeds them.
  virtual vpColVector saturated(const vpColVector& velocity) const = 0;
  /// Applies saturated(velocity) for `dt` seconds; an arm stops a joint at its limit.
  /// Returns the velocity actually applied.
  virtual vpColVector move(const vpColVector& velocity, double dt) = 0;

  /// Number of moves in which an arm joint was stopped at its limit.
  virtual int joint_limit_stops() const { return 0; }
  virtual std::string name() const = 0;
};

/// The robot of `scenario`, at its start: the free-flying camera at the world origin, an
/// arm at ArmSpec::initial_joints. Eye-to-hand, the fixed camera is placed where it sees
/// the held object at the scenario's initial_cMo. Grasp, the object stands at
/// GraspSpec::start_gMo from the gripper and the fixed camera sees it at initial_cMo. With
/// `truth`, the arm's joints and camera are truly where it says (its joint offsets and
/// camera error): the robot moves and shows the camera there, while its Jacobians, and the
/// placements above, take the nominal calibration. Without, the calibration is exact.
std::unique_ptr<SimulatedRobot> make_robot(const Scenario& scenario, const TrueCalibration& truth);
std::unique_ptr<SimulatedRobot> make_robot(const Scenario& scenario);

/// Where the object is in the world at the start, so that the camera sees it at
/// initial_cMo: wMc(start) * initial_cMo for eye-in-hand and grasp robots, the held
/// object's pose for eye-to-hand.
vpHomogeneousMatrix initial_world_T_object(const Scenario& scenario, const SimulatedRobot& robot);

}  // namespace icgp::servo
