// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/modality/color_histograms.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace icgp {

ColorHistograms::ColorHistograms(int n_bins, int channels) : n_bins_(n_bins), channels_(channels) {
  if (n_bins < 2 || n_bins > 64 || (n_bins & (n_bins - 1)) != 0)
    throw std::invalid_argument("n_histogram_bins must be a power of two in [2, 64] (got " + std::to_string(n_bins) +
                                ")");
  if (channels != 1 && channels != 3)
    throw std::invalid_argument("colour histograms need a 1- or 3-channel 8-bit image (got " +
                                std::to_string(channels) + " channels)");
  // A grey histogram gets as many bins as a colour one would have, up to one per grey
  // level: 16 grey bins cannot tell an object from a background of similar brightness.
  if (channels == 1) n_bins_ = std::min(256, n_bins * n_bins * n_bins);
  int shift = 0;
  while ((256 >> shift) > n_bins_) ++shift;
  // Bin index ((c0 · n) + c1) · n + c2 of the channels' bins c0, c1, c2 (BGR), or c0 (grey).
  for (int c = 0; c < channels; ++c) {
    const int weight = channels == 1 ? 1 : (c == 0 ? n_bins_ * n_bins_ : c == 1 ? n_bins_ : 1);
    for (int v = 0; v < 256; ++v) channel_bins_[c][v] = static_cast<std::uint32_t>((v >> shift) * weight);
  }
  const std::size_t size = channels == 1 ? n_bins_ : n_bins_ * n_bins_ * n_bins_;
  hist_f_.assign(size, 0.f);
  hist_b_.assign(size, 0.f);
  posterior_f_.assign(size, 0.5f);
  count_f_.assign(size, 0);
  count_b_.assign(size, 0);
}

void ColorHistograms::clear_counts() {
  std::fill(count_f_.begin(), count_f_.end(), 0u);
  std::fill(count_b_.begin(), count_b_.end(), 0u);
}

namespace {
double total(const std::vector<std::uint32_t>& counts) { return std::accumulate(counts.begin(), counts.end(), 0.0); }
}  // namespace

bool ColorHistograms::set_from_counts() { return blend_counts(1.0, 1.0); }

bool ColorHistograms::blend_counts(double rate_f, double rate_b) {
  const double n_f = total(count_f_), n_b = total(count_b_);
  if (n_f == 0.0 || n_b == 0.0) return false;
  for (std::size_t i = 0; i < hist_f_.size(); ++i) {
    hist_f_[i] = static_cast<float>((1.0 - rate_f) * hist_f_[i] + rate_f * count_f_[i] / n_f);
    hist_b_[i] = static_cast<float>((1.0 - rate_b) * hist_b_[i] + rate_b * count_b_[i] / n_b);
  }
  update_posteriors();
  return true;
}

void ColorHistograms::update_posteriors() {
  // Posteriors stay a little away from 0 and 1: a segment whose pixels straddle the
  // contour then has a product of posteriors with both sides non-zero, so it reads as
  // "undecided" (0.5 when split evenly) instead of collapsing to whichever side its last
  // pixel falls on.
  constexpr float kMinPosterior = 1e-3f;
  for (std::size_t i = 0; i < hist_f_.size(); ++i) {
    const float sum = hist_f_[i] + hist_b_[i];
    const float posterior = sum > 0.f ? hist_f_[i] / sum : 0.5f;
    posterior_f_[i] = std::clamp(posterior, kMinPosterior, 1.f - kMinPosterior);
  }
}

}  // namespace icgp
