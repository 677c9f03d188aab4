// SPDX-License-Identifier: GPL-2.0-or-later
// Internal: the single-channel view of an image that the descriptors work on.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace icgp {

/// `image` itself when it has one channel, else its grey conversion (BGR or BGRA).
inline cv::Mat grey_image(const cv::Mat& image) {
  CV_Assert(image.channels() == 1 || image.channels() == 3 || image.channels() == 4);
  if (image.channels() == 1) return image;
  cv::Mat grey;
  cv::cvtColor(image, grey, image.channels() == 3 ? cv::COLOR_BGR2GRAY : cv::COLOR_BGRA2GRAY);
  return grey;
}

}  // namespace icgp
