// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/modality/frame_pyramids.h"

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

namespace icgp {
namespace {

/// A new region is the wanted one grown by this share of its size on each side, so that the
/// body may move for a few frames before the region has to follow it.
constexpr double kRegionMargin = 0.25;
/// A region more than this many times the wanted one's area is rebuilt smaller: the body
/// moved away or shrank.
constexpr int kMaxAreaRatio = 4;

}  // namespace

bool FramePyramids::load(const cv::Mat& image) {
  std::swap(previous_grey_, grey_);
  std::swap(previous_pyramid_, pyramid_);
  previous_built_ = built_;
  built_ = false;
  previous_region_ = region_;
  // A copy, not a view: the caller may reuse the image's buffer for its next frame while
  // this one is still the previous.
  if (image.channels() == 3)
    cv::cvtColor(image, grey_, cv::COLOR_BGR2GRAY);
  else
    image.copyTo(grey_);
  return !previous_grey_.empty() && previous_grey_.size() == grey_.size();
}

void FramePyramids::focus(const cv::Rect& wanted) {
  const cv::Rect image(0, 0, grey_.cols, grey_.rows);
  const cv::Rect clipped = wanted & image;
  const bool keep = !region_.empty() && (clipped & region_) == clipped &&
                    region_.area() <= kMaxAreaRatio * std::max(1, clipped.area());
  if (!keep) {
    const int du = static_cast<int>(kRegionMargin * wanted.width), dv = static_cast<int>(kRegionMargin * wanted.height);
    region_ = cv::Rect(wanted.x - du, wanted.y - dv, wanted.width + 2 * du, wanted.height + 2 * dv) & image;
  }
  if (region_.empty()) return;
  cv::buildOpticalFlowPyramid(grey_(region_), pyramid_, window_, levels_, true);
  built_ = true;
  const bool previous_fits = !previous_grey_.empty() && previous_grey_.size() == grey_.size();
  if (previous_fits && (!previous_built_ || previous_region_ != region_)) {
    cv::buildOpticalFlowPyramid(previous_grey_(region_), previous_pyramid_, window_, levels_, true);
    previous_region_ = region_;
    previous_built_ = true;
  }
  if (!previous_fits) previous_built_ = false;
}

}  // namespace icgp
