// SPDX-License-Identifier: GPL-2.0-or-later
#include "vector_cloud_reader.h"

#include <utility>

namespace icgp {

void VectorCloudReader::start_frame(const std::vector<vpColVector>& cloud, unsigned int width, unsigned int height) {
  cloud_ = &cloud;
  if (width != width_ || height != height_) {
    width_ = width;
    height_ = height;
    ahead_slot_.assign(static_cast<std::size_t>(width) * height, 0);
    read_.clear();
  }
  std::swap(ahead_, read_);
  read_.clear();
  // One loop without calls: the memory reads of many points are in flight at once.
  ahead_points_.resize(ahead_.size());
  for (std::uint32_t slot = 0; slot < ahead_.size(); ++slot) {
    ahead_slot_[ahead_[slot]] = slot;
    ahead_points_[slot] = point(ahead_[slot]);
  }
  n_carried_ = ahead_.size();
}

void VectorCloudReader::read_soon(const std::vector<cv::Point>& pixels) {
  for (const cv::Point& p : pixels) {
    const std::uint32_t pixel = static_cast<std::uint32_t>(p.y) * width_ + static_cast<std::uint32_t>(p.x);
    std::uint32_t slot = 0;
    if (read_ahead(pixel, slot)) continue;
    ahead_slot_[pixel] = static_cast<std::uint32_t>(ahead_.size());
    ahead_.push_back(pixel);
    ahead_points_.push_back(point(pixel));
  }
}

Eigen::Vector3f VectorCloudReader::operator()(int row, int col) {
  const std::uint32_t pixel = static_cast<std::uint32_t>(row) * width_ + static_cast<std::uint32_t>(col);
  std::uint32_t slot = 0;
  if (!read_ahead(pixel, slot)) {
    read_.push_back(pixel);
    return point(pixel);
  }
  if (slot < n_carried_) read_.push_back(pixel);
  return ahead_points_[slot];
}

Eigen::Vector3f VectorCloudReader::point(std::uint32_t pixel) const {
  const vpColVector& p = (*cloud_)[pixel];
  if (p.size() < 3) return Eigen::Vector3f::Zero();
  return {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])};
}

}  // namespace icgp
