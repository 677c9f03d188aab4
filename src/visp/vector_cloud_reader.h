// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <opencv2/core/types.hpp>
#include <vector>
#include <visp3/core/vpColVector.h>

namespace icgp {

/// Reads the points of ViSP's organised clouds (std::vector<vpColVector>, one point per
/// pixel, row-major, `width` points a row; the caller checked the size). A vpColVector of
/// fewer than 3 values (ViSP's zero-length vectors) is no measurement, 0.
///
/// A point of such a cloud is two pointers away (the vpColVector, then its heap array), in
/// memory the cache no longer holds: read alone, each point waits for both; read in one
/// loop, the reads of many points overlap. The cues read a few hundred scattered pixels of
/// a frame, mostly the ones the last frame read (LazyDepthSource reads those ahead).
class VectorCloudReader {
 public:
  VectorCloudReader(const std::vector<vpColVector>& cloud, unsigned int width) : cloud_(&cloud), width_(width) {}

  /// The point of pixel (row, col).
  Eigen::Vector3f operator()(int row, int col) const {
    return point(static_cast<std::size_t>(row) * width_ + static_cast<std::size_t>(col));
  }
  /// The points of `pixels`, in one loop without calls.
  void operator()(const std::vector<cv::Point>& pixels, std::vector<Eigen::Vector3f>& points) const;

 private:
  Eigen::Vector3f point(std::size_t pixel) const {
    const vpColVector& p = (*cloud_)[pixel];
    if (p.size() < 3) return Eigen::Vector3f::Zero();
    return {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])};
  }

  const std::vector<vpColVector>* cloud_;
  std::size_t width_;
};

}  // namespace icgp
