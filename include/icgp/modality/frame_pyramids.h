// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <opencv2/core.hpp>
#include <vector>

namespace icgp {

/// The grey images of the last two frames and their Lucas–Kanade pyramids (with
/// derivatives) over one region of interest, for following points from the previous frame
/// to the current one and back.
///
/// Pyramids are built only over the region where the points can be: a body covers a small
/// part of the image, and the derivatives of a whole 640 × 480 pyramid cost more than
/// following a few hundred points. The region is kept from frame to frame while it still
/// holds the wanted one with room to spare, so that the current pyramid becomes the next
/// frame's previous one; a new region rebuilds the previous pyramid from its image.
class FramePyramids {
 public:
  FramePyramids(int window_size, int levels) : window_(window_size, window_size), levels_(levels) {}

  /// Makes `image` (CV_8UC3 BGR or CV_8UC1, copied) the current frame and the last current
  /// one the previous. False when the previous frame was of another size (or there was
  /// none): its points cannot be followed.
  bool load(const cv::Mat& image);
  /// Builds the pyramids over a region that holds `wanted` (clipped to the image).
  void focus(const cv::Rect& wanted);
  /// Forgets the previous frame (after a restart: nothing is followed from before it).
  void forget_previous() {
    previous_grey_.release();
    previous_built_ = false;
  }

  const cv::Mat& grey() const { return grey_; }
  /// Whether both pyramids exist over region().
  bool ready() const { return previous_built_ && built_; }
  const cv::Rect& region() const { return region_; }
  const std::vector<cv::Mat>& previous() const { return previous_pyramid_; }
  const std::vector<cv::Mat>& current() const { return pyramid_; }
  cv::Size window() const { return window_; }
  int levels() const { return levels_; }

 private:
  cv::Size window_;
  int levels_;
  cv::Mat grey_, previous_grey_;
  cv::Rect region_, previous_region_;  ///< of pyramid_ and of previous_pyramid_
  /// The two pyramids swap their buffers from frame to frame; these say which hold this
  /// frame pair's images.
  std::vector<cv::Mat> pyramid_, previous_pyramid_;
  bool built_ = false, previous_built_ = false;
};

}  // namespace icgp
