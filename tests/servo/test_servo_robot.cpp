// SPDX-License-Identifier: GPL-2.0-or-later
// The simulated robots of the servo simulator, checked against independent truth: ViSP's
// exponential map and Viper 850 forward kinematics, finite differences of the poses, and
// closed PBVS loops (vpServo) built from the true camera-object pose.
#include <catch2/catch.hpp>
#include <functional>

#include <cmath>
#include <visp3/core/vpExponentialMap.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/robot/vpViper850.h>
#include <visp3/visual_features/vpFeatureThetaU.h>
#include <visp3/visual_features/vpFeatureTranslation.h>
#include <visp3/vs/vpServo.h>

#include "icgp/servo/simulated_robot.h"
#include "icgp/visp/conversions.h"

using namespace icgp::servo;

namespace {

constexpr double kDt = 1.0 / 30.0;

// Joints (deg) well away from singularities: elbow bent ~70 deg from its stretched-out
// singularity (q3 ~ 102 deg), wrist at q5 = 70 deg, wrist centre far from the joint 1 axis.
// The camera is ~0.41 m above the base plane, 0.71 m out, looking down.
const double kArmJointsDeg[6] = {0, -60, 170, 0, 70, 0};

vpColVector joints_rad(const double (&deg)[6]) {
  vpColVector q(6);
  for (unsigned i = 0; i < 6; ++i) q[i] = vpMath::rad(deg[i]);
  return q;
}

vpColVector vec6(double a, double b, double c, double d, double e, double f) {
  vpColVector v(6);
  v[0] = a, v[1] = b, v[2] = c, v[3] = d, v[4] = e, v[5] = f;
  return v;
}

vpHomogeneousMatrix make_pose(double tx, double ty, double tz, double rx_deg, double ry_deg, double rz_deg) {
  return vpHomogeneousMatrix(vpTranslationVector(tx, ty, tz),
                             vpThetaUVector(vpMath::rad(rx_deg), vpMath::rad(ry_deg), vpMath::rad(rz_deg)));
}

Scenario make_scenario(RobotKind robot, const vpColVector& q0 = joints_rad(kArmJointsDeg)) {
  Scenario s;
  s.robot = robot;
  for (unsigned i = 0; i < 6; ++i) s.arm.initial_joints[i] = q0[i];
  s.arm.eMo = icgp::to_pose(make_pose(0.0, 0.0, 0.1, 0, 0, 0));
  // The camera sees the object 0.35 m ahead, a little off-centre and tilted.
  s.initial_cMo = icgp::to_pose(make_pose(0.01, -0.02, 0.35, 5, -8, 20));
  return s;
}

// Translation (m) and rotation (rad) between two poses.
double translation_between(const vpHomogeneousMatrix& a, const vpHomogeneousMatrix& b) {
  return (a.inverse() * b).getTranslationVector().frobeniusNorm();
}
double rotation_between(const vpHomogeneousMatrix& a, const vpHomogeneousMatrix& b) {
  return vpThetaUVector((a.inverse() * b).getRotationMatrix()).getTheta();
}
bool poses_equal(const vpHomogeneousMatrix& a, const vpHomogeneousMatrix& b, double tol = 1e-12) {
  return translation_between(a, b) < tol && rotation_between(a, b) < tol;
}

double norm3(const vpColVector& v, unsigned first) {
  return std::sqrt(v[first] * v[first] + v[first + 1] * v[first + 1] + v[first + 2] * v[first + 2]);
}

// The object's pose in the world: held by the arm (eye-to-hand) or fixed.
vpHomogeneousMatrix world_T_object(const SimulatedRobot& robot, const vpHomogeneousMatrix& fixed_wMo) {
  return robot.world_T_held_object().value_or(fixed_wMo);
}

// True camera-object pose from the robot's state.
vpHomogeneousMatrix camera_T_object(const SimulatedRobot& robot, const vpHomogeneousMatrix& fixed_wMo) {
  return robot.world_T_camera().inverse() * world_T_object(robot, fixed_wMo);
}

// Twist (in the frame of `before`, per second) that moves `before` to `after` in dt.
vpColVector measured_twist(const vpHomogeneousMatrix& before, const vpHomogeneousMatrix& after, double dt) {
  return vpExponentialMap::inverse(before.inverse() * after, dt);
}

struct PbvsResult {
  int steps = 0;
  double translation = 0.0;  // m, servoed frame to its desired pose
  double rotation = 0.0;     // rad
  bool converged = false;
};

// PBVS with vpServo on the true pose of the servoed frame c (the camera, or a grasp's
// gripper) to the object, cMo = `servoed_T_object()`: s = (t, θu) of cdMc, s* = 0.
PbvsResult run_pbvs(SimulatedRobot& robot, const std::function<vpHomogeneousMatrix()>& servoed_T_object,
                    const vpHomogeneousMatrix& cdMo, int max_steps) {
  vpServo task;
  task.setServo(robot.servo_type());
  task.setInteractionMatrixType(vpServo::CURRENT);
  task.setLambda(0.5);
  vpFeatureTranslation t(vpFeatureTranslation::cdMc);
  vpFeatureThetaU tu(vpFeatureThetaU::cdRc);
  task.addFeature(t);  // desired features default to zero
  task.addFeature(tu);

  PbvsResult r;
  for (r.steps = 0; r.steps <= max_steps; ++r.steps) {
    const vpHomogeneousMatrix cdMc = cdMo * servoed_T_object().inverse();
    t.buildFrom(cdMc);
    tu.buildFrom(cdMc);
    r.translation = cdMc.getTranslationVector().frobeniusNorm();
    r.rotation = vpThetaUVector(cdMc.getRotationMatrix()).getTheta();
    if (r.translation < 1e-4 && r.rotation < vpMath::rad(0.01)) {
      r.converged = true;
      break;
    }
    robot.update_jacobians(task);
    robot.move(task.computeControlLaw(), kDt);
  }
  return r;
}

/// Moves the arm from q0 for 0.1 s: the frame it carries (`carried`, eMx from the end
/// effector) follows fMe(q0 + q̇ · 0.1) eMx, and the fixed camera stays where it was.
void check_arm_carries(SimulatedRobot& robot, const vpColVector& q0, const vpHomogeneousMatrix& eMx,
                       std::optional<vpHomogeneousMatrix> (SimulatedRobot::*carried)() const) {
  const vpHomogeneousMatrix wMc = robot.world_T_camera();
  const vpColVector qdot = vec6(-0.2, 0.1, 0.3, -0.4, 0.2, 0.6);
  robot.move(qdot, 0.1);
  vpViper850 model;
  vpHomogeneousMatrix fMe;
  model.get_fMe(q0 + qdot * 0.1, fMe);
  CHECK(poses_equal(*(robot.*carried)(), fMe * eMx, 1e-12));
  CHECK(poses_equal(robot.world_T_camera(), wMc, 1e-15));  // fixed
}

}  // namespace

TEST_CASE("make_robot builds the scenario's robot at its start", "[servo][robot]") {
  const auto free = make_robot(make_scenario(RobotKind::kFreeFlyingCamera));
  const auto in_hand = make_robot(make_scenario(RobotKind::kViper850EyeInHand));
  const auto to_hand = make_robot(make_scenario(RobotKind::kViper850EyeToHand));
  CHECK(free->name() == "free-flying camera");
  CHECK(in_hand->name() == "Viper 850 (eye-in-hand)");
  CHECK(to_hand->name() == "Viper 850 (eye-to-hand)");
  CHECK(free->servo_type() == vpServo::EYEINHAND_CAMERA);
  CHECK(in_hand->servo_type() == vpServo::EYEINHAND_L_cVe_eJe);
  CHECK(to_hand->servo_type() == vpServo::EYETOHAND_L_cVf_fVe_eJe);
  CHECK(poses_equal(free->world_T_camera(), vpHomogeneousMatrix()));
  CHECK_FALSE(free->world_T_held_object().has_value());
  CHECK_FALSE(in_hand->world_T_held_object().has_value());
  CHECK(to_hand->world_T_held_object().has_value());
  CHECK(free->joint_limit_stops() == 0);
}

TEST_CASE("initial_world_T_object makes the camera see the object at initial_cMo", "[servo][robot]") {
  for (RobotKind kind : {RobotKind::kFreeFlyingCamera, RobotKind::kViper850EyeInHand, RobotKind::kViper850EyeToHand}) {
    const Scenario s = make_scenario(kind);
    const auto robot = make_robot(s);
    const vpHomogeneousMatrix wMo = initial_world_T_object(s, *robot);
    CHECK(poses_equal(robot->world_T_camera().inverse() * wMo, icgp::to_homogeneous_matrix(s.initial_cMo), 1e-12));
  }
}

TEST_CASE("an arm refuses initial joints outside its limits", "[servo][robot]") {
  vpColVector q = joints_rad(kArmJointsDeg);
  q[2] = vpMath::rad(-40);  // joint 3 limits: [-29, 256] deg
  CHECK_THROWS_AS(make_robot(make_scenario(RobotKind::kViper850EyeInHand, q)), std::invalid_argument);
}

TEST_CASE("free-flying camera: a twist held for dt moves wMc by the exponential map", "[servo][robot][free]") {
  const auto robot = make_robot(make_scenario(RobotKind::kFreeFlyingCamera));
  const vpColVector v = vec6(0.03, -0.05, 0.04, 0.2, -0.1, 0.3);  // within 0.1 m/s, 0.5 rad/s
  const vpColVector applied = robot->move(v, kDt);
  CHECK((applied - v).frobeniusNorm() == 0.0);
  const vpHomogeneousMatrix expected1 = vpExponentialMap::direct(v, kDt);
  CHECK(poses_equal(robot->world_T_camera(), expected1, 1e-12));
  // From a non-identity pose, the twist is in the camera frame: wMc <- wMc exp(v dt).
  const vpColVector v2 = vec6(-0.02, 0.01, 0.06, -0.3, 0.2, 0.1);
  robot->move(v2, 0.1);
  CHECK(poses_equal(robot->world_T_camera(), expected1 * vpExponentialMap::direct(v2, 0.1), 1e-12));
  // Not a first-order approximation: a large rotation over the step is exact too.
  CHECK(rotation_between(vpHomogeneousMatrix(), vpExponentialMap::direct(v2, 0.1)) > 0);
}

TEST_CASE("free-flying camera: saturation scales the twist uniformly", "[servo][robot][free]") {
  Scenario s = make_scenario(RobotKind::kFreeFlyingCamera);
  s.control.max_linear_velocity = 0.1;
  s.control.max_angular_velocity = 0.5;

  SECTION("linear part over its limit") {
    const auto robot = make_robot(s);
    const vpColVector v = vec6(0.3, -0.4, 0.0, 0.1, 0.0, -0.1);  // |v| = 0.5 -> factor 0.2
    const vpColVector applied = robot->move(v, kDt);
    CHECK(norm3(applied, 0) == Approx(0.1).epsilon(1e-12));
    CHECK(norm3(applied, 3) <= 0.5);
    CHECK((applied - 0.2 * v).frobeniusNorm() < 1e-15);  // same direction, both parts
    CHECK(poses_equal(robot->world_T_camera(), vpExponentialMap::direct(applied, kDt), 1e-12));
  }
  SECTION("angular part over its limit") {
    const auto robot = make_robot(s);
    const vpColVector v = vec6(0.05, 0.0, 0.05, 0.0, 3.0, 4.0);  // |w| = 5 -> factor 0.1
    const vpColVector applied = robot->move(v, kDt);
    CHECK(norm3(applied, 3) == Approx(0.5).epsilon(1e-12));
    CHECK(norm3(applied, 0) <= 0.1);
    CHECK((applied - 0.1 * v).frobeniusNorm() < 1e-15);
  }
  SECTION("both over: the tighter limit wins") {
    const auto robot = make_robot(s);
    const vpColVector v = vec6(0.0, 0.0, 1.0, 1.0, 0.0, 0.0);  // factors 0.1 and 0.5
    const vpColVector applied = robot->move(v, kDt);
    CHECK(applied[2] == Approx(0.1));
    CHECK(applied[3] == Approx(0.1));
  }
}

TEST_CASE("Viper eye-in-hand: the camera follows vpViper850's forward kinematics", "[servo][robot][viper]") {
  const vpColVector q0 = joints_rad(kArmJointsDeg);
  const auto robot = make_robot(make_scenario(RobotKind::kViper850EyeInHand, q0));
  vpViper850 model;  // the same default tool as the robot
  CHECK(poses_equal(robot->world_T_camera(), model.get_fMc(q0), 1e-12));
  // At these joints the camera looks down: the optical axis is -z of the base.
  CHECK(robot->world_T_camera().getRotationMatrix().getCol(2)[2] < -0.99);

  // A move integrates q += qdot dt.
  const vpColVector qdot = vec6(0.2, -0.1, 0.3, 0.4, -0.2, 0.5);
  const vpColVector applied = robot->move(qdot, 0.1);
  CHECK((applied - qdot).frobeniusNorm() < 1e-12);
  CHECK(poses_equal(robot->world_T_camera(), model.get_fMc(q0 + qdot * 0.1), 1e-12));
  CHECK(robot->joint_limit_stops() == 0);
}

TEST_CASE("Viper eye-in-hand: cVe eJe qdot is the camera twist (first order)", "[servo][robot][viper]") {
  const vpColVector qdot = vec6(0.3, -0.2, 0.25, 0.4, -0.3, 0.5);
  double error_at[2] = {0, 0};
  const double dts[2] = {1e-2, 1e-3};
  for (int k = 0; k < 2; ++k) {
    const auto robot = make_robot(make_scenario(RobotKind::kViper850EyeInHand));
    vpServo task;
    task.setServo(robot->servo_type());
    robot->update_jacobians(task);
    const vpColVector predicted = task.get_cVe() * task.get_eJe() * qdot;
    const vpHomogeneousMatrix before = robot->world_T_camera();
    robot->move(qdot, dts[k]);
    const vpColVector measured = measured_twist(before, robot->world_T_camera(), dts[k]);
    // Displacement error over the step: second order in dt.
    error_at[k] = (measured - predicted).frobeniusNorm() * dts[k];
    CHECK(error_at[k] < 2.0 * dts[k] * dts[k]);
    CHECK(predicted.frobeniusNorm() > 0.1);  // a real motion, not a trivial match
  }
  CHECK(error_at[0] / error_at[1] > 50.0);  // ~100 for a second-order error
}

TEST_CASE("Viper: joint velocities are saturated uniformly and joints stop at their limits", "[servo][robot][viper]") {
  vpViper850 model;
  const vpColVector q_max = model.getJointMax();
  const vpColVector q_min = model.getJointMin();

  SECTION("saturation keeps the direction") {
    Scenario s = make_scenario(RobotKind::kViper850EyeInHand);
    s.control.max_joint_velocity = 0.5;
    const auto robot = make_robot(s);
    const vpColVector qdot = vec6(0.2, -1.0, 0.5, 0.0, 0.3, -0.4);  // largest 1.0 -> factor 0.5
    const vpColVector applied = robot->move(qdot, kDt);
    CHECK((applied - 0.5 * qdot).frobeniusNorm() < 1e-12);
    CHECK(robot->joint_limit_stops() == 0);
  }
  SECTION("a joint is clamped at its limit and the stop is counted") {
    vpColVector q0 = joints_rad(kArmJointsDeg);
    q0[4] = q_max[4] - 0.01;  // joint 5, 0.01 rad below its maximum
    const auto robot = make_robot(make_scenario(RobotKind::kViper850EyeInHand, q0));
    const vpColVector qdot = vec6(0.1, 0.0, 0.0, 0.0, 0.6, 0.0);  // joint 5 would go 0.02 rad
    vpColVector applied = robot->move(qdot, kDt);
    vpColVector q1 = q0 + qdot * kDt;
    q1[4] = q_max[4];
    CHECK(poses_equal(robot->world_T_camera(), model.get_fMc(q1), 1e-12));
    CHECK(robot->joint_limit_stops() == 1);
    CHECK(applied[0] == Approx(0.1));
    CHECK(applied[4] == Approx(0.01 / kDt));  // what was actually applied
    // Still pushing: stays at the limit, counted again.
    applied = robot->move(qdot, kDt);
    CHECK(applied[4] == Approx(0.0).margin(1e-12));
    CHECK(robot->joint_limit_stops() == 2);
    // Moving away is not a stop: joint 1 comes back to q1, joint 5 leaves its limit.
    robot->move(-1.0 * qdot, kDt);
    CHECK(robot->joint_limit_stops() == 2);
    vpColVector q3 = q1;
    q3[4] = q_max[4] - 0.6 * kDt;
    CHECK(poses_equal(robot->world_T_camera(), model.get_fMc(q3), 1e-12));
  }
  SECTION("the lower limit too") {
    vpColVector q0 = joints_rad(kArmJointsDeg);
    q0[2] = q_min[2] + 0.005;  // joint 3
    const auto robot = make_robot(make_scenario(RobotKind::kViper850EyeInHand, q0));
    robot->move(vec6(0, 0, -0.9, 0, 0, 0), kDt);
    vpColVector q1 = q0;
    q1[2] = q_min[2];
    CHECK(poses_equal(robot->world_T_camera(), model.get_fMc(q1), 1e-12));
    CHECK(robot->joint_limit_stops() == 1);
  }
}

TEST_CASE("Viper eye-to-hand: the held object follows fMe(q) eMo, the camera stays", "[servo][robot][viper]") {
  const vpColVector q0 = joints_rad(kArmJointsDeg);
  const Scenario s = make_scenario(RobotKind::kViper850EyeToHand, q0);
  const auto robot = make_robot(s);
  const vpHomogeneousMatrix eMo = icgp::to_homogeneous_matrix(s.arm.eMo);
  vpViper850 model;
  vpHomogeneousMatrix fMe;
  model.get_fMe(q0, fMe);
  REQUIRE(robot->world_T_held_object().has_value());
  CHECK(poses_equal(*robot->world_T_held_object(), fMe * eMo, 1e-12));
  // At the start the fixed camera sees the object at initial_cMo.
  const vpHomogeneousMatrix wMc = robot->world_T_camera();
  CHECK(poses_equal(wMc.inverse() * *robot->world_T_held_object(), icgp::to_homogeneous_matrix(s.initial_cMo), 1e-12));

  check_arm_carries(*robot, q0, eMo, &SimulatedRobot::world_T_held_object);
}

TEST_CASE("Viper eye-to-hand: cVf fVe eJe qdot is the object's twist seen by the camera", "[servo][robot][viper]") {
  const vpColVector qdot = vec6(0.3, -0.2, 0.25, 0.4, -0.3, 0.5);
  double error_at[2] = {0, 0};
  const double dts[2] = {1e-2, 1e-3};
  for (int k = 0; k < 2; ++k) {
    const auto robot = make_robot(make_scenario(RobotKind::kViper850EyeToHand));
    vpServo task;
    task.setServo(robot->servo_type());
    robot->update_jacobians(task);
    const vpColVector predicted = task.get_cVf() * task.get_fVe() * task.get_eJe() * qdot;
    const vpHomogeneousMatrix before = *robot->world_T_held_object();
    robot->move(qdot, dts[k]);
    // The object's twist in its own frame, expressed in the (fixed) camera frame.
    const vpColVector in_object = measured_twist(before, *robot->world_T_held_object(), dts[k]);
    const vpHomogeneousMatrix cMo = robot->world_T_camera().inverse() * before;
    const vpColVector measured = vpVelocityTwistMatrix(cMo) * in_object;
    error_at[k] = (measured - predicted).frobeniusNorm() * dts[k];
    CHECK(error_at[k] < 2.0 * dts[k] * dts[k]);
    CHECK(predicted.frobeniusNorm() > 0.1);
  }
  CHECK(error_at[0] / error_at[1] > 50.0);
}

TEST_CASE("each robot's task Jacobian predicts how the PBVS features change", "[servo][robot][sign]") {
  // vpServo's J1 (with its eye-to-hand minus sign) against the true change of s over a
  // small step: a sign or frame error in update_jacobians shows here directly.
  for (RobotKind kind : {RobotKind::kFreeFlyingCamera, RobotKind::kViper850EyeInHand, RobotKind::kViper850EyeToHand}) {
    CAPTURE(static_cast<int>(kind));
    const Scenario s = make_scenario(kind);
    const auto robot = make_robot(s);
    const vpHomogeneousMatrix wMo = initial_world_T_object(s, *robot);
    const vpHomogeneousMatrix cdMo = make_pose(0.03, 0.01, 0.32, -3, 4, 12);
    auto features = [&] {
      const vpHomogeneousMatrix cdMc = cdMo * camera_T_object(*robot, wMo).inverse();
      vpColVector s6(6);
      const vpTranslationVector t = cdMc.getTranslationVector();
      const vpThetaUVector tu(cdMc.getRotationMatrix());
      for (unsigned i = 0; i < 3; ++i) s6[i] = t[i], s6[3 + i] = tu[i];
      return s6;
    };
    vpServo task;
    task.setServo(robot->servo_type());
    task.setInteractionMatrixType(vpServo::CURRENT);
    task.setLambda(0.5);
    vpFeatureTranslation t(vpFeatureTranslation::cdMc);
    vpFeatureThetaU tu(vpFeatureThetaU::cdRc);
    const vpHomogeneousMatrix cdMc = cdMo * camera_T_object(*robot, wMo).inverse();
    t.buildFrom(cdMc);
    tu.buildFrom(cdMc);
    task.addFeature(t);
    task.addFeature(tu);
    robot->update_jacobians(task);
    const vpColVector v = task.computeControlLaw();
    const vpMatrix J1 = task.getTaskJacobian();
    // ViSP's sign convention, stated: eye-in-hand J1 = L cVe eJe, eye-to-hand J1 = -L cVf fVe eJe.
    if (kind == RobotKind::kViper850EyeInHand)
      CHECK((J1 - task.getInteractionMatrix() * task.get_cVe() * task.get_eJe()).frobeniusNorm() < 1e-12);
    if (kind == RobotKind::kViper850EyeToHand)
      CHECK((J1 + task.getInteractionMatrix() * task.get_cVf() * task.get_fVe() * task.get_eJe()).frobeniusNorm() < 1e-12);
    const double dt = 1e-4;
    const vpColVector s0 = features();
    const vpColVector applied = robot->move(v, dt);
    const vpColVector ds = features() - s0;
    const vpColVector predicted = J1 * applied * dt;
    CHECK((ds - predicted).frobeniusNorm() < 1e-3 * predicted.frobeniusNorm());
    // And the control law makes the error decrease: ds ~ -lambda e dt.
    CHECK((ds + 0.5 * s0 * dt).frobeniusNorm() < 1e-3 * ds.frobeniusNorm());
  }
}

TEST_CASE("PBVS converges in closed loop with each robot", "[servo][robot][sign]") {
  // The desired pose is the initial one seen from a camera displaced by c0Mcd: 2-5 cm and
  // ~10 deg (for eye-to-hand the object makes the opposite move).
  struct Case {
    RobotKind kind;
    vpHomogeneousMatrix c0Mcd;
  };
  const Case cases[] = {
      {RobotKind::kFreeFlyingCamera, make_pose(0.03, -0.01, 0.02, 4, -6, 7)},
      {RobotKind::kViper850EyeInHand, make_pose(-0.02, 0.025, -0.015, -6, 3, 8)},
      {RobotKind::kViper850EyeToHand, make_pose(0.015, 0.02, 0.025, 5, 7, -5)},
  };
  for (const Case& c : cases) {
    const Scenario s = make_scenario(c.kind);
    const auto robot = make_robot(s);
    CAPTURE(robot->name());
    const vpHomogeneousMatrix wMo = initial_world_T_object(s, *robot);
    const vpHomogeneousMatrix cMo0 = camera_T_object(*robot, wMo);
    const vpHomogeneousMatrix cdMo = c.c0Mcd.inverse() * cMo0;
    const double t0 = translation_between(cMo0.inverse(), cdMo.inverse());
    const double r0 = rotation_between(cMo0, cdMo);
    CAPTURE(t0, vpMath::deg(r0));
    REQUIRE(t0 > 0.02);
    REQUIRE(t0 < 0.05);
    REQUIRE(vpMath::deg(r0) > 8.0);
    REQUIRE(vpMath::deg(r0) < 12.0);
    const vpHomogeneousMatrix wMc0 = robot->world_T_camera();
    const vpHomogeneousMatrix wMo0 = world_T_object(*robot, wMo);

    const PbvsResult r = run_pbvs(*robot, [&] { return camera_T_object(*robot, wMo); }, cdMo, 600);
    CAPTURE(r.steps, r.translation, vpMath::deg(r.rotation));
    CHECK(r.converged);
    CHECK(r.steps > 100);  // it really had to move there, at the gain's pace
    CHECK(robot->joint_limit_stops() == 0);
    // The right thing moved: the camera (eye-in-hand) or the object (eye-to-hand).
    if (c.kind == RobotKind::kViper850EyeToHand) {
      CHECK(poses_equal(robot->world_T_camera(), wMc0, 1e-15));
      CHECK(translation_between(world_T_object(*robot, wMo), wMo0) > 0.01);
    } else {
      CHECK(translation_between(robot->world_T_camera(), wMc0) > 0.01);
    }
  }
}

TEST_CASE("eye-to-hand without the minus sign of vpServo's eye-to-hand law does not converge", "[servo][robot][sign]") {
  // The closed loop is sensitive to the sign: commanding the held object with an eye-in-hand
  // law (J = +L cVe eJe, cVe = cVf fVe) drives the error away.
  const Scenario s = make_scenario(RobotKind::kViper850EyeToHand);
  const auto robot = make_robot(s);
  const vpHomogeneousMatrix cdMo = make_pose(0.035, -0.01, 0.34, 0, -2, 13);
  vpServo task;
  task.setServo(vpServo::EYEINHAND_L_cVe_eJe);
  task.setInteractionMatrixType(vpServo::CURRENT);
  task.setLambda(0.5);
  vpFeatureTranslation t(vpFeatureTranslation::cdMc);
  vpFeatureThetaU tu(vpFeatureThetaU::cdRc);
  const vpHomogeneousMatrix wMo = initial_world_T_object(s, *robot);
  auto update = [&] {
    const vpHomogeneousMatrix cdMc = cdMo * camera_T_object(*robot, wMo).inverse();
    t.buildFrom(cdMc);
    tu.buildFrom(cdMc);
    return cdMc.getTranslationVector().frobeniusNorm();
  };
  const double e0 = update();
  task.addFeature(t);
  task.addFeature(tu);
  for (int i = 0; i < 20; ++i) {
    vpServo reference;
    reference.setServo(robot->servo_type());
    robot->update_jacobians(reference);
    task.set_cVe(reference.get_cVf() * reference.get_fVe());
    task.set_eJe(reference.get_eJe());
    robot->move(task.computeControlLaw(), kDt);
    update();
  }
  CHECK(update() > e0);
}

namespace {

// A grasp: the gripper on a 1 cm plate turned 90 deg on the flange, the object 0.2 m ahead of
// it along its approach axis, tilted; the camera sees the object 0.6 m away.
Scenario make_grasp_scenario() {
  Scenario s = make_scenario(RobotKind::kViper850Grasp);
  GraspSpec grasp;
  grasp.eMg = icgp::to_pose(make_pose(0.0, 0.0, 0.01, 0, 0, 90));
  grasp.start_gMo = icgp::to_pose(make_pose(0.03, -0.02, 0.2, 80, -10, 5));
  grasp.desired_gMo = icgp::to_pose(make_pose(0.0, 0.0, 0.15, 90, 0, 0));
  s.grasp = grasp;
  s.initial_cMo = icgp::to_pose(make_pose(0.0, 0.05, 0.6, -150, -10, 40));
  return s;
}

vpHomogeneousMatrix gripper_T_object(const SimulatedRobot& robot, const vpHomogeneousMatrix& wMo) {
  return robot.world_T_gripper().value().inverse() * wMo;
}

}  // namespace

TEST_CASE("Viper grasp: the gripper follows fMe(q) eMg, the camera and the object stand where the scenario says",
          "[servo][robot][viper][grasp]") {
  const vpColVector q0 = joints_rad(kArmJointsDeg);
  const Scenario s = make_grasp_scenario();
  const auto robot = make_robot(s);
  CHECK(robot->servo_type() == vpServo::EYEINHAND_L_cVe_eJe);
  CHECK_FALSE(robot->world_T_held_object().has_value());
  const vpHomogeneousMatrix eMg = icgp::to_homogeneous_matrix(s.grasp->eMg);
  vpViper850 model;
  vpHomogeneousMatrix fMe;
  model.get_fMe(q0, fMe);
  REQUIRE(robot->world_T_gripper().has_value());
  CHECK(poses_equal(*robot->world_T_gripper(), fMe * eMg, 1e-12));
  // At the start the object stands at start_gMo from the gripper, and the camera sees it at
  // initial_cMo.
  const vpHomogeneousMatrix wMo = initial_world_T_object(s, *robot);
  CHECK(poses_equal(gripper_T_object(*robot, wMo), icgp::to_homogeneous_matrix(s.grasp->start_gMo), 1e-12));
  const vpHomogeneousMatrix wMc = robot->world_T_camera();
  CHECK(poses_equal(wMc.inverse() * wMo, icgp::to_homogeneous_matrix(s.initial_cMo), 1e-12));

  check_arm_carries(*robot, q0, eMg, &SimulatedRobot::world_T_gripper);
}

TEST_CASE("Viper grasp: a robot without a gripper spec is refused", "[servo][robot][grasp]") {
  CHECK_THROWS_AS(make_robot(make_scenario(RobotKind::kViper850Grasp)), std::invalid_argument);
}

TEST_CASE("Viper grasp: cVe eJe qdot (gVe from eMg) is the gripper's twist (first order)", "[servo][robot][viper][grasp]") {
  const vpColVector qdot = vec6(0.3, -0.2, 0.25, 0.4, -0.3, 0.5);
  double error_at[2] = {0, 0};
  const double dts[2] = {1e-2, 1e-3};
  for (int k = 0; k < 2; ++k) {
    const auto robot = make_robot(make_grasp_scenario());
    vpServo task;
    task.setServo(robot->servo_type());
    robot->update_jacobians(task);
    const vpColVector predicted = task.get_cVe() * task.get_eJe() * qdot;
    const vpHomogeneousMatrix before = *robot->world_T_gripper();
    robot->move(qdot, dts[k]);
    const vpColVector measured = measured_twist(before, *robot->world_T_gripper(), dts[k]);
    error_at[k] = (measured - predicted).frobeniusNorm() * dts[k];
    CHECK(error_at[k] < 2.0 * dts[k] * dts[k]);
    CHECK(predicted.frobeniusNorm() > 0.1);
  }
  CHECK(error_at[0] / error_at[1] > 50.0);
}

TEST_CASE("Viper grasp: PBVS on gMo brings the gripper to the desired pose, the object and camera stay",
          "[servo][robot][viper][grasp]") {
  const Scenario s = make_grasp_scenario();
  const auto robot = make_robot(s);
  const vpHomogeneousMatrix wMo = initial_world_T_object(s, *robot);
  const vpHomogeneousMatrix wMc0 = robot->world_T_camera();
  const vpHomogeneousMatrix gdMo = icgp::to_homogeneous_matrix(s.grasp->desired_gMo);
  const int steps = run_pbvs(*robot, [&] { return gripper_T_object(*robot, wMo); }, gdMo, 599).steps;
  CHECK(steps > 100);
  CHECK(steps < 600);
  CHECK(robot->joint_limit_stops() == 0);
  CHECK(poses_equal(robot->world_T_camera(), wMc0, 1e-15));
}
