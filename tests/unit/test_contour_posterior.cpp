// SPDX-License-Identifier: GPL-2.0-or-later
// The region modality's contour posterior between its discrete positions, against a
// sampled Gaussian whose peak is known.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "icgp/modality/contour_posterior.h"

using icgp::ContourPosterior;

namespace {

/// exp(−(d − peak)² / (2 s²)) at d = 0 … n−1, normalised: what a line's posterior looks
/// like when its contour lies at `peak` segments.
std::vector<float> sampled_gaussian(int n, double peak, double s) {
  std::vector<float> p(n);
  double sum = 0.0;
  for (int d = 0; d < n; ++d) sum += p[d] = static_cast<float>(std::exp(-(d - peak) * (d - peak) / (2 * s * s)));
  for (float& v : p) v = static_cast<float>(v / sum);
  return p;
}

std::vector<float> logs(const std::vector<float>& p) {
  std::vector<float> log_p(p.size());
  for (std::size_t d = 0; d < p.size(); ++d) log_p[d] = std::log(p[d]);
  return log_p;
}

/// The position in [0, n − 1) where the posterior's slope changes sign from + to −.
double stationary_point(const ContourPosterior& posterior, int n) {
  double lo = 0.0, hi = n - 1 - 1e-9;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (posterior.slope(mid) > 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

TEST_CASE("contour posterior: the sub-pixel form peaks where the sampled Gaussian does") {
  const int n = 12;
  for (const double peak : {5.0, 5.1, 5.25, 5.5, 5.8, 4.37}) {
    const std::vector<float> log_p = logs(sampled_gaussian(n, peak, 1.3));
    const ContourPosterior subpixel(log_p.data(), n, true), discrete(log_p.data(), n, false);
    INFO("peak " << peak);
    // Central differences of a quadratic ln p are exact, so is their interpolation.
    CHECK(stationary_point(subpixel, n) == Approx(peak).margin(1e-3));
    // The papers' form: the slope is constant between positions, so the optimum is on a
    // whole position, up to half a segment from the peak.
    const double snapped = stationary_point(discrete, n);
    CHECK(std::abs(snapped - std::round(snapped)) < 1e-6);
    CHECK(std::abs(snapped - peak) <= 0.5 + 1e-6);
  }
}

TEST_CASE("contour posterior: slope is the derivative of log, which is continuous") {
  const int n = 12;
  // Not a Gaussian: a skewed, two-peaked posterior like a line near clutter.
  std::vector<float> p = sampled_gaussian(n, 3.4, 1.1);
  const std::vector<float> second = sampled_gaussian(n, 8.2, 0.8);
  for (int d = 0; d < n; ++d) p[d] = 0.7f * p[d] + 0.3f * second[d] + 1e-4f;
  const std::vector<float> log_p = logs(p);
  for (const bool subpixel : {true, false}) {
    const ContourPosterior posterior(log_p.data(), n, subpixel);
    INFO((subpixel ? "sub-pixel" : "discrete"));
    const double h = 1e-6;
    for (double x = 0.05; x < n - 1.05; x += 0.37) {
      INFO("x " << x);
      CHECK(posterior.slope(x) == Approx((posterior.log(x + h) - posterior.log(x - h)) / (2 * h)).margin(1e-5));
    }
    for (int d = 1; d < n - 1; ++d) {
      INFO("position " << d);
      CHECK(posterior.log(d - 1e-9) == Approx(posterior.log(d)).margin(1e-6));
    }
    if (subpixel)  // C¹: the slope is continuous too
      for (int d = 1; d < n - 1; ++d) CHECK(posterior.slope(d - 1e-9) == Approx(posterior.slope(d)).margin(1e-6));
  }
  // The discrete form is the papers' linear interpolation of ln p.
  const ContourPosterior discrete(log_p.data(), n, false);
  CHECK(discrete.log(2.25) == Approx(0.75 * std::log(p[2]) + 0.25 * std::log(p[3])));
  CHECK(discrete.slope(2.25) == Approx(std::log(p[3]) - std::log(p[2])));
}
