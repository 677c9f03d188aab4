// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/detection/orientation_responses.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace icgp {
namespace {

/// A gradient magnitude below this (Sobel 3x3 on 8-bit values, about 10 grey levels across
/// a sharp edge) carries no orientation: it is noise or shading.
constexpr float kMinMagnitude = 40.f;
/// Of the 3x3 neighbourhood, at least this many pixels share the centre's bin.
constexpr int kMinAgreeing = 4;

/// Similarity of two orientation bins by their circular distance (0..4 bins of 22.5
/// degrees): a point answers fully to its own orientation, partly to the next one.
constexpr std::array<std::uint8_t, 5> kSimilarity = {OrientationResponses::kMaxResponse, 2, 0, 0, 0};

/// For each bin, the response to a spread mask: the best similarity among its bits.
std::array<std::array<std::uint8_t, 256>, OrientationResponses::kBins> response_table() {
  std::array<std::array<std::uint8_t, 256>, OrientationResponses::kBins> table{};
  for (int bin = 0; bin < OrientationResponses::kBins; ++bin)
    for (int mask = 0; mask < 256; ++mask)
      for (int b = 0; b < OrientationResponses::kBins; ++b) {
        if (!(mask & (1 << b))) continue;
        const int d = std::abs(bin - b);
        const int distance = std::min(d, OrientationResponses::kBins - d);
        table[bin][mask] = std::max(table[bin][mask], kSimilarity[distance]);
      }
  return table;
}

/// The quantised orientation of every pixel (255: none), from the strongest channel.
cv::Mat quantised_orientations(const cv::Mat& image) {
  cv::Mat smoothed;
  cv::GaussianBlur(image, smoothed, cv::Size(3, 3), 0.0);
  std::vector<cv::Mat> channels;
  cv::split(smoothed, channels);
  cv::Mat best_dx(image.size(), CV_16S, cv::Scalar(0)), best_dy(image.size(), CV_16S, cv::Scalar(0));
  cv::Mat best_magnitude(image.size(), CV_32S, cv::Scalar(0));
  cv::Mat dx, dy;
  for (const cv::Mat& channel : channels) {
    cv::Sobel(channel, dx, CV_16S, 1, 0, 3);
    cv::Sobel(channel, dy, CV_16S, 0, 1, 3);
    for (int r = 0; r < image.rows; ++r) {
      const short* gx = dx.ptr<short>(r);
      const short* gy = dy.ptr<short>(r);
      int* m = best_magnitude.ptr<int>(r);
      short* bx = best_dx.ptr<short>(r);
      short* by = best_dy.ptr<short>(r);
      for (int c = 0; c < image.cols; ++c) {
        const int magnitude = gx[c] * gx[c] + gy[c] * gy[c];
        if (magnitude <= m[c]) continue;
        m[c] = magnitude;
        bx[c] = gx[c];
        by[c] = gy[c];
      }
    }
  }
  cv::Mat bins(image.size(), CV_8U, cv::Scalar(255));
  const int min_squared = static_cast<int>(kMinMagnitude * kMinMagnitude);
  for (int r = 0; r < image.rows; ++r) {
    const int* m = best_magnitude.ptr<int>(r);
    const short* bx = best_dx.ptr<short>(r);
    const short* by = best_dy.ptr<short>(r);
    std::uint8_t* out = bins.ptr<std::uint8_t>(r);
    for (int c = 0; c < image.cols; ++c)
      if (m[c] >= min_squared) out[c] = static_cast<std::uint8_t>(OrientationResponses::bin_of(bx[c], by[c]));
  }
  // Keep a pixel's bin only where its neighbourhood agrees.
  cv::Mat kept(image.size(), CV_8U, cv::Scalar(255));
  for (int r = 1; r + 1 < image.rows; ++r)
    for (int c = 1; c + 1 < image.cols; ++c) {
      const std::uint8_t bin = bins.ptr<std::uint8_t>(r)[c];
      if (bin == 255) continue;
      int agreeing = 0;
      for (int i = -1; i <= 1; ++i) {
        const std::uint8_t* row = bins.ptr<std::uint8_t>(r + i);
        for (int j = -1; j <= 1; ++j) agreeing += row[c + j] == bin;
      }
      if (agreeing >= kMinAgreeing) kept.ptr<std::uint8_t>(r)[c] = bin;
    }
  return kept;
}

/// OR of the orientation bits within kSpreadRadius (separable: rows, then columns).
cv::Mat spread_orientations(const cv::Mat& bins) {
  constexpr int R = OrientationResponses::kSpreadRadius;
  cv::Mat bits(bins.size(), CV_8U, cv::Scalar(0));
  for (int r = 0; r < bins.rows; ++r) {
    const std::uint8_t* in = bins.ptr<std::uint8_t>(r);
    std::uint8_t* out = bits.ptr<std::uint8_t>(r);
    for (int c = 0; c < bins.cols; ++c)
      if (in[c] != 255) out[c] = static_cast<std::uint8_t>(1u << in[c]);
  }
  cv::Mat rows(bins.size(), CV_8U, cv::Scalar(0));
  for (int r = 0; r < bins.rows; ++r) {
    const std::uint8_t* in = bits.ptr<std::uint8_t>(r);
    std::uint8_t* out = rows.ptr<std::uint8_t>(r);
    for (int c = 0; c < bins.cols; ++c)
      for (int k = std::max(0, c - R); k <= std::min(bins.cols - 1, c + R); ++k) out[c] |= in[k];
  }
  cv::Mat spread(bins.size(), CV_8U, cv::Scalar(0));
  for (int r = 0; r < bins.rows; ++r) {
    std::uint8_t* out = spread.ptr<std::uint8_t>(r);
    for (int k = std::max(0, r - R); k <= std::min(bins.rows - 1, r + R); ++k) {
      const std::uint8_t* in = rows.ptr<std::uint8_t>(k);
      for (int c = 0; c < bins.cols; ++c) out[c] |= in[c];
    }
  }
  return spread;
}

}  // namespace

int OrientationResponses::bin_of(float dx, float dy) {
  constexpr float kPi = 3.14159265358979f;
  float angle = std::atan2(dy, dx);
  if (angle < 0.f) angle += kPi;
  const int bin = static_cast<int>(angle / kPi * kBins);
  return bin >= kBins ? 0 : bin;  // angle == pi is orientation 0
}

void OrientationResponses::compute(const cv::Mat& image, const cv::Mat& usable) {
  static const auto table = response_table();
  width_ = image.cols;
  height_ = image.rows;
  spread_ = spread_orientations(quantised_orientations(image));
  if (!usable.empty()) spread_.setTo(0, usable == 0);
  const int cols = grid_cols(), rows = grid_rows(), size = grid_size();
  for (int bin = 0; bin < kBins; ++bin) {
    std::vector<std::uint8_t>& linear = linear_[bin];
    linear.assign(static_cast<std::size_t>(kStride * kStride) * size, 0);
    const std::array<std::uint8_t, 256>& answer = table[bin];
    for (int py = 0; py < kStride; ++py)
      for (int px = 0; px < kStride; ++px) {
        std::uint8_t* out = linear.data() + static_cast<std::size_t>(py * kStride + px) * size;
        for (int r = 0; r < rows; ++r) {
          const std::uint8_t* in = spread_.ptr<std::uint8_t>(r * kStride + py);
          for (int c = 0; c < cols; ++c) out[r * cols + c] = answer[in[c * kStride + px]];
        }
      }
  }
}

}  // namespace icgp
