// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <array>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

namespace icgp {

/// Foreground and background colour statistics p(y|f), p(y|b) over n_bins per channel
/// (ALGORITHMS.md §4), with a lookup table of the pixel-wise posterior P_f(y).
/// Works on BGR (n_bins³ bins) and grey images (min(256, n_bins³) bins).
class ColorHistograms {
 public:
  /// n_bins must be a power of two in [2, 64]; channels 1 or 3.
  ColorHistograms(int n_bins, int channels);

  int channels() const { return channels_; }

  /// Counting pass: clear(), add pixels, then set_from_counts() or blend_counts().
  void clear_counts();
  void add_foreground(const cv::Mat& image, int row, int col) { ++count_f_[bin(image, row, col)]; }
  void add_background(const cv::Mat& image, int row, int col) { ++count_b_[bin(image, row, col)]; }
  /// Histograms := normalised counts (on start). Returns false when either side is empty
  /// (then nothing changes).
  bool set_from_counts();
  /// h <- (1 - rate) h + rate * normalised counts, per side (after each frame).
  bool blend_counts(double rate_f, double rate_b);

  /// P_f(y) of the pixel: p(y|f) / (p(y|f) + p(y|b)), 0.5 when both are 0, kept within
  /// [0.001, 0.999].
  float foreground_posterior(const cv::Mat& image, int row, int col) const {
    return posterior_f_[bin(image, row, col)];
  }
  /// The same for a pixel given by its address in an image of kChannels == channels()
  /// channels: the form for per-pixel loops, with the channel count known at compile time.
  template <int kChannels>
  float foreground_posterior(const std::uint8_t* pixel) const {
    if constexpr (kChannels == 1) return posterior_f_[channel_bins_[0][pixel[0]]];
    return posterior_f_[channel_bins_[0][pixel[0]] + channel_bins_[1][pixel[1]] + channel_bins_[2][pixel[2]]];
  }

 private:
  int bin(const cv::Mat& image, int row, int col) const {
    const std::uint8_t* p = image.ptr<std::uint8_t>(row) + channels_ * col;
    return channels_ == 1 ? channel_bins_[0][p[0]] : channel_bins_[0][p[0]] + channel_bins_[1][p[1]] + channel_bins_[2][p[2]];
  }
  void update_posteriors();

  int n_bins_;
  int channels_;
  /// Each channel value's contribution to the bin index: the bin of a pixel is the sum over
  /// its channels, a few table reads instead of shifts and multiplies per pixel.
  std::array<std::array<std::uint32_t, 256>, 3> channel_bins_{};
  std::vector<float> hist_f_, hist_b_, posterior_f_;
  std::vector<std::uint32_t> count_f_, count_b_;
};

}  // namespace icgp
