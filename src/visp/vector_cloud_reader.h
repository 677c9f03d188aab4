// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core/types.hpp>
#include <vector>
#include <visp3/core/vpColVector.h>

namespace icgp {

/// Reads one camera's ViSP organised clouds (std::vector<vpColVector>, one point per pixel,
/// row-major) frame after frame; when a frame starts, it reads at once the pixels the last
/// frame read.
///
/// The cues read a few hundred scattered pixels of a frame, each when they need it, between
/// their own computations (DepthImage::source), and consecutive frames read mostly the same
/// pixels: the depth cue's search and the occlusion tests sample lattices fixed in the
/// image. A point of such a cloud is two pointers away (the vpColVector, then its heap
/// array), in memory the cache no longer holds: read alone, each point waits for both; read
/// in one loop, the reads of many points overlap. A point read ahead that the frame does not
/// read costs one read in that loop; a pixel the last frame did not read is read when asked.
/// The points are the cloud's either way.
class VectorCloudReader {
 public:
  /// Starts a frame of `cloud`, width x height points (the caller checked the size), and
  /// reads the points of the pixels the last frame read (none after a change of size).
  /// `cloud` must stay valid until end_frame().
  void start_frame(const std::vector<vpColVector>& cloud, unsigned int width, unsigned int height);

  /// The point of pixel (row, col) in the frame's cloud; a vpColVector of fewer than 3
  /// values (ViSP's zero-length vectors) is no measurement, 0. The pixel is read ahead in
  /// the next frame, unless it came through read_soon.
  Eigen::Vector3f operator()(int row, int col);

  /// Reads now, in one loop, the points of `pixels` (inside the cloud) that are not read
  /// yet, which the cues are about to read (DepthImage::read_soon): pixels that move with
  /// the body, so they are not read ahead in the next frame.
  void read_soon(const std::vector<cv::Point>& pixels);

  /// Forgets the frame's cloud, which is the caller's.
  void end_frame() { cloud_ = nullptr; }

 private:
  Eigen::Vector3f point(std::uint32_t pixel) const;
  /// Whether `pixel` was read ahead in this frame, at ahead_[slot].
  bool read_ahead(std::uint32_t pixel, std::uint32_t& slot) const {
    slot = ahead_slot_[pixel];
    return slot < ahead_.size() && ahead_[slot] == pixel;
  }

  const std::vector<vpColVector>* cloud_ = nullptr;
  unsigned int width_ = 0, height_ = 0;
  /// Row-major pixel indices: those read ahead in this frame with their points (the first
  /// n_carried_ when the frame started, the others through read_soon), and those read in
  /// this frame to read ahead in the next.
  std::vector<std::uint32_t> ahead_, read_;
  std::vector<Eigen::Vector3f> ahead_points_;
  std::size_t n_carried_ = 0;
  /// Per pixel, its index in ahead_ if it is there (read_ahead checks; a stale index is
  /// harmless, so it is never cleared).
  std::vector<std::uint32_t> ahead_slot_;
};

}  // namespace icgp
