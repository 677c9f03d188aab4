// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/modality/contour_posterior.h"

#include <algorithm>
#include <cmath>

namespace icgp {

double ContourPosterior::slope_at(int d) const {
  const int before = std::max(d - 1, 0), after = std::min(d + 1, n_ - 1);
  return (double{log_p_[after]} - log_p_[before]) / (after - before);
}

double ContourPosterior::slope(double x) const {
  const int lower = static_cast<int>(std::floor(x));
  if (!subpixel_) return double{log_p_[lower + 1]} - log_p_[lower];
  const double fraction = x - lower;
  return (1.0 - fraction) * slope_at(lower) + fraction * slope_at(lower + 1);
}

double ContourPosterior::log(double x) const {
  const int lower = static_cast<int>(std::floor(x));
  const double fraction = x - lower;
  if (!subpixel_) return (1.0 - fraction) * log_p_[lower] + fraction * log_p_[lower + 1];
  // The trapezoid rule integrates each interval's linear slope exactly.
  double value = log_p_[0];
  for (int d = 0; d < lower; ++d) value += 0.5 * (slope_at(d) + slope_at(d + 1));
  const double s0 = slope_at(lower), s1 = slope_at(lower + 1);
  return value + s0 * fraction + 0.5 * (s1 - s0) * fraction * fraction;
}

}  // namespace icgp
