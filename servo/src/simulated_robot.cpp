// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/servo/simulated_robot.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/robot/vpSimulatorCamera.h>
#include <visp3/robot/vpViper850.h>

#include "icgp/visp/conversions.h"

namespace icgp::servo {
namespace {

// Largest factor in (0, 1] that brings `norm` down to `limit` (1 when already within it).
double scale_to_limit(double norm, double limit) { return norm > limit ? limit / norm : 1.0; }

// ---------------------------------------------------------------------------------------
// Free-flying camera: ViSP's vpSimulatorCamera, which applies wMc <- wMc * exp(v dt)
// (vpExponentialMap::direct over the sampling time), i.e. the exact motion of a twist held
// constant during the step.
class FreeFlyingCamera final : public SimulatedRobot {
 public:
  explicit FreeFlyingCamera(const ControlSpec& control) : control_(control) {
    simulator_.setPosition(vpHomogeneousMatrix());  // world origin
    // vpRobot saturates each component separately (changing the direction); our uniform
    // norm scaling below comes first, so ViSP's limits are only set loose enough never to
    // trigger (component <= norm <= limit, with a margin for rounding).
    simulator_.setMaxTranslationVelocity(2.0 * control_.max_linear_velocity);
    simulator_.setMaxRotationVelocity(2.0 * control_.max_angular_velocity);
  }

  vpHomogeneousMatrix world_T_camera() const override { return simulator_.getPosition(); }
  vpServo::vpServoType servo_type() const override { return vpServo::EYEINHAND_CAMERA; }
  // The control law gives the camera twist directly: no Jacobian to set.
  void update_jacobians(vpServo&) const override {}

  vpColVector saturated(const vpColVector& velocity) const override {
    if (velocity.size() != 6) throw std::invalid_argument("free-flying camera: expected a 6-vector twist");
    const double linear = std::sqrt(velocity[0] * velocity[0] + velocity[1] * velocity[1] + velocity[2] * velocity[2]);
    const double angular = std::sqrt(velocity[3] * velocity[3] + velocity[4] * velocity[4] + velocity[5] * velocity[5]);
    // One factor for both parts, so the direction of the screw motion is kept.
    const double s = std::min(scale_to_limit(linear, control_.max_linear_velocity),
                              scale_to_limit(angular, control_.max_angular_velocity));
    return velocity * s;
  }

  vpColVector move(const vpColVector& velocity, double dt) override {
    const vpColVector applied = saturated(velocity);
    simulator_.setSamplingTime(dt);
    simulator_.setVelocity(vpRobot::CAMERA_FRAME, applied);
    return applied;
  }

  std::string name() const override { return "free-flying camera"; }

 private:
  ControlSpec control_;
  vpSimulatorCamera simulator_;
};

// ---------------------------------------------------------------------------------------
// Viper 850 arm: ViSP's kinematic model only (vpViper850), with the joint vector kept here
// and integrated explicitly, so runs are deterministic (vpSimulatorViper850 runs its own
// real-time thread). World = robot base frame f.
//
// Tool: the model's default (vpViper850() calls init() with TOOL_PTGREY_FLEA2_CAMERA), a
// calibrated camera on the flange: eMc = ~4.6 cm off axis, rotated ~-90.8 deg about the
// flange z, optical axis along the flange z. Its non-identity eMc makes cVe matter, so a
// wrong twist transform would show in the tests.
class Viper850Arm : public SimulatedRobot {
 public:
  Viper850Arm(const Scenario& scenario, const TrueCalibration& truth)
      : joint_offsets_(truth.joint_offsets), control_(scenario.control), q_(6) {
    for (unsigned i = 0; i < 6; ++i) q_[i] = scenario.arm.initial_joints[i];
    q_min_ = model_.getJointMin();
    q_max_ = model_.getJointMax();
    // A start outside the limits would be silently moved by clamping: refuse it instead.
    for (unsigned i = 0; i < 6; ++i)
      if (q_[i] < q_min_[i] || q_[i] > q_max_[i])
        throw std::invalid_argument("Viper 850: initial joint " + std::to_string(i + 1) + " (" +
                                    std::to_string(vpMath::deg(q_[i])) + " deg) is outside its limits [" +
                                    std::to_string(vpMath::deg(q_min_[i])) + ", " +
                                    std::to_string(vpMath::deg(q_max_[i])) + "] deg");
  }

  vpColVector saturated(const vpColVector& velocity) const override {
    if (velocity.size() != 6) throw std::invalid_argument("Viper 850: expected 6 joint velocities");
    double largest = 0.0;
    for (unsigned i = 0; i < 6; ++i) largest = std::max(largest, std::abs(velocity[i]));
    return velocity * scale_to_limit(largest, control_.max_joint_velocity);
  }

  vpColVector move(const vpColVector& velocity, double dt) override {
    const vpColVector commanded = saturated(velocity);
    const vpColVector q_before = q_;
    q_ += commanded * dt;
    if (clamp_to_limits()) ++joint_limit_stops_;
    // A joint stopped at its limit moved less than commanded: report what was applied.
    return dt > 0.0 ? vpColVector((q_ - q_before) / dt) : commanded;
  }

  int joint_limit_stops() const override { return joint_limit_stops_; }

 protected:
  /// The flange where it truly is: at the joint angles the encoders report plus their offsets.
  vpHomogeneousMatrix f_T_e() const {
    vpColVector q = q_;
    for (unsigned i = 0; i < 6; ++i) q[i] += joint_offsets_[static_cast<int>(i)];
    vpHomogeneousMatrix fMe;
    model_.get_fMe(q, fMe);
    return fMe;
  }
  /// The flange where the robot's controller believes it is, from its encoders.
  vpHomogeneousMatrix nominal_f_T_e() const {
    vpHomogeneousMatrix fMe;
    model_.get_fMe(q_, fMe);
    return fMe;
  }
  /// The Jacobian the controller computes, at the encoders' joint angles.
  vpMatrix e_J_e() const {
    vpMatrix eJe;
    model_.get_eJe(q_, eJe);
    return eJe;
  }

  vpViper850 model_;

 private:
  // Clamps q to the software joint limits; true when a joint had to be stopped.
  bool clamp_to_limits() {
    bool stopped = false;
    for (unsigned i = 0; i < 6; ++i) {
      const double clamped = std::clamp(q_[i], q_min_[i], q_max_[i]);
      stopped = stopped || clamped != q_[i];
      q_[i] = clamped;
    }
    return stopped;
  }

  Eigen::Matrix<double, 6, 1> joint_offsets_;
  ControlSpec control_;
  vpColVector q_, q_min_, q_max_;
  int joint_limit_stops_ = 0;
};

// Camera on the flange: wMc = fMe(q) eMc; camera twist = cVe eJe qdot.
class Viper850EyeInHand final : public Viper850Arm {
 public:
  Viper850EyeInHand(const Scenario& scenario, const TrueCalibration& truth)
      : Viper850Arm(scenario, truth), camera_error_(to_homogeneous_matrix(truth.camera_error)) {}

  // The camera where it truly is on the flange; the Jacobians take the calibrated eMc.
  vpHomogeneousMatrix world_T_camera() const override {
    vpHomogeneousMatrix eMc;
    model_.get_eMc(eMc);
    return f_T_e() * eMc * camera_error_;
  }
  vpServo::vpServoType servo_type() const override { return vpServo::EYEINHAND_L_cVe_eJe; }
  void update_jacobians(vpServo& task) const override {
    vpVelocityTwistMatrix cVe;
    model_.get_cVe(cVe);  // from the constant cMe
    task.set_cVe(cVe);
    task.set_eJe(e_J_e());
  }
  std::string name() const override { return "Viper 850 (eye-in-hand)"; }

 private:
  vpHomogeneousMatrix camera_error_;
};

// Fixed camera watching the object held at eMo: wMo = fMe(q) eMo. The camera is placed once,
// where it sees the object at initial_cMo with the arm at its initial joints.
class Viper850EyeToHand final : public Viper850Arm {
 public:
  Viper850EyeToHand(const Scenario& scenario, const TrueCalibration& truth)
      : Viper850Arm(scenario, truth), eMo_(to_homogeneous_matrix(scenario.arm.eMo)) {
    nominal_world_T_camera_ = nominal_f_T_e() * eMo_ * to_homogeneous_matrix(scenario.initial_cMo).inverse();
    world_T_camera_ = nominal_world_T_camera_ * to_homogeneous_matrix(truth.camera_error);
  }

  vpHomogeneousMatrix world_T_camera() const override { return world_T_camera_; }
  std::optional<vpHomogeneousMatrix> world_T_held_object() const override { return f_T_e() * eMo_; }
  vpServo::vpServoType servo_type() const override { return vpServo::EYETOHAND_L_cVf_fVe_eJe; }
  // vpServo builds J = -L cVf fVe eJe for eye-to-hand (the minus: the features change as if
  // the camera moved opposite to the object). cVf and fVe are full twist transforms
  // (rotation and the [t]x R coupling), so cVf fVe = cVe: the end-effector twist eJe qdot
  // (at e, in e) seen in the camera frame.
  void update_jacobians(vpServo& task) const override {
    task.set_cVf(nominal_world_T_camera_.inverse());  // cMf as calibrated, constant
    task.set_fVe(nominal_f_T_e());
    task.set_eJe(e_J_e());
  }
  std::string name() const override { return "Viper 850 (eye-to-hand)"; }

 private:
  vpHomogeneousMatrix eMo_;
  vpHomogeneousMatrix nominal_world_T_camera_;  ///< where the calibration puts the camera
  vpHomogeneousMatrix world_T_camera_;          ///< where it is
};

// A gripper on the flange (eMg), a fixed camera and an object standing still: the PBVS
// law treats the gripper as vpServo's "camera", the frame whose pose to the object (gMo)
// it servoes. Its twist is gVe eJe qdot, as the eye-in-hand camera's is cVe eJe qdot.
class Viper850Grasp final : public Viper850Arm {
 public:
  Viper850Grasp(const Scenario& scenario, const TrueCalibration& truth)
      : Viper850Arm(scenario, truth), eMg_(to_homogeneous_matrix(grasp_of(scenario).eMg)) {
    const GraspSpec& grasp = grasp_of(scenario);
    nominal_world_T_camera_ = nominal_f_T_e() * eMg_ * to_homogeneous_matrix(grasp.start_gMo) *
                              to_homogeneous_matrix(scenario.initial_cMo).inverse();
    world_T_camera_ = nominal_world_T_camera_ * to_homogeneous_matrix(truth.camera_error);
  }

  vpHomogeneousMatrix world_T_camera() const override { return world_T_camera_; }
  std::optional<vpHomogeneousMatrix> world_T_gripper() const override { return f_T_e() * eMg_; }
  std::optional<vpHomogeneousMatrix> kinematic_camera_T_gripper() const override {
    return nominal_world_T_camera_.inverse() * nominal_f_T_e() * eMg_;
  }
  vpServo::vpServoType servo_type() const override { return vpServo::EYEINHAND_L_cVe_eJe; }
  void update_jacobians(vpServo& task) const override {
    task.set_cVe(vpVelocityTwistMatrix(eMg_.inverse()));  // gVe, from the constant gMe
    task.set_eJe(e_J_e());
  }
  std::string name() const override { return "Viper 850 (gripper on the flange, fixed camera)"; }

 private:
  static const GraspSpec& grasp_of(const Scenario& scenario) {
    if (!scenario.grasp) throw std::invalid_argument("Viper 850 grasp: the scenario has no gripper (GraspSpec)");
    return *scenario.grasp;
  }
  vpHomogeneousMatrix eMg_;
  vpHomogeneousMatrix nominal_world_T_camera_;  ///< where the calibration puts the camera
  vpHomogeneousMatrix world_T_camera_;          ///< where it is
};

}  // namespace

std::unique_ptr<SimulatedRobot> make_robot(const Scenario& scenario, const TrueCalibration& truth) {
  switch (scenario.robot) {
    case RobotKind::kFreeFlyingCamera:
      return std::make_unique<FreeFlyingCamera>(scenario.control);
    case RobotKind::kViper850EyeInHand:
      return std::make_unique<Viper850EyeInHand>(scenario, truth);
    case RobotKind::kViper850EyeToHand:
      return std::make_unique<Viper850EyeToHand>(scenario, truth);
    case RobotKind::kViper850Grasp:
      return std::make_unique<Viper850Grasp>(scenario, truth);
  }
  throw std::invalid_argument("make_robot: unknown robot kind");
}

std::unique_ptr<SimulatedRobot> make_robot(const Scenario& scenario) {
  return make_robot(scenario, nominal_calibration(scenario));
}

vpHomogeneousMatrix initial_world_T_object(const Scenario& scenario, const SimulatedRobot& robot) {
  if (const auto held = robot.world_T_held_object()) return *held;
  return robot.world_T_camera() * to_homogeneous_matrix(scenario.initial_cMo);
}

}  // namespace icgp::servo
