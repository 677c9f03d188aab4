// SPDX-License-Identifier: GPL-2.0-or-later
// What makes the simulated cell differ from what its controller and tracker are told:
// calibration errors drawn at the sizes the scenario gives, the robot and the images made
// with the true values while the controller and the tracker get the nominal ones (checked
// against ViSP's Viper 850 model and the rendered images), and an object that is not its
// model (checked against the model's own geometry).
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/robot/vpViper850.h>

#include "icgp/servo/calibration_errors.h"
#include "icgp/servo/pose_estimator.h"
#include "icgp/servo/rgbd_simulator.h"
#include "icgp/servo/servo_controller.h"
#include "icgp/servo/servo_run.h"
#include "icgp/servo/simulated_robot.h"
#include "icgp/servo/true_object.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/conversions.h"

using namespace icgp::servo;

namespace {

/// An eye-in-hand Viper 850 at joints well away from singularities, the camera seeing the
/// object 0.35 m ahead, and the calibration errors given.
Scenario arm_scenario(RobotKind robot = RobotKind::kViper850EyeInHand) {
  Scenario s;
  s.robot = robot;
  const double joints_deg[6] = {0, -60, 170, 0, 70, 0};
  for (int i = 0; i < 6; ++i) s.arm.initial_joints[i] = vpMath::rad(joints_deg[i]);
  s.initial_cMo = icgp::Pose::from_rotation_vector(Eigen::Vector3d(0.1, -0.1, 0.3), Eigen::Vector3d(0.01, -0.02, 0.35));
  s.camera.depth_T_color = icgp::Pose::from_rotation_vector(Eigen::Vector3d::Zero(), Eigen::Vector3d(-0.025, 0, 0));
  s.calibration_error.focal = 0.02;
  s.calibration_error.principal_point = 3.0;
  s.calibration_error.depth_T_color_translation = 0.002;
  s.calibration_error.depth_T_color_rotation = 0.5 * kDegree;
  s.calibration_error.hand_eye_translation = 0.004;
  s.calibration_error.hand_eye_rotation = 1.0 * kDegree;
  s.calibration_error.joint_offset = 0.2 * kDegree;
  return s;
}

double angle_of(const icgp::Pose& p) { return Eigen::AngleAxisd(p.rotation()).angle(); }

/// The textured box alone (no background) facing a 320x240 free-flying camera 0.4 m away,
/// `right` metres right of the optical axis.
Scenario facing_box(double right) {
  Scenario s;
  s.object.model = ICGP_MODELS_DIR "/textured_box/textured_box.obj";
  s.camera.color = s.camera.depth = icgp::Intrinsics::centred(320, 240, 300.0);
  s.background.enabled = false;
  s.initial_cMo = icgp::Pose::from_rotation_vector(Eigen::Vector3d(M_PI, 0, 0), Eigen::Vector3d(right, 0, 0.4));
  return s;
}

/// The mean column of the pixels of `image` where `on` holds.
template <typename Pixel, typename Test>
double column_centroid(const vpImage<Pixel>& image, Test on) {
  double sum = 0.0, n = 0.0;
  for (unsigned v = 0; v < image.getHeight(); ++v)
    for (unsigned u = 0; u < image.getWidth(); ++u)
      if (on(image[v][u])) sum += u, n += 1.0;
  return sum / n;
}

}  // namespace

TEST_CASE("calibration: the true values are drawn at the sizes given, in directions the seed sets",
          "[servo][calibration]") {
  const Scenario s = arm_scenario();
  const TrueCalibration truth = draw_true_calibration(s, 7);
  for (const auto& [real, nominal] : {std::pair{truth.color, s.camera.color}, std::pair{truth.depth, s.camera.depth}}) {
    CHECK(std::abs(real.fu / nominal.fu - 1.0) == Approx(0.02));
    CHECK(real.fv / nominal.fv == Approx(real.fu / nominal.fu));
    CHECK(std::hypot(real.pu - nominal.pu, real.pv - nominal.pv) == Approx(3.0));
  }
  const icgp::Pose depth_error = truth.depth_T_color * s.camera.depth_T_color.inverse();
  CHECK(depth_error.translation().norm() == Approx(0.002));
  CHECK(angle_of(depth_error) == Approx(0.5 * kDegree));
  CHECK(truth.camera_error.translation().norm() == Approx(0.004));
  CHECK(angle_of(truth.camera_error) == Approx(1.0 * kDegree));
  for (int i = 0; i < 6; ++i) CHECK(std::abs(truth.joint_offsets[i]) == Approx(0.2 * kDegree));

  // The same seed draws the same cell, another seed another one.
  const TrueCalibration again = draw_true_calibration(s, 7), other = draw_true_calibration(s, 8);
  CHECK(again.camera_error.matrix() == truth.camera_error.matrix());
  CHECK(other.camera_error.matrix() != truth.camera_error.matrix());

  // Without errors the cell is exactly the nominal one.
  Scenario exact = s;
  exact.calibration_error = {};
  const TrueCalibration nominal = draw_true_calibration(exact, 7);
  CHECK((nominal.color.fu == s.camera.color.fu && nominal.color.pu == s.camera.color.pu));
  CHECK(nominal.depth_T_color.matrix() == s.camera.depth_T_color.matrix());
  CHECK(nominal.camera_error.matrix().isIdentity(0.0));
  CHECK(nominal.joint_offsets.isZero(0.0));
}

TEST_CASE("calibration: the arm moves and shows its camera where it truly is, its Jacobians stay nominal",
          "[servo][calibration]") {
  const Scenario s = arm_scenario();
  const TrueCalibration truth = draw_true_calibration(s, 3);
  const auto robot = make_robot(s, truth), nominal = make_robot(s);
  // ViSP's model at the encoders' angles plus the offsets, with the camera moved by its error.
  vpViper850 viper;
  vpColVector q(6);
  for (unsigned i = 0; i < 6; ++i) q[i] = s.arm.initial_joints[i] + truth.joint_offsets[i];
  vpHomogeneousMatrix fMe, eMc;
  viper.get_fMe(q, fMe);
  viper.get_eMc(eMc);
  const vpHomogeneousMatrix expected = fMe * eMc * icgp::to_homogeneous_matrix(truth.camera_error);
  const vpHomogeneousMatrix wMc = robot->world_T_camera();
  CHECK((wMc.getTranslationVector() - expected.getTranslationVector()).frobeniusNorm() < 1e-12);
  // About 4 mm of hand-eye error and 0.2 deg per joint put the camera millimetres off.
  const double off = (wMc.getTranslationVector() - nominal->world_T_camera().getTranslationVector()).frobeniusNorm();
  CHECK(off > 0.002);
  CHECK(off < 0.02);
  // The controller's Jacobians come from the encoders and the calibrated eMc.
  vpServo a, b;
  a.setServo(robot->servo_type());
  b.setServo(nominal->servo_type());
  robot->update_jacobians(a);
  nominal->update_jacobians(b);
  CHECK((a.get_eJe() - b.get_eJe()).frobeniusNorm() == 0.0);
  CHECK((vpMatrix(a.get_cVe()) - vpMatrix(b.get_cVe())).frobeniusNorm() == 0.0);
}

TEST_CASE("calibration: a grasp's tracker gets the gripper from the nominal kinematics, not the truth",
          "[servo][calibration]") {
  Scenario s = arm_scenario(RobotKind::kViper850Grasp);
  GraspSpec grasp;
  grasp.eMg = icgp::Pose::from_rotation_vector(Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 0.01));
  grasp.start_gMo = icgp::Pose::from_rotation_vector(Eigen::Vector3d(1.4, 0, 0), Eigen::Vector3d(0.03, -0.02, 0.2));
  s.grasp = grasp;
  const TrueCalibration truth = draw_true_calibration(s, 5);
  const auto robot = make_robot(s, truth);
  const vpHomogeneousMatrix true_cMg = robot->world_T_camera().inverse() * *robot->world_T_gripper();
  const vpHomogeneousMatrix known_cMg = *robot->kinematic_camera_T_gripper();
  const double apart = (true_cMg.getTranslationVector() - known_cMg.getTranslationVector()).frobeniusNorm();
  CHECK(apart > 0.002);
  CHECK(apart < 0.03);
  // Exact calibration: the kinematics know the truth.
  const auto exact = make_robot(s);
  const vpHomogeneousMatrix exact_cMg = exact->world_T_camera().inverse() * *exact->world_T_gripper();
  CHECK((exact_cMg.getTranslationVector() - exact->kinematic_camera_T_gripper()->getTranslationVector())
            .frobeniusNorm() < 1e-12);
}

TEST_CASE("calibration: the images are made with the true intrinsics, the sensor reports the nominal ones",
          "[servo][calibration]") {
  const Scenario s = facing_box(0.0);
  TrueCalibration truth = nominal_calibration(s);
  truth.depth.pu += 10.0;  // the depth camera's principal point 10 px right of what it reports
  const auto robot = make_robot(s);
  const vpHomogeneousMatrix wMc = robot->world_T_camera();
  const vpHomogeneousMatrix wMo = initial_world_T_object(s, *robot);
  RgbdSimulator exact(s, wMc, wMo, 1), shifted(s, truth, wMc, wMo, 1);
  // The column centroid of the measured pixels (the box alone: no background).
  const auto measured = [](uint16_t z) { return z > 0; };
  const double u_exact = column_centroid(exact.capture(0.0, wMc, wMc).depth_raw, measured);
  const double u_shifted = column_centroid(shifted.capture(0.0, wMc, wMc).depth_raw, measured);
  CHECK(u_shifted - u_exact == Approx(10.0).margin(0.5));
  CHECK(shifted.depth_camera().get_u0() == Approx(s.camera.depth.pu));
}

TEST_CASE("model mismatch: the scene's object is scaled and its vertices moved, coincident ones together",
          "[servo][calibration]") {
  ObjectSpec object;
  object.model = ICGP_MODELS_DIR "/textured_box/textured_box.obj";
  const icgp::Mesh model = icgp::load_any_mesh(object.model);
  // Nothing asked: the model itself.
  const icgp::Mesh same = true_object_mesh(object, 1);
  CHECK(same.all_vertices() == model.all_vertices());

  object.scale_error = -0.02;
  Eigen::Vector3f lo, hi, lo_true, hi_true;
  model.bounds(lo, hi);
  true_object_mesh(object, 1).bounds(lo_true, hi_true);
  CHECK(((hi_true - lo_true) - 0.98f * (hi - lo)).norm() < 1e-6f);

  object.scale_error = 0.0;
  object.vertex_noise = 0.001;
  const std::vector<Eigen::Vector3f> a = model.all_vertices(), b = true_object_mesh(object, 1).all_vertices();
  REQUIRE(a.size() == b.size());
  double sum_sq = 0.0;
  std::size_t coincident = 0, kept_together = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sum_sq += (b[i] - a[i]).squaredNorm();
    for (std::size_t j = i + 1; j < a.size(); ++j)
      if ((a[i] - a[j]).norm() < 1e-7f) {
        ++coincident;
        kept_together += (b[i] - b[j]).norm() < 1e-7f;
      }
  }
  // A textured box repeats each corner per face: they must stay one point.
  CHECK(coincident > 0);
  CHECK(kept_together == coincident);
  // 1 mm per axis on 8 distinct corners: the RMS displacement is near sqrt(3) mm.
  CHECK(std::sqrt(sum_sq / a.size()) == Approx(std::sqrt(3.0) * 1e-3).epsilon(0.6));
  CHECK(true_object_mesh(object, 1).all_vertices() == b);  // the same seed, the same object
  CHECK(true_object_mesh(object, 2).all_vertices() != b);
}

TEST_CASE("calibration: a colour lens's radial distortion moves the image as x (1 + k1 r²) says", "[servo][calibration]") {
  // The box's front face 0.12 m right of the optical axis, where barrel distortion pulls it in.
  const Scenario s = facing_box(0.12);
  TrueCalibration truth = nominal_calibration(s);
  truth.color_k1 = -0.5;
  const auto robot = make_robot(s);
  const vpHomogeneousMatrix wMc = robot->world_T_camera();
  const vpHomogeneousMatrix wMo = initial_world_T_object(s, *robot);
  RgbdSimulator pinhole(s, wMc, wMo, 1), lens(s, truth, wMc, wMo, 1);
  const auto on_box = [](const vpRGBa& p) { return p.R + p.G + p.B > 30; };
  // The pinhole image's box pixels, moved by the forward model and weighted by the area the
  // lens gives them (its Jacobian, (1 + k1 r²)(1 + 3 k1 r²)), against the lens image's.
  const RgbdCapture& straight = pinhole.capture(0.0, wMc, wMc);
  const icgp::Intrinsics& k = s.camera.color;
  double predicted = 0.0, weight = 0.0;
  for (unsigned v = 0; v < straight.color.getHeight(); ++v)
    for (unsigned u = 0; u < straight.color.getWidth(); ++u)
      if (on_box(straight.color[v][u])) {
        const double x = (u - k.pu) / k.fu, y = (v - k.pv) / k.fv, r2 = x * x + y * y;
        const double area = (1.0 + truth.color_k1 * r2) * (1.0 + 3.0 * truth.color_k1 * r2);
        predicted += area * (k.pu + k.fu * x * (1.0 + truth.color_k1 * r2));
        weight += area;
      }
  predicted /= weight;
  const RgbdCapture& bent = lens.capture(0.0, wMc, wMc);
  const double measured = column_centroid(bent.color, on_box);
  const double straight_centroid = column_centroid(straight.color, on_box);
  INFO("box centroid: pinhole " << straight_centroid << " px, predicted " << predicted << ", through the lens "
                                << measured);
  CHECK(straight_centroid - predicted > 4.0);  // the distortion is large enough to see
  CHECK(measured == Approx(predicted).margin(0.3));
  // The sensor reports no distortion, and its depth image stays rectified.
  CHECK(lens.color_camera().get_kud() == 0.0);
  const unsigned pixels = straight.depth_raw.getSize();
  CHECK(std::equal(straight.depth_raw.bitmap, straight.depth_raw.bitmap + pixels, bent.depth_raw.bitmap));
}

TEST_CASE("image oracle: the true corners read through the nominal intrinsics, as a calibrated program reads them",
          "[servo][calibration]") {
  Scenario s = facing_box(0.03);
  s.tracker.kind = TrackerKind::kImageOracle;
  s.calibration_error.focal = 0.03;
  const auto robot = make_robot(s);
  const vpHomogeneousMatrix wMc = robot->world_T_camera(), wMo = initial_world_T_object(s, *robot);
  const std::vector<vpPoint> corners = bounding_box_corners(s.object.model);
  for (const bool exact : {true, false}) {
    const TrueCalibration truth = exact ? nominal_calibration(s) : draw_true_calibration(s, 3);
    RgbdSimulator simulator(s, truth, wMc, wMo, 1);
    const RgbdCapture& capture = simulator.capture(0.0, wMc, wMc);
    const vpHomogeneousMatrix cMo = make_pose_estimator(s.tracker, s, simulator)->track(capture).cMo;
    const PoseError error = pose_error(cMo, capture.cMo_true);
    INFO((exact ? "exact" : "focal 3 % off") << ": " << 1e3 * error.translation << " mm, "
                                            << error.rotation / kDegree << " deg from the truth");
    if (exact) {
      CHECK(error.translation < 1e-6);
      CHECK(error.rotation < 1e-5);
      continue;
    }
    // The estimate explains the true image through the nominal camera as well as a rigid pose
    // can (no pose scales an image exactly): each corner within a quarter pixel of where the
    // true camera shows it...
    const icgp::Intrinsics& nominal = s.camera.color;
    for (vpPoint corner : corners) {
      vpPoint seen = corner;
      seen.track(capture.cMo_true);
      corner.track(cMo);
      CHECK(nominal.fu * corner.get_x() + nominal.pu ==
            Approx(truth.color.fu * seen.get_x() + truth.color.pu).margin(0.25));
      CHECK(nominal.fv * corner.get_y() + nominal.pv ==
            Approx(truth.color.fv * seen.get_y() + truth.color.pv).margin(0.25));
    }
    // ... so the object seems nearer or farther by the focal error, about Z e.
    const double z = capture.cMo_true[2][3], e = truth.color.fu / nominal.fu - 1.0;
    CHECK(std::abs(e) == Approx(0.03));
    CHECK(cMo[2][3] - z == Approx(-z * e / (1.0 + e)).epsilon(0.1));
  }
}

namespace {

/// Trial 0 of scenarios/textbook/<name>.yaml with its focal error set to `percent`.
ServoResult textbook_run(const std::string& name, double percent) {
  const Scenario s = load_scenario(ICGP_MODELS_DIR "/../scenarios/textbook/" + name + ".yaml", ICGP_MODELS_DIR,
                                   {{"calibration_error.focal_percent", percent}});
  ServoRunOptions quiet;
  quiet.progress = false;
  return run_servo(s, quiet);
}

}  // namespace

TEST_CASE("textbook: IBVS taught by showing reaches the true goal whatever the focal error, PBVS to a given pose "
          "misses it by Z e", "[servo][calibration]") {
  // Chaumette & Hutchinson (IEEE RAM 2006), with exact image measurements (image_oracle).
  double previous_pbvs = -1.0;
  for (const double percent : {0.0, 2.5, 5.0}) {
    const ServoResult ibvs = textbook_run("ibvs_taught_by_showing", percent);
    const ServoResult pbvs = textbook_run("pbvs_calibrated", percent);
    INFO(percent << " % focal error: IBVS taught by showing ends " << 1e3 * ibvs.final_t << " mm, "
                 << ibvs.final_r / kDegree << " deg from the goal; PBVS " << 1e3 * pbvs.final_t << " mm, "
                 << pbvs.final_r / kDegree << " deg");
    CHECK(ibvs.converged);
    CHECK(ibvs.final_t < 1e-3);
    CHECK(ibvs.final_r < 0.1 * kDegree);
    CHECK(pbvs.converged);  // it settles: on the wrong pose
    // The desired pose is 0.35 m from the box; a pose read through a focal length e off
    // puts it at about 0.35 e from where it is.
    CHECK(pbvs.final_t == Approx(0.35 * percent * 1e-2).margin(1e-3));
    CHECK(pbvs.final_t > previous_pbvs);
    previous_pbvs = pbvs.final_t;
  }
}
