// SPDX-License-Identifier: GPL-2.0-or-later
// The geometry primitives checked against ViSP (an independent implementation of the same
// conventions) and against finite differences.
#include <catch2/catch.hpp>
#include <cmath>
#include <opencv2/core.hpp>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/core/vpRotationMatrix.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpTranslationVector.h>

#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"
#include "icgp/visp/conversions.h"

using Eigen::Matrix3d;
using Eigen::Vector2d;
using Eigen::Vector3d;
using icgp::Intrinsics;
using icgp::kPi;
using icgp::Pose;
using Vector6d = Eigen::Matrix<double, 6, 1>;

namespace {

Matrix3d to_eigen(const vpRotationMatrix& R) {
  Matrix3d m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = R[i][j];
  return m;
}

Eigen::Matrix4d to_eigen(const vpHomogeneousMatrix& M) {
  Eigen::Matrix4d m;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) m(i, j) = M[i][j];
  return m;
}

// A pose and its ViSP twin, both built from the same theta-u and translation.
struct PosePair {
  Pose icgp;
  vpHomogeneousMatrix visp;
};

PosePair make_pose(double tx, double ty, double tz, double rx, double ry, double rz) {
  return {Pose::from_rotation_vector(Vector3d(rx, ry, rz), Vector3d(tx, ty, tz)),
          vpHomogeneousMatrix(vpTranslationVector(tx, ty, tz), vpThetaUVector(rx, ry, rz))};
}

Intrinsics test_intrinsics() {
  Intrinsics k;
  k.fu = 612.3;
  k.fv = 598.7;
  k.pu = 321.4;
  k.pv = 243.9;
  k.width = 640;
  k.height = 480;
  return k;
}

}  // namespace

TEST_CASE("exp_so3 matches ViSP's theta-u rotation") {
  const std::vector<Vector3d> rotation_vectors = {{0.0, 0.0, 0.0},     {1e-7, -2e-7, 3e-7}, {0.3, -0.2, 0.1},
                                                  {0.0, 0.0, kPi / 2}, {1.0, 2.0, -0.5},    {0.0, kPi - 1e-6, 0.0}};
  for (const Vector3d& w : rotation_vectors) {
    const Matrix3d expected = to_eigen(vpRotationMatrix(vpThetaUVector(w.x(), w.y(), w.z())));
    CHECK((icgp::exp_so3(w) - expected).cwiseAbs().maxCoeff() < 1e-12);
  }
}

TEST_CASE("Pose composition, inverse and point action match vpHomogeneousMatrix") {
  const PosePair a = make_pose(0.1, -0.2, 0.5, 0.3, -0.1, 0.7);
  const PosePair b = make_pose(-0.3, 0.05, 0.2, -1.2, 0.4, 0.2);
  CHECK((a.icgp.matrix() - to_eigen(a.visp)).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(((a.icgp * b.icgp).matrix() - to_eigen(a.visp * b.visp)).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((a.icgp.inverse().matrix() - to_eigen(a.visp.inverse())).cwiseAbs().maxCoeff() < 1e-12);

  const vpColVector X_visp = a.visp * vpColVector({0.01, 0.2, -0.3, 1.0});
  const Vector3d X = a.icgp * Vector3d(0.01, 0.2, -0.3);
  for (int i = 0; i < 3; ++i) CHECK(X(i) == Approx(X_visp[i]).margin(1e-12));
}

TEST_CASE("updated_in_body_frame right-multiplies [exp(theta_r), theta_t]") {
  const PosePair camera_T_body = make_pose(0.02, -0.01, 0.6, 0.4, 0.2, -0.3);
  Vector6d theta;
  theta << 0.05, -0.02, 0.03, 0.001, 0.002, -0.003;
  // ViSP's construction of the same increment: rotation from theta-u, translation as is
  // (not vpExponentialMap, whose translation part is coupled to the rotation).
  const vpHomogeneousMatrix increment(vpTranslationVector(theta(3), theta(4), theta(5)),
                                      vpThetaUVector(theta(0), theta(1), theta(2)));
  const Pose updated = camera_T_body.icgp.updated_in_body_frame(theta);
  CHECK((updated.matrix() - to_eigen(camera_T_body.visp * increment)).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("updated_in_body_frame agrees with its first-order model for small theta") {
  const Pose camera_T_body = make_pose(0.02, -0.01, 0.6, 0.4, 0.2, -0.3).icgp;
  const Vector3d body_X(0.03, -0.02, 0.05);
  const Eigen::Matrix<double, 3, 6> J = icgp::point_jacobian_body_variation(camera_T_body.rotation(), body_X);
  Vector6d direction;
  direction << 0.3, -0.5, 0.2, 0.4, 0.1, -0.6;
  for (const double step : {1e-3, 1e-4, 1e-5}) {
    const Vector3d moved = camera_T_body.updated_in_body_frame(step * direction) * body_X;
    const Vector3d linear = camera_T_body * body_X + J * (step * direction);
    // The remainder of a first-order model is quadratic in the step.
    CHECK((moved - linear).norm() < 2.0 * step * step);
  }
}

TEST_CASE("point_jacobian_body_variation matches central finite differences") {
  const Pose camera_T_body = make_pose(-0.05, 0.03, 0.45, -0.7, 0.5, 1.1).icgp;
  const Vector3d body_X(0.04, 0.01, -0.03);
  const Eigen::Matrix<double, 3, 6> J = icgp::point_jacobian_body_variation(camera_T_body.rotation(), body_X);
  const double h = 1e-6;
  for (int k = 0; k < 6; ++k) {
    const Vector6d step = Vector6d::Unit(k) * h;
    const Vector3d numeric =
        (camera_T_body.updated_in_body_frame(step) * body_X - camera_T_body.updated_in_body_frame(-step) * body_X) /
        (2 * h);
    CHECK((J.col(k) - numeric).norm() < 1e-8);
  }
}

TEST_CASE("Intrinsics::project matches vpMeterPixelConversion") {
  const Intrinsics k = test_intrinsics();
  const vpCameraParameters camera(k.fu, k.fv, k.pu, k.pv);
  for (const Vector3d& X : {Vector3d(0.1, -0.05, 0.8), Vector3d(-0.3, 0.2, 1.5), Vector3d(0.0, 0.0, 0.3)}) {
    double u = 0, v = 0;
    vpMeterPixelConversion::convertPoint(camera, X.x() / X.z(), X.y() / X.z(), u, v);
    const Vector2d uv = k.project(X);
    CHECK(uv.x() == Approx(u).margin(1e-9));
    CHECK(uv.y() == Approx(v).margin(1e-9));
  }
}

TEST_CASE("Intrinsics::projection_jacobian matches central finite differences") {
  const Intrinsics k = test_intrinsics();
  const Vector3d X(0.12, -0.07, 0.65);
  const Eigen::Matrix<double, 2, 3> J = k.projection_jacobian(X);
  const double h = 1e-7;
  for (int i = 0; i < 3; ++i) {
    const Vector3d dX = Vector3d::Unit(i) * h;
    const Vector2d numeric = (k.project<double>(X + dX) - k.project<double>(X - dX)) / (2 * h);
    CHECK((J.col(i) - numeric).norm() < 1e-4);  // pixels per metre, entries ~1e3
  }
}

TEST_CASE("Intrinsics::back_project inverts project") {
  const Intrinsics k = test_intrinsics();
  for (const Vector3d& X : {Vector3d(0.1, -0.05, 0.8), Vector3d(-0.3, 0.2, 1.5)}) {
    const Vector2d uv = k.project(X);
    CHECK((k.back_project(uv.x(), uv.y(), X.z()) - X).norm() < 1e-12);
  }
}

TEST_CASE("rotation_angle_between recovers known angles, including near and at 180 degrees") {
  const Matrix3d a = icgp::exp_so3(Vector3d(0.3, -0.2, 0.5));
  const Vector3d axis = Vector3d(1.0, 2.0, -0.5).normalized();
  for (const double degrees : {0.0, 1e-6, 0.5, 90.0, 179.9, 180.0}) {
    const double angle = degrees * kPi / 180.0;
    const Matrix3d b = a * Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    CHECK(icgp::rotation_angle_between(a, b) == Approx(angle).margin(1e-9));
  }
}

TEST_CASE("Intrinsics::cropped maps a point to the crop's pixel grid") {
  const Intrinsics full = test_intrinsics();
  const double u_min = 100, v_min = 50, crop_width = 240, crop_height = 180;
  const int out_width = 200, out_height = 150;
  const Intrinsics crop = full.cropped(u_min, v_min, crop_width, crop_height, out_width, out_height);
  const Vector3d X(0.05, 0.02, 0.7);
  const Vector2d uv_full = full.project(X);
  const Vector2d uv_crop = crop.project(X);
  // The crop starts on the edge of pixel u_min, i.e. at u_min - 0.5; output pixel centres
  // are half an output pixel inside that edge.
  CHECK(uv_crop.x() == Approx((uv_full.x() - (u_min - 0.5)) * out_width / crop_width - 0.5).margin(1e-9));
  CHECK(uv_crop.y() == Approx((uv_full.y() - (v_min - 0.5)) * out_height / crop_height - 0.5).margin(1e-9));
  CHECK(crop.width == out_width);
  CHECK(crop.height == out_height);
}

TEST_CASE("Intrinsics::validate rejects a zero focal length") {
  Intrinsics k = test_intrinsics();
  CHECK_NOTHROW(k.validate());
  k.fu = 0.0;
  CHECK_THROWS_AS(k.validate(), std::invalid_argument);
}

TEST_CASE("Pose <-> vpHomogeneousMatrix round trip") {
  const PosePair p = make_pose(0.1, -0.2, 0.5, 0.3, -0.1, 0.7);
  CHECK((to_eigen(icgp::to_homogeneous_matrix(p.icgp)) - p.icgp.matrix()).cwiseAbs().maxCoeff() == 0.0);
  CHECK((icgp::to_pose(p.visp).matrix() - to_eigen(p.visp)).cwiseAbs().maxCoeff() == 0.0);
  CHECK((icgp::to_pose(icgp::to_homogeneous_matrix(p.icgp)).matrix() - p.icgp.matrix()).cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("Intrinsics <-> vpCameraParameters round trip") {
  const Intrinsics k = test_intrinsics();
  const vpCameraParameters camera = icgp::to_camera_parameters(k);
  CHECK(camera.get_projModel() == vpCameraParameters::perspectiveProjWithoutDistortion);
  CHECK(camera.get_px() == k.fu);
  CHECK(camera.get_py() == k.fv);
  CHECK(camera.get_u0() == k.pu);
  CHECK(camera.get_v0() == k.pv);

  const Intrinsics back = icgp::to_intrinsics(camera, k.width, k.height);
  CHECK(back.fu == k.fu);
  CHECK(back.fv == k.fv);
  CHECK(back.pu == k.pu);
  CHECK(back.pv == k.pv);
  CHECK(back.width == k.width);
  CHECK(back.height == k.height);
}

TEST_CASE("to_intrinsics refuses cameras with distortion and invalid sizes") {
  vpCameraParameters distorted;
  distorted.initPersProjWithDistortion(600, 600, 320, 240, -0.1, 0.1);
  try {
    icgp::to_intrinsics(distorted, 640, 480);
    FAIL("no exception");
  } catch (const std::invalid_argument& e) {
    CHECK_THAT(e.what(), Catch::Contains("distortion"));
  }
  CHECK_THROWS_AS(icgp::to_intrinsics(vpCameraParameters(600, 600, 320, 240), 0, 480), std::invalid_argument);
}

TEST_CASE("cv::Mat <-> vpImage keeps pixel values") {
  SECTION("colour: BGR <-> RGBa") {
    cv::Mat bgr(3, 4, CV_8UC3);
    for (int r = 0; r < bgr.rows; ++r)
      for (int c = 0; c < bgr.cols; ++c) bgr.at<cv::Vec3b>(r, c) = cv::Vec3b(10 * r + c, 100 + r, 200 + c);
    vpImage<vpRGBa> rgba;
    icgp::to_vp_image(bgr, rgba);
    REQUIRE(rgba.getHeight() == 3);
    REQUIRE(rgba.getWidth() == 4);
    for (unsigned int r = 0; r < 3; ++r)
      for (unsigned int c = 0; c < 4; ++c) {
        CHECK(int(rgba[r][c].B) == int(10 * r + c));
        CHECK(int(rgba[r][c].G) == int(100 + r));
        CHECK(int(rgba[r][c].R) == int(200 + c));
        CHECK(int(rgba[r][c].A) == 255);
      }
    cv::Mat back;
    icgp::to_cv_mat(rgba, back);
    REQUIRE(back.type() == CV_8UC3);
    CHECK(cv::norm(back, bgr, cv::NORM_INF) == 0.0);
  }
  SECTION("grey levels, from a non-contiguous view") {
    cv::Mat big(6, 8, CV_8UC1);
    for (int r = 0; r < big.rows; ++r)
      for (int c = 0; c < big.cols; ++c) big.at<unsigned char>(r, c) = static_cast<unsigned char>(30 * r + c);
    const cv::Mat view = big(cv::Rect(2, 1, 5, 4));
    REQUIRE_FALSE(view.isContinuous());
    vpImage<unsigned char> image;
    icgp::to_vp_image(view, image);
    REQUIRE(image.getHeight() == 4);
    REQUIRE(image.getWidth() == 5);
    for (unsigned int r = 0; r < 4; ++r)
      for (unsigned int c = 0; c < 5; ++c) CHECK(int(image[r][c]) == int(30 * (r + 1) + c + 2));
    cv::Mat back;
    icgp::to_cv_mat(image, back);
    REQUIRE(back.type() == CV_8UC1);
    CHECK(cv::norm(back, view, cv::NORM_INF) == 0.0);
  }
  SECTION("other types are refused") {
    vpImage<vpRGBa> rgba;
    vpImage<unsigned char> gray;
    CHECK_THROWS_AS(icgp::to_vp_image(cv::Mat(2, 2, CV_8UC1), rgba), std::invalid_argument);
    CHECK_THROWS_AS(icgp::to_vp_image(cv::Mat(2, 2, CV_8UC3), gray), std::invalid_argument);
    CHECK_THROWS_AS(icgp::to_vp_image(cv::Mat(2, 2, CV_32FC1), gray), std::invalid_argument);
  }
}
