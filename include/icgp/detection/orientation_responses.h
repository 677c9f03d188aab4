// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <array>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

namespace icgp {

/// The image side of gradient template matching (docs/detection.md): quantised gradient
/// orientations of one image, spread over a small neighbourhood, and for every orientation
/// a map of how well each pixel answers a template point of that orientation. The maps are
/// stored by grid phase (LINEMOD's linearised memories, Hinterstoisser et al., PAMI 2012),
/// so that one template point adds one contiguous run of bytes to the scores of all grid
/// positions at once.
class OrientationResponses {
 public:
  /// Orientations modulo 180 degrees: a contour's polarity depends on what is behind it.
  static constexpr int kBins = 8;
  /// Grid step of the template positions, in pixels of this image.
  static constexpr int kStride = 4;
  /// A gradient anywhere within this many pixels answers a template point.
  static constexpr int kSpreadRadius = 2;
  /// The best answer to a template point (same orientation bin).
  static constexpr int kMaxResponse = 4;

  /// From a CV_8UC3 (BGR) or CV_8UC1 image. A pixel's orientation is that of the colour
  /// channel with the strongest gradient, kept only where its 3x3 neighbourhood agrees, so
  /// that noise and isolated texture specks answer nothing. `usable` (CV_8UC1 of the
  /// image's size, or empty: every pixel): pixels where it is 0 answer nothing.
  void compute(const cv::Mat& image, const cv::Mat& usable = {});

  int width() const { return width_; }
  int height() const { return height_; }
  int grid_cols() const { return width_ / kStride; }
  int grid_rows() const { return height_ / kStride; }
  int grid_size() const { return grid_cols() * grid_rows(); }

  /// Responses to orientation `bin` at the pixels (col * kStride + phase_x, row * kStride +
  /// phase_y), for all grid positions in row-major order.
  const std::uint8_t* linear(int bin, int phase_x, int phase_y) const {
    return linear_[bin].data() + static_cast<std::size_t>(phase_y * kStride + phase_x) * grid_size();
  }
  /// The quantised, spread orientations as a bit mask per pixel (for tests and display).
  const cv::Mat& spread() const { return spread_; }

  /// The bin of an image direction (dx, dy), orientation modulo 180 degrees.
  static int bin_of(float dx, float dy);

 private:
  int width_ = 0, height_ = 0;
  cv::Mat spread_;  ///< CV_8UC1, bit b set where orientation b is within the spread radius
  std::array<std::vector<std::uint8_t>, kBins> linear_;
};

}  // namespace icgp
