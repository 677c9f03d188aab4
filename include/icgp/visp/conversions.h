// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <opencv2/core/mat.hpp>
#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpRGBa.h>

#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"

namespace icgp {

/// a_T_b as ViSP's aMb (same convention: maps points from frame b into frame a).
vpHomogeneousMatrix to_homogeneous_matrix(const Pose& a_T_b);
/// ViSP's aMb as a_T_b. The rotation is copied as is, not re-orthonormalised.
Pose to_pose(const vpHomogeneousMatrix& aMb);

/// Perspective camera without distortion; fu, fv, pu, pv are ViSP's px, py, u0, v0
/// (both use the pixel-centre-at-integer convention, so no half-pixel shift).
vpCameraParameters to_camera_parameters(const Intrinsics& intrinsics);
/// The inverse of to_camera_parameters for an image of width x height pixels. Throws
/// std::invalid_argument for a camera with distortion (icgp has no distortion model, so
/// silently dropping it would bias every projection) or when the result fails validate().
Intrinsics to_intrinsics(const vpCameraParameters& camera, int width, int height);

// Images. The output arguments are resized only when their size differs, so converting
// every frame into the same buffers does not allocate. Other cv::Mat types than the ones
// named throw std::invalid_argument.

/// CV_8UC3 (BGR) into RGBa with opaque alpha.
void to_vp_image(const cv::Mat& bgr, vpImage<vpRGBa>& rgba);
/// CV_8UC1 into a grey-level image.
void to_vp_image(const cv::Mat& gray, vpImage<unsigned char>& image);
/// RGBa into CV_8UC3 (BGR); alpha is dropped.
void to_cv_mat(const vpImage<vpRGBa>& rgba, cv::Mat& bgr);
/// Grey levels into CV_8UC1.
void to_cv_mat(const vpImage<unsigned char>& image, cv::Mat& gray);

}  // namespace icgp
