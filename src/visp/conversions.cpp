// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/visp/conversions.h"

#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>

namespace icgp {

vpHomogeneousMatrix to_homogeneous_matrix(const Pose& a_T_b) {
  // Element-wise on purpose: building a vpRotationMatrix would reject rotations that
  // drifted slightly from orthonormal, and a conversion should not judge its input.
  vpHomogeneousMatrix aMb;
  const Eigen::Matrix4d m = a_T_b.matrix();
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 4; ++j) aMb[i][j] = m(i, j);
  return aMb;
}

Pose to_pose(const vpHomogeneousMatrix& aMb) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 4; ++j) m(i, j) = aMb[i][j];
  return Pose(m);
}

vpCameraParameters to_camera_parameters(const Intrinsics& intrinsics) {
  vpCameraParameters camera;
  camera.initPersProjWithoutDistortion(intrinsics.fu, intrinsics.fv, intrinsics.pu, intrinsics.pv);
  return camera;
}

Intrinsics to_intrinsics(const vpCameraParameters& camera, int width, int height) {
  if (camera.get_projModel() != vpCameraParameters::perspectiveProjWithoutDistortion)
    throw std::invalid_argument(
        "to_intrinsics: the camera has a distortion model, but icgp only supports perspective projection "
        "without distortion (undistort the images and use the undistorted camera)");
  Intrinsics intrinsics;
  intrinsics.fu = camera.get_px();
  intrinsics.fv = camera.get_py();
  intrinsics.pu = camera.get_u0();
  intrinsics.pv = camera.get_v0();
  intrinsics.width = width;
  intrinsics.height = height;
  intrinsics.validate("intrinsics converted from vpCameraParameters");
  return intrinsics;
}

// Images are converted by hand rather than with vpImageConvert because that one accepts
// other types silently (colour into grey) and allocates on every call.
namespace {

void require_type(const cv::Mat& image, int type, const char* expected) {
  if (image.type() != type)
    throw std::invalid_argument(std::string("image conversion: expected a ") + expected + " cv::Mat, got type " +
                                std::to_string(image.type()) + " with " + std::to_string(image.channels()) +
                                " channels");
}

}  // namespace

void to_vp_image(const cv::Mat& bgr, vpImage<vpRGBa>& rgba) {
  require_type(bgr, CV_8UC3, "CV_8UC3 (BGR)");
  rgba.resize(static_cast<unsigned int>(bgr.rows), static_cast<unsigned int>(bgr.cols));
  for (int r = 0; r < bgr.rows; ++r) {
    const cv::Vec3b* in = bgr.ptr<cv::Vec3b>(r);
    vpRGBa* out = rgba[static_cast<unsigned int>(r)];
    for (int c = 0; c < bgr.cols; ++c) out[c] = vpRGBa(in[c][2], in[c][1], in[c][0], vpRGBa::alpha_default);
  }
}

void to_vp_image(const cv::Mat& gray, vpImage<unsigned char>& image) {
  require_type(gray, CV_8UC1, "CV_8UC1");
  image.resize(static_cast<unsigned int>(gray.rows), static_cast<unsigned int>(gray.cols));
  // Row by row because a cv::Mat view (ROI) is not contiguous, while vpImage always is.
  for (int r = 0; r < gray.rows; ++r)
    std::copy(gray.ptr<unsigned char>(r), gray.ptr<unsigned char>(r) + gray.cols, image[static_cast<unsigned int>(r)]);
}

void to_cv_mat(const vpImage<vpRGBa>& rgba, cv::Mat& bgr) {
  bgr.create(static_cast<int>(rgba.getHeight()), static_cast<int>(rgba.getWidth()), CV_8UC3);
  for (int r = 0; r < bgr.rows; ++r) {
    const vpRGBa* in = rgba[static_cast<unsigned int>(r)];
    cv::Vec3b* out = bgr.ptr<cv::Vec3b>(r);
    for (int c = 0; c < bgr.cols; ++c) out[c] = cv::Vec3b(in[c].B, in[c].G, in[c].R);
  }
}

void to_cv_mat(const vpImage<unsigned char>& image, cv::Mat& gray) {
  gray.create(static_cast<int>(image.getHeight()), static_cast<int>(image.getWidth()), CV_8UC1);
  for (int r = 0; r < gray.rows; ++r) {
    const unsigned char* in = image[static_cast<unsigned int>(r)];
    std::copy(in, in + gray.cols, gray.ptr<unsigned char>(r));
  }
}

}  // namespace icgp
