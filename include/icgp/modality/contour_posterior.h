// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

namespace icgp {

/// The log of a correspondence line's contour-location posterior p(d), known at the whole
/// positions d = 0 … n−1 (segments), as a function of a continuous position x in
/// [0, n−1]: what the region modality's likelihood reads between those positions.
///
/// * Discrete (the ICG papers): ln p interpolated linearly between the two positions
///   around x. Its slope is constant between positions, so an optimum sits on a kink,
///   at a whole position: a line's contour snaps to a segment boundary, and a straight
///   edge, whose lines share one sub-pixel offset, snaps as a whole (half a pixel at worst).
/// * Sub-pixel: the slope of ln p (its central differences inside, one-sided differences at
///   the ends) interpolated linearly, and ln p its integral from ln p(0). The function is C¹,
///   and its stationary point is the posterior's sub-segment peak, exactly where ln p is
///   quadratic (a Gaussian-shaped posterior).
class ContourPosterior {
 public:
  /// `log_distribution`: ln p at the n > 1 positions, not copied (must outlive this object).
  ContourPosterior(const float* log_distribution, int n, bool subpixel)
      : log_p_(log_distribution), n_(n), subpixel_(subpixel) {}

  /// d ln p / dx, for 0 <= x < n − 1.
  double slope(double x) const;
  /// ln p at x (up to a constant per line: the sub-pixel form starts at ln p(0) and
  /// integrates its slope), for 0 <= x < n − 1.
  double log(double x) const;

 private:
  /// The slope of the sub-pixel form at the whole position d.
  double slope_at(int d) const;

  const float* log_p_;
  int n_;
  bool subpixel_;
};

}  // namespace icgp
