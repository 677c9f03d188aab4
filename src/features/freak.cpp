// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/features/freak.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <tuple>

#include "grey_image.h"

namespace icgp {

namespace {

// Ring k has radius kRingRatio^k of the outer one: 7 rings then span a factor 11, so at
// the default scale the innermost ring (about 2 px) still differs from the centre.
constexpr float kRingRatio = 2.f / 3.f;
// A field's half side relative to its ring's radius: neighbours on a ring (one radius
// apart) touch, and the staggered fields of the next ring overlap both.
constexpr float kFieldSizeRatio = 0.5f;
// No field is smaller than one pixel: below that a box only interpolates a single pixel.
constexpr float kMinHalfSize = 0.5f;
// Scales below half the reference size are not covered: there the innermost ring's
// fields are already down to a pixel at the default pattern scale.
constexpr float kMinScale = 0.5f;
// The orientation uses the 5 outer rings: the 2 inner ones span only a few pixels at
// ORB's sizes, so their differences are dominated by pixel noise.
constexpr int kOrientationRings = 5;
constexpr int kOrientationPairs = kOrientationRings * 9;

/// Bilinear interpolation of the integral image (CV_64F, (rows + 1) × (cols + 1)) at the
/// continuous point (x, y), pixel (i, j) covering [j, j + 1) × [i, i + 1). The integral of
/// a piecewise-constant image is bilinear inside each cell, so this is exact; the caller
/// guarantees 0 <= x < cols and 0 <= y < rows.
double integral_at(const cv::Mat& sums, double x, double y) {
  // x = cols exactly (float rounding at the border) reads as the cell before it, fx = 1.
  const int x0 = std::min(static_cast<int>(x), sums.cols - 2), y0 = std::min(static_cast<int>(y), sums.rows - 2);
  const double fx = x - x0, fy = y - y0;
  const double* top = sums.ptr<double>(y0) + x0;
  const double* bottom = sums.ptr<double>(y0 + 1) + x0;
  return (1 - fy) * ((1 - fx) * top[0] + fx * top[1]) + fy * ((1 - fx) * bottom[0] + fx * bottom[1]);
}

/// Mean intensity over the square of half side h centred at (x, y).
float box_mean(const cv::Mat& sums, double x, double y, double h) {
  const double sum = integral_at(sums, x + h, y + h) - integral_at(sums, x - h, y + h) -
                     integral_at(sums, x + h, y - h) + integral_at(sums, x - h, y - h);
  return static_cast<float>(sum / (4 * h * h));
}

std::array<Freak::Pair, kOrientationPairs> make_orientation_pairs() {
  std::array<Freak::Pair, kOrientationPairs> pairs;
  int n = 0;
  for (int ring = 0; ring < kOrientationRings; ++ring) {
    const int first = ring * Freak::kFieldsPerRing;
    auto field = [&](int j) { return static_cast<std::uint8_t>(first + j % Freak::kFieldsPerRing); };
    for (int j = 0; j < Freak::kFieldsPerRing; ++j) pairs[n++] = {field(j), field(j + 2)};  // 120° apart
    for (int j = 0; j < Freak::kFieldsPerRing / 2; ++j) pairs[n++] = {field(j), field(j + 3)};  // opposite
  }
  return pairs;
}

const std::array<Freak::Pair, kOrientationPairs>& orientation_pairs() {
  static const auto pairs = make_orientation_pairs();
  return pairs;
}

std::array<Freak::Field, Freak::kFields> make_pattern() {
  std::array<Freak::Field, Freak::kFields> fields;
  for (int ring = 0; ring < Freak::kRings; ++ring) {
    const float radius = std::pow(kRingRatio, static_cast<float>(ring));
    const double turn = ring % 2 == 1 ? CV_PI / Freak::kFieldsPerRing : 0.0;
    for (int j = 0; j < Freak::kFieldsPerRing; ++j) {
      const double angle = turn + 2 * CV_PI * j / Freak::kFieldsPerRing;
      fields[ring * Freak::kFieldsPerRing + j] = {
          {radius * static_cast<float>(std::cos(angle)), radius * static_cast<float>(std::sin(angle))},
          kFieldSizeRatio * radius, ring};
    }
  }
  // The centre continues the rings' progression of sizes.
  fields[Freak::kFields - 1] = {
      {0.f, 0.f}, kFieldSizeRatio * std::pow(kRingRatio, static_cast<float>(Freak::kRings)), Freak::kRings};
  return fields;
}

std::array<Freak::Pair, Freak::kPairs> make_descriptor_pairs() {
  const auto& fields = Freak::pattern();
  std::vector<Freak::Pair> candidates;
  for (int a = 0; a < Freak::kFields; ++a)
    for (int b = a + 1; b < Freak::kFields; ++b)
      if (fields[b].ring - fields[a].ring <= 2) candidates.emplace_back(a, b);
  auto key = [&](const Freak::Pair& p) {
    const int ra = fields[p.first].ring, rb = fields[p.second].ring;
    return std::make_tuple(ra + rb, ra - rb, p.first, p.second);  // fields[a].ring <= fields[b].ring
  };
  std::sort(candidates.begin(), candidates.end(), [&](const auto& p, const auto& q) { return key(p) < key(q); });
  CV_Assert(candidates.size() >= Freak::kPairs);
  std::array<Freak::Pair, Freak::kPairs> pairs;
  std::copy_n(candidates.begin(), Freak::kPairs, pairs.begin());
  return pairs;
}

}  // namespace

const std::array<Freak::Field, Freak::kFields>& Freak::pattern() {
  static const auto fields = make_pattern();
  return fields;
}

const std::array<Freak::Pair, Freak::kPairs>& Freak::descriptorPairs() {
  static const auto pairs = make_descriptor_pairs();
  return pairs;
}

cv::Ptr<Freak> Freak::create(bool orientation_normalized, bool scale_normalized, float pattern_scale, int n_octaves) {
  return cv::makePtr<Freak>(orientation_normalized, scale_normalized, pattern_scale, n_octaves);
}

Freak::Freak(bool orientation_normalized, bool scale_normalized, float pattern_scale, int n_octaves)
    : orientation_normalized_(orientation_normalized),
      scale_normalized_(scale_normalized),
      pattern_scale_(pattern_scale),
      min_scale_(kMinScale),
      max_scale_(kMinScale * std::exp2(static_cast<float>(n_octaves))) {
  if (!(pattern_scale > 0.f) || !std::isfinite(pattern_scale) || n_octaves < 1)
    throw std::invalid_argument("Freak needs pattern_scale > 0 and n_octaves >= 1");
}

float Freak::scale_of(const cv::KeyPoint& keypoint) const {
  if (!scale_normalized_) return 1.f;
  // std::clamp would pass a NaN size through; max/min with the bound first do not.
  return std::min(max_scale_, std::max(min_scale_, keypoint.size / kReferenceKeypointSize));
}

void Freak::detectAndCompute(cv::InputArray image, cv::InputArray mask, std::vector<cv::KeyPoint>& keypoints,
                             cv::OutputArray descriptors, bool useProvidedKeypoints) {
  if (!useProvidedKeypoints)
    CV_Error(cv::Error::StsNotImplemented, "icgp::Freak only describes given keypoints; detect them first");
  if (image.empty()) keypoints.clear();
  if (!mask.empty()) cv::KeyPointsFilter::runByPixelsMask(keypoints, mask.getMat());

  // The pattern reaches |offset| + half side from the keypoint in any orientation; the
  // outer ring reaches furthest at every scale (also when half sides are clamped). Pixel
  // (i, j) covers [j, j + 1), so keypoint coordinates (pixel centres) shift by half a pixel.
  const cv::Size size = image.size();
  const float outer_half_size = pattern()[0].half_size;
  keypoints.erase(std::remove_if(keypoints.begin(), keypoints.end(),
                                 [&](const cv::KeyPoint& k) {
                                   const float radius = pattern_scale_ * scale_of(k);
                                   const float reach = radius + std::max(radius * outer_half_size, kMinHalfSize);
                                   const float x = k.pt.x + 0.5f, y = k.pt.y + 0.5f;
                                   return !(x - reach >= 0.f && x + reach < size.width && y - reach >= 0.f &&
                                            y + reach < size.height);
                                 }),
                  keypoints.end());
  if (keypoints.empty()) {
    descriptors.release();
    return;
  }

  const cv::Mat grey = grey_image(image.getMat());
  cv::Mat sums;
  cv::integral(grey, sums, CV_64F);

  descriptors.create(static_cast<int>(keypoints.size()), descriptorSize(), CV_8U);
  cv::Mat out = descriptors.getMat();
  for (std::size_t k = 0; k < keypoints.size(); ++k) describe(sums, keypoints[k], out.ptr<std::uint8_t>(static_cast<int>(k)));
}

void Freak::describe(const cv::Mat& sums, cv::KeyPoint& keypoint, std::uint8_t* descriptor) const {
  const float radius = pattern_scale_ * scale_of(keypoint);
  const double x = keypoint.pt.x + 0.5, y = keypoint.pt.y + 0.5;
  const auto& fields = pattern();
  std::array<float, kFields> intensity;
  auto sample = [&](float cos_a, float sin_a) {
    for (int i = 0; i < kFields; ++i) {
      const Field& f = fields[i];
      const float dx = radius * (cos_a * f.offset.x - sin_a * f.offset.y);
      const float dy = radius * (sin_a * f.offset.x + cos_a * f.offset.y);
      intensity[i] = box_mean(sums, x + dx, y + dy, std::max(radius * f.half_size, kMinHalfSize));
    }
  };

  sample(1.f, 0.f);
  if (orientation_normalized_) {
    float ox = 0.f, oy = 0.f;
    for (const auto& [a, b] : orientation_pairs()) {
      const cv::Point2f d = fields[a].offset - fields[b].offset;
      const float weight = (intensity[a] - intensity[b]) / std::hypot(d.x, d.y);
      ox += weight * d.x;
      oy += weight * d.y;
    }
    const float angle = std::atan2(oy, ox);
    sample(std::cos(angle), std::sin(angle));
    const float degrees = angle * static_cast<float>(180.0 / CV_PI);
    keypoint.angle = degrees < 0.f ? degrees + 360.f : degrees;
  }

  std::fill(descriptor, descriptor + descriptorSize(), std::uint8_t{0});
  const auto& pairs = descriptorPairs();
  for (int b = 0; b < kPairs; ++b)
    if (intensity[pairs[b].first] > intensity[pairs[b].second]) descriptor[b / 8] |= static_cast<std::uint8_t>(1u << (b % 8));
}

}  // namespace icgp
