// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/modality/residual_noise.h"

#include <algorithm>
#include <cmath>

namespace icgp {

void ResidualNoise::estimate_from_residuals() {
  estimate_ = -1.0;
  // estimate() collects nothing when neither estimation nor robust weights are on.
  if (static_cast<int>(residuals_.size()) < std::max(1, params_.min_residuals)) return;
  for (float& r : residuals_) r = std::abs(r);
  const auto middle = residuals_.begin() + static_cast<std::ptrdiff_t>(residuals_.size() / 2);
  std::nth_element(residuals_.begin(), middle, residuals_.end());
  // 1.4826 = 1 / Φ⁻¹(3/4): the median of |u| for u ~ N(0, σ²) is σ / 1.4826.
  if (std::isfinite(*middle)) estimate_ = 1.4826 * static_cast<double>(*middle);
}

void ResidualNoise::discount(double known_variance, double own_fit) {
  if (estimate_ < 0.0) return;
  estimate_ = std::sqrt(std::max(estimate_ * estimate_ - known_variance, 0.0));
  if (own_fit < 0.0) return;
  const double standard_error = 1.166 * own_fit / std::sqrt(static_cast<double>(residuals_.size()));
  if (estimate_ <= own_fit + 2.0 * standard_error) estimate_ = own_fit;
}

double ResidualNoise::sigma(double scheduled) const { return params_.estimate ? scale(scheduled) : scheduled; }

double ResidualNoise::scale(double scheduled) const {
  if (estimate_ < 0.0) return scheduled;
  return std::min(scheduled, std::max(params_.floor, estimate_));
}

}  // namespace icgp
