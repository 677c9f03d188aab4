// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <opencv2/core/mat.hpp>

namespace icgp {

/// Metric depth (CV_32F, 0 = none) as a colour map over its valid range; black where empty.
cv::Mat depth_to_bgr(const cv::Mat& depth);
/// Unit normals (CV_32FC3) mapped from [-1, 1] to [0, 255] per axis (x→R, y→G, z→B).
cv::Mat normals_to_bgr(const cv::Mat& normals);
/// Body ids (CV_8U) in distinct colours; background black.
cv::Mat ids_to_bgr(const cv::Mat& ids);
/// Images of equal size tiled row by row, `columns` per row (missing tiles black).
cv::Mat tile(const std::vector<cv::Mat>& images, int columns);

}  // namespace icgp
