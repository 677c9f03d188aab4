// SPDX-License-Identifier: GPL-2.0-or-later
// ResidualNoise against samples of known distribution: the robust scale, its clamping to
// [floor, schedule], and Tukey's weight as the derivative of its loss.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "icgp/modality/residual_noise.h"

using namespace icgp;

namespace {

std::vector<float> gaussian(int n, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> normal(0.f, static_cast<float>(sigma));
  std::vector<float> v(n);
  for (float& x : v) x = normal(rng);
  return v;
}

/// Hands `residuals` to ResidualNoise::estimate.
void estimate(ResidualNoise& noise, const std::vector<float>& residuals) {
  noise.estimate([&](auto add) {
    for (float r : residuals) add(r);
  });
}

}  // namespace

TEST_CASE("residual noise: the scale of Gaussian residuals is their standard deviation") {
  ResidualNoise noise;
  for (double sigma : {1e-4, 0.7, 12.0}) {
    std::vector<float> r = gaussian(4000, sigma, 1);
    estimate(noise, r);
    INFO("sigma " << sigma << " estimate " << noise.estimated());
    CHECK(std::abs(noise.estimated() / sigma - 1.0) < 0.05);
  }
}

TEST_CASE("residual noise: a tenth of wild residuals moves the scale little, a common offset counts") {
  ResidualNoise noise;
  std::vector<float> r = gaussian(3600, 0.5, 2);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> wild(-200.f, 200.f);
  for (int i = 0; i < 400; ++i) r.push_back(wild(rng));
  estimate(noise, r);
  // The median of |u| then sits at the 0.5/0.9 quantile of the inliers' |u|: 1.13 sigma.
  CHECK(noise.estimated() == Approx(0.5 * 1.13).epsilon(0.06));

  // Residuals that agree with each other but not with zero are not precise: a cue whose
  // every residual is 2 px off must not be trusted to 0.01 px.
  std::vector<float> offset = gaussian(1000, 0.01, 4);
  for (float& x : offset) x += 2.f;
  estimate(noise, offset);
  CHECK(noise.estimated() == Approx(1.4826 * 2.0).epsilon(0.02));
}

TEST_CASE("residual noise: a known variance taken out of the scale leaves the rest, kept where it exceeds the own fit") {
  // Residuals of σ = 0.6 spread further by an independent error of σ = 1.5: their scale is
  // √(0.6² + 1.5²); the known 1.5² taken out leaves 0.6.
  ResidualNoise noise;
  std::vector<float> r = gaussian(8000, 0.6, 5), spread = gaussian(8000, 1.5, 6);
  for (std::size_t i = 0; i < r.size(); ++i) r[i] += spread[i];
  estimate(noise, r);
  CHECK(noise.estimated() == Approx(std::hypot(0.6, 1.5)).epsilon(0.04));
  noise.discount(1.5 * 1.5, 0.1);
  CHECK(noise.estimated() == Approx(0.6).epsilon(0.12));
  // More known variance than the residuals show: the own fit, or zero without one.
  estimate(noise, r);
  noise.discount(9.0, 0.3);
  CHECK(noise.estimated() == Approx(0.3));
  estimate(noise, r);
  noise.discount(9.0, -1.0);
  CHECK(noise.estimated() == 0.0);
  // 100 residuals of scale exactly 1: the own fit's standard error is 11.66 % of it. Above
  // an own fit of 0.9 by less than twice that, 1 is within sampling error; above 0.8 it is not.
  std::vector<float> unit(100);
  for (std::size_t i = 0; i < unit.size(); ++i) unit[i] = (i % 2 ? 1.f : -1.f) / 1.4826f;
  estimate(noise, unit);
  REQUIRE(noise.estimated() == Approx(1.0));
  noise.discount(0.0, 0.9);
  CHECK(noise.estimated() == Approx(0.9));
  estimate(noise, unit);
  noise.discount(0.0, 0.8);
  CHECK(noise.estimated() == Approx(1.0));
  // Without an estimate there is nothing to discount: the schedule stays in force.
  estimate(noise, gaussian(5, 1.0, 7));
  noise.discount(1.0, 0.5);
  CHECK(noise.estimated() < 0.0);
  CHECK(noise.sigma(3.0) == 3.0);
}

TEST_CASE("residual noise: the standard deviation used is the estimate within [floor, schedule]") {
  NoiseParams params;
  params.floor = 0.3;
  params.min_residuals = 10;
  ResidualNoise noise(params);
  CHECK(noise.sigma(1.5) == 1.5);  // no estimate yet: the schedule

  std::vector<float> r = gaussian(1000, 0.8, 5);
  estimate(noise, r);
  CHECK(noise.sigma(1.5) == Approx(noise.estimated()));
  CHECK(noise.sigma(0.5) == 0.5);  // the schedule is the upper bound
  std::vector<float> tiny = gaussian(1000, 1e-3, 6);
  estimate(noise, tiny);
  CHECK(noise.sigma(1.5) == 0.3);  // the floor

  std::vector<float> few = gaussian(9, 0.8, 7);
  estimate(noise, few);
  CHECK(noise.estimated() < 0.0);
  CHECK(noise.sigma(1.5) == 1.5);

  estimate(noise, tiny);
  noise.reset();
  CHECK(noise.sigma(1.5) == 1.5);
}

TEST_CASE("residual noise: switched off, the schedule and plain least squares") {
  NoiseParams params;
  params.estimate = params.robust = false;
  ResidualNoise noise(params);
  std::vector<float> r = gaussian(1000, 0.1, 8);
  estimate(noise, r);
  CHECK(noise.estimated() < 0.0);  // nothing asked for an estimate
  CHECK(noise.sigma(2.0) == 2.0);
  CHECK(noise.weight(50.f, 2.0) == 1.f);
  CHECK(noise.loss(3.0) == Approx(4.5));
}

TEST_CASE("residual noise: robust weights on the measured scale while the schedule weighs the cue") {
  NoiseParams params;
  params.estimate = false;
  params.floor = 0.05;
  params.min_residuals = 10;
  ResidualNoise noise(params);
  std::vector<float> r = gaussian(1000, 0.1, 9);
  estimate(noise, r);
  CHECK(noise.sigma(2.0) == 2.0);                          // the schedule weighs the cue
  CHECK(noise.scale(2.0) == Approx(noise.estimated()));    // the residuals' own scatter
  CHECK(noise.scale(2.0) == Approx(0.1).epsilon(0.1));
  const double c = params.tukey_constant, scale = noise.scale(2.0);
  CHECK(noise.weight(static_cast<float>(0.5 * scale), scale) > 0.9f);
  CHECK(noise.weight(static_cast<float>(1.01 * c * scale), scale) == 0.f);  // an outlier of the scatter
  std::vector<float> tiny = gaussian(1000, 1e-3, 10);
  estimate(noise, tiny);
  CHECK(noise.scale(2.0) == 0.05);  // the floor
}

TEST_CASE("residual noise: Tukey's weight is the derivative of its loss over the residual") {
  ResidualNoise noise;
  const double sigma = 0.2, c = noise.params().tukey_constant;
  CHECK(noise.weight(0.f, sigma) == 1.f);
  CHECK(noise.weight(static_cast<float>(1.01 * c * sigma), sigma) == 0.f);
  for (double u : {0.05, 0.3, 0.7, 0.9}) {
    // weight(u, σ) is ψ(x)/x with x = u/σ, ψ = ρ'.
    const double x = u / sigma, h = 1e-6;
    const double psi = (noise.loss(x + h) - noise.loss(x - h)) / (2 * h);
    INFO("u " << u);
    CHECK(noise.weight(static_cast<float>(u), sigma) == Approx(psi / x).epsilon(1e-4));
  }
  CHECK(noise.loss(10 * c) == Approx(c * c / 6));
}
