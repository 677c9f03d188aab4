// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/base/frame.h"

#include <utility>

namespace icgp {

void LazyDepthSource::read_many(cv::Mat& depth, cv::Mat& rays, const std::vector<cv::Point>& pixels,
                                bool read_ahead) {
  points_.clear();
  read_many_(pixels, points_);
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const cv::Point& p = pixels[i];
    const float z = measured_depth(points_[i], rays, p.y, p.x);
    store(depth.ptr<float>(p.y)[p.x], read_ahead ? (z > 0.f ? -z : -kReadAheadZero) : z);
    converted_.push_back(p);
  }
}

float LazyDepthSource::measured_depth(const Eigen::Vector3f& P, cv::Mat& rays, int row, int col) const {
  const float z = P.allFinite() ? sanitized(P.z()) : 0.f;  // a non-finite coordinate: none
  if (read_point_ && z > 0.f) rays.ptr<cv::Vec2f>(row)[col] = cv::Vec2f(P.x() / z, P.y() / z);
  return z;
}

void LazyDepthSource::read_soon(cv::Mat& depth, cv::Mat& rays, const std::vector<cv::Point>& pixels) {
  if (!read_many_) return;
  const std::lock_guard<std::mutex> lock(source_lock_.mutex);
  pending_.clear();
  for (const cv::Point& p : pixels)
    if (std::isnan(load(depth.ptr<float>(p.y)[p.x]))) pending_.push_back(p);
  if (!pending_.empty()) read_many(depth, rays, pending_, false);
}

void LazyDepthSource::read_ahead(cv::Mat& depth, cv::Mat& rays) {
  if (!read_many_) return;
  pending_.clear();
  // A pixel outside: the image changed size since the last frame.
  for (const cv::Point& p : read_last_)
    if (p.x < depth.cols && p.y < depth.rows && std::isnan(depth.ptr<float>(p.y)[p.x])) pending_.push_back(p);
  if (!pending_.empty()) read_many(depth, rays, pending_, true);
}

float LazyDepthSource::resolve(cv::Mat& depth, cv::Mat& rays, int row, int col) {
  if (!has_reader()) return 0.f;
  float& held = depth.ptr<float>(row)[col];
  const auto take_read_ahead = [&held](float h) {
    const float z = h == -kReadAheadZero ? 0.f : -h;
    store(held, z);  // threads that race here store the same value
    return z;
  };
  if (const float h = load(held); !std::isnan(h)) return h >= 0.f ? h : take_read_ahead(h);
  const std::lock_guard<std::mutex> lock(source_lock_.mutex);
  if (const float h = load(held); !std::isnan(h)) return h >= 0.f ? h : take_read_ahead(h);  // read meanwhile
  const float z = read_point_ ? measured_depth(read_point_(row, col), rays, row, col) : sanitized(read_(row, col));
  store(held, z);
  converted_.emplace_back(col, row);
  return z;
}

void LazyDepthSource::unconvert(cv::Mat& depth) {
  read_last_.clear();
  for (const cv::Point& p : converted_) {
    float& held = depth.ptr<float>(p.y)[p.x];
    if (held >= 0.f) read_last_.push_back(p);  // read ahead and never read: still negative
    held = kNotConverted;
  }
  converted_.clear();
}

}  // namespace icgp
