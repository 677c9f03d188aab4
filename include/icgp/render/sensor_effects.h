// SPDX-License-Identifier: GPL-2.0-or-later
// What a real RGB-D sensor does to rendered images that a renderer alone does not: depth
// holes at grazing angles and along depth edges, and motion blur. Shared by the sequence
// writer and the servo simulator so that both simulate the same sensor.
#pragma once

#include <functional>
#include <opencv2/core/mat.hpp>

#include "icgp/base/intrinsics.h"

namespace icgp {

/// Removes depth (sets 0) where the surface is seen more obliquely than `max_angle_deg`
/// (angle between its normal and the viewing ray), as structured-light and stereo sensors
/// lose it there. `normals`: CV_32FC3 camera-frame normals of the same render; `intrinsics`
/// of the depth image. Nothing happens for angles of 90 degrees or more.
void remove_grazing_depth(cv::Mat& depth, const cv::Mat& normals, const Intrinsics& intrinsics, double max_angle_deg);

/// Removes depth within `radius_px` pixels of a depth discontinuity (a step of more than 3 %
/// of Z between neighbours, or an edge against missing depth), where real sensors report
/// nothing or "flying pixels" between the two surfaces. Nothing happens for radius 0.
void remove_depth_edges(cv::Mat& depth, int radius_px);

/// Motion blur: the mean of `samples` CV_8UC3 colour renders, `render(i)` being the image
/// at the i-th instant of the exposure (i = 0 .. samples-1), rounded to 8 bits. One sample
/// returns that render unchanged. Throws std::invalid_argument for samples < 1.
cv::Mat average_color_renders(int samples, const std::function<cv::Mat(int sample)>& render);

}  // namespace icgp
