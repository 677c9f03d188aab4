// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <opencv2/core.hpp>
#include <vector>

namespace icgp {

/// The nearest train descriptor of one query descriptor, and the distances of the
/// nearest and the second nearest (the ratio test needs both); train_index −1: none.
struct TwoNearest {
  int train_index;
  float best, second;
};

/// Exhaustive 2-NN of binary descriptors (CV_8U rows) by Hamming distance, like
/// cv::BFMatcher with k = 2 but several times faster. With `groups` (one per train row),
/// the second nearest is the nearest of another group than the nearest's: rows of one
/// group are one thing described several times (a surface point seen in several views),
/// and should not fail each other's ratio test.
void two_nearest_hamming(const cv::Mat& query, const cv::Mat& train, std::vector<TwoNearest>& out,
                         const std::vector<int>* groups = nullptr);

}  // namespace icgp
