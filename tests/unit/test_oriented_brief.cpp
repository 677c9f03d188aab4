// SPDX-License-Identifier: GPL-2.0-or-later
// The ORB-style extractor: its pattern against BRIEF's G II, detection limits, Harris
// ranking and orientation against direct computations, the bits on a linear ramp (known
// answers), and orientation and matching under known rotations of a synthetic texture.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <set>
#include <vector>

#include "icgp/features/oriented_brief.h"
#include "test_noise.h"

using namespace icgp;

namespace {

/// Random grey rectangles and discs, slightly blurred: corners and blobs at all angles.
cv::Mat textured_image(int size, std::uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat image(size, size, CV_8U, cv::Scalar(128));
  for (int i = 0; i < size * size / 200; ++i) {
    const cv::Scalar grey(rng.uniform(0, 256));
    if (rng.uniform(0, 2) == 0) {
      const int w = rng.uniform(3, 30), h = rng.uniform(3, 30);
      cv::rectangle(image, cv::Rect(rng.uniform(-w, size), rng.uniform(-h, size), w, h), grey, cv::FILLED);
    } else {
      cv::circle(image, cv::Point(rng.uniform(0, size), rng.uniform(0, size)), rng.uniform(2, 12), grey, cv::FILLED,
                 cv::LINE_AA);
    }
  }
  cv::GaussianBlur(image, image, cv::Size(), 0.8);
  return image;
}

const cv::Mat& texture() {
  static const cv::Mat image = textured_image(300, 20110611);
  return image;
}

constexpr int kCrop = 200;  // the tracker's focused crop

/// The central kCrop² crops of the texture and of the texture turned by `degrees` (counter-
/// clockwise on screen, cv::getRotationMatrix2D's convention) about its centre, the turned
/// one noisy, and the map from a's pixels to b's.
struct RotatedPair {
  cv::Mat a, b;
  cv::Matx23d a_to_b;
};

RotatedPair rotated_pair(double degrees) {
  const cv::Mat& t = texture();
  const cv::Point2f centre(0.5f * (t.cols - 1), 0.5f * (t.rows - 1));
  const cv::Matx23d turn = cv::getRotationMatrix2D(centre, degrees, 1.0);
  cv::Mat turned;
  cv::warpAffine(t, turned, turn, t.size(), cv::INTER_LINEAR);
  const cv::Rect crop((t.cols - kCrop) / 2, (t.rows - kCrop) / 2, kCrop, kCrop);
  // p_b = turn (p_a + corner) - corner
  cv::Matx23d a_to_b = turn;
  const cv::Vec2d corner(crop.x, crop.y);
  const cv::Vec2d shift = cv::Matx22d(turn(0, 0), turn(0, 1), turn(1, 0), turn(1, 1)) * corner - corner;
  a_to_b(0, 2) += shift[0];
  a_to_b(1, 2) += shift[1];
  return {t(crop).clone(), test::with_noise(turned(crop), 2.0, 7), a_to_b};
}

cv::Point2f apply(const cv::Matx23d& m, const cv::Point2f& p) {
  return {static_cast<float>(m(0, 0) * p.x + m(0, 1) * p.y + m(0, 2)),
          static_cast<float>(m(1, 0) * p.x + m(1, 1) * p.y + m(1, 2))};
}

struct Features {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
};

Features extract(const cv::Mat& image, int n_features = 300) {
  Features f;
  OrientedBrief::create(n_features)->detectAndCompute(image, cv::noArray(), f.keypoints, f.descriptors);
  return f;
}

/// The difference a - b of two angles in degrees, in [-180, 180).
double angle_difference(double a, double b) { return std::remainder(a - b, 360.0); }

struct Matching {
  int accepted = 0;  ///< nearest neighbours that pass Lowe's ratio test (0.8)
  int correct = 0;   ///< of which land within 2 px of the true position
  double precision() const { return accepted > 0 ? static_cast<double>(correct) / accepted : 0.0; }
};

Matching match(const Features& a, const Features& b, const cv::Matx23d& a_to_b) {
  std::vector<std::vector<cv::DMatch>> knn;
  cv::BFMatcher(cv::NORM_HAMMING).knnMatch(a.descriptors, b.descriptors, knn, 2);
  Matching m;
  for (const auto& pair : knn) {
    if (pair.size() < 2 || !(pair[0].distance < 0.8f * pair[1].distance)) continue;
    ++m.accepted;
    const cv::Point2f truth = apply(a_to_b, a.keypoints[pair[0].queryIdx].pt);
    if (cv::norm(b.keypoints[pair[0].trainIdx].pt - truth) <= 2.0) ++m.correct;
  }
  return m;
}

/// The Harris response from its definition, in double: M summed over the 7×7 window of
/// the central-difference gradients, det(M) - 0.04 trace(M)².
double harris_by_definition(const cv::Mat& image, cv::Point at) {
  double xx = 0, yy = 0, xy = 0;
  for (int v = -3; v <= 3; ++v)
    for (int u = -3; u <= 3; ++u) {
      const int x = at.x + u, y = at.y + v;
      const double ix = 0.5 * (image.at<std::uint8_t>(y, x + 1) - image.at<std::uint8_t>(y, x - 1));
      const double iy = 0.5 * (image.at<std::uint8_t>(y + 1, x) - image.at<std::uint8_t>(y - 1, x));
      xx += ix * ix;
      yy += iy * iy;
      xy += ix * iy;
    }
  return xx * yy - xy * xy - 0.04 * (xx + yy) * (xx + yy);
}

bool bit(const cv::Mat& descriptors, int row, int b) {
  return ((descriptors.at<std::uint8_t>(row, b / 8) >> (b % 8)) & 1) != 0;
}

}  // namespace

TEST_CASE("OrientedBrief: 256-bit binary descriptor compared by Hamming distance") {
  const cv::Ptr<OrientedBrief> extractor = OrientedBrief::create();
  CHECK(extractor->descriptorSize() == 32);
  CHECK(extractor->descriptorType() == CV_8U);
  CHECK(extractor->defaultNorm() == cv::NORM_HAMMING);
  CHECK(extractor->getDefaultName() == "icgp.OrientedBrief");

  const Features f = extract(rotated_pair(0.0).a);
  REQUIRE(f.keypoints.size() > 50);
  CHECK(f.descriptors.rows == static_cast<int>(f.keypoints.size()));
  CHECK(f.descriptors.cols == 32);
  CHECK(f.descriptors.type() == CV_8UC1);
  for (const cv::KeyPoint& k : f.keypoints) {
    CHECK(k.size == 31.f);
    CHECK(k.octave == 0);
    CHECK(k.angle >= 0.f);
    CHECK(k.angle < 360.f);
  }

  CHECK_THROWS_AS(OrientedBrief::create(0), std::invalid_argument);
  CHECK_THROWS_AS(OrientedBrief::create(300, 0), std::invalid_argument);
  CHECK_THROWS_AS(OrientedBrief::create(300, 255), std::invalid_argument);
  CHECK_NOTHROW(OrientedBrief::create(1, 254));
}

TEST_CASE("OrientedBrief: BRIEF's G II pattern inside the 31x31 patch") {
  const auto& pairs = OrientedBrief::pattern();
  std::set<std::pair<std::pair<int, int>, std::pair<int, int>>> distinct;
  double sum = 0.0, sum_squares = 0.0;
  for (const auto& [a, b] : pairs) {
    for (const cv::Point& p : {a, b}) {
      // The 5×5 sub-window stays in the patch.
      CHECK(std::abs(p.x) <= 13);
      CHECK(std::abs(p.y) <= 13);
      sum += p.x + p.y;
      sum_squares += p.x * p.x + p.y * p.y;
    }
    CHECK(a != b);
    const std::pair<int, int> pa(a.x, a.y), pb(b.x, b.y);
    distinct.insert({std::min(pa, pb), std::max(pa, pb)});  // either order is the same test
  }
  CHECK(distinct.size() == 256);
  // N(0, (31/5)²) cut at ±13 (2.1 σ) has σ = 5.57 (5.58 once rounded to pixels); 1024
  // coordinates estimate the mean to ±0.17 and σ to ±0.15 (one standard error).
  const double mean = sum / 1024, sigma = std::sqrt(sum_squares / 1024 - mean * mean);
  CHECK(std::abs(mean) < 0.6);
  CHECK(sigma == Approx(5.58).margin(0.5));
}

TEST_CASE("OrientedBrief: deterministic") {
  const cv::Mat image = rotated_pair(30.0).b;
  const cv::Ptr<OrientedBrief> extractor = OrientedBrief::create();
  Features f1, f2, f3;
  extractor->detectAndCompute(image, cv::noArray(), f1.keypoints, f1.descriptors);
  extractor->detectAndCompute(image.clone(), cv::noArray(), f2.keypoints, f2.descriptors);
  f3 = extract(image);
  REQUIRE(!f1.keypoints.empty());
  for (const Features* other : {&f2, &f3}) {
    REQUIRE(other->keypoints.size() == f1.keypoints.size());
    for (std::size_t i = 0; i < f1.keypoints.size(); ++i) {
      CHECK(other->keypoints[i].pt == f1.keypoints[i].pt);
      CHECK(other->keypoints[i].angle == f1.keypoints[i].angle);
      CHECK(other->keypoints[i].response == f1.keypoints[i].response);
    }
    CHECK(cv::norm(other->descriptors, f1.descriptors, cv::NORM_HAMMING) == 0.0);
  }
  // BGR input is described as its grey conversion.
  cv::Mat bgr;
  cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
  const Features from_bgr = extract(bgr);
  REQUIRE(from_bgr.keypoints.size() == f1.keypoints.size());
  CHECK(cv::norm(from_bgr.descriptors, f1.descriptors, cv::NORM_HAMMING) == 0.0);
}

TEST_CASE("OrientedBrief: no corners on a blank image, none near the border, at most n_features") {
  const Features blank = extract(cv::Mat(kCrop, kCrop, CV_8U, cv::Scalar(90)));
  CHECK(blank.keypoints.empty());
  CHECK(blank.descriptors.empty());

  std::vector<cv::KeyPoint> keypoints{cv::KeyPoint(100.f, 100.f, 31.f)};
  cv::Mat descriptors;
  OrientedBrief::create()->detectAndCompute(cv::Mat(), cv::noArray(), keypoints, descriptors);
  CHECK(keypoints.empty());
  CHECK(descriptors.empty());

  // The border covers the orientation disk of radius 15 and the 5×5 sub-windows of the
  // pattern turned by each multiple of 12° (rounded to pixels), and not much more.
  int reach = 0;
  double radius = 0.0;
  for (int bin = 0; bin < 30; ++bin) {
    const double c = std::cos(bin * CV_PI / 15), s = std::sin(bin * CV_PI / 15);
    for (const auto& [a, b] : OrientedBrief::pattern())
      for (const cv::Point& q : {a, b}) {
        reach = std::max({reach, std::abs(cvRound(c * q.x - s * q.y)), std::abs(cvRound(s * q.x + c * q.y))});
        radius = std::max(radius, cv::norm(q));
      }
  }
  const int border = OrientedBrief::borderWidth();
  CHECK(border >= reach + 2);
  CHECK(border >= 15);
  CHECK(border <= std::max(radius + 3, 17.0));

  const cv::Mat image = rotated_pair(0.0).a;
  const Features all = extract(image, 100000);
  REQUIRE(all.keypoints.size() > 100);
  for (const cv::KeyPoint& k : all.keypoints) {
    CHECK(k.pt.x >= border);
    CHECK(k.pt.y >= border);
    CHECK(k.pt.x <= kCrop - 1 - border);
    CHECK(k.pt.y <= kCrop - 1 - border);
  }

  // The n best by Harris response are kept.
  const int n = 40;
  const Features best = extract(image, n);
  REQUIRE(best.keypoints.size() == static_cast<std::size_t>(n));
  std::vector<float> responses;
  for (const cv::KeyPoint& k : all.keypoints) responses.push_back(k.response);
  std::sort(responses.rbegin(), responses.rend());
  for (const cv::KeyPoint& k : best.keypoints) CHECK(k.response >= responses[n - 1]);

  // Given keypoints too close to the border, not finite or masked out are dropped.
  cv::Mat mask(image.size(), CV_8U, cv::Scalar(255));
  mask(cv::Rect(0, 0, kCrop / 2, kCrop)).setTo(0);
  keypoints = {cv::KeyPoint(150.f, 100.f, 31.f), cv::KeyPoint(border - 1.f, 100.f, 31.f),
               cv::KeyPoint(150.f, kCrop - border + 0.f, 31.f), cv::KeyPoint(NAN, 100.f, 31.f),
               cv::KeyPoint(150.f, 100.f, 31.f, NAN), cv::KeyPoint(60.f, 100.f, 31.f),
               cv::KeyPoint(kCrop - 1.f - border, border + 0.f, 31.f)};
  OrientedBrief::create()->detectAndCompute(image, mask, keypoints, descriptors, true);
  REQUIRE(keypoints.size() == 2);
  CHECK(keypoints[0].pt == cv::Point2f(150.f, 100.f));
  CHECK(keypoints[1].pt == cv::Point2f(kCrop - 1.f - border, border + 0.f));
  CHECK(descriptors.rows == 2);

  // Detected corners respect the mask too.
  std::vector<cv::KeyPoint> masked;
  OrientedBrief::create()->detectAndCompute(image, mask, masked, descriptors);
  REQUIRE(!masked.empty());
  for (const cv::KeyPoint& k : masked) CHECK(k.pt.x >= kCrop / 2);
}

TEST_CASE("OrientedBrief: keypoints ranked by the Harris response") {
  const cv::Mat image = rotated_pair(0.0).a;
  const Features f = extract(image);
  REQUIRE(!f.keypoints.empty());
  for (const cv::KeyPoint& k : f.keypoints) {
    const double truth = harris_by_definition(image, cv::Point(cvRound(k.pt.x), cvRound(k.pt.y)));
    CHECK(k.response == Approx(truth).epsilon(1e-5).margin(1e-2));
  }
}

TEST_CASE("OrientedBrief: orientation and bits on a linear ramp") {
  // On I = c + g · p, the disk's intensity centroid lies along g from its centre.
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  for (const double degrees : {0.0, 37.0, 135.0, 250.0}) {
    CAPTURE(degrees);
    const double gx = std::cos(degrees * CV_PI / 180.0), gy = std::sin(degrees * CV_PI / 180.0);
    cv::Mat ramp(kCrop, kCrop, CV_8U);
    for (int y = 0; y < kCrop; ++y)
      for (int x = 0; x < kCrop; ++x)
        ramp.at<std::uint8_t>(y, x) = cv::saturate_cast<std::uint8_t>(128 + 0.6 * (gx * (x - 100) + gy * (y - 100)));
    keypoints = {cv::KeyPoint(100.f, 100.f, 31.f)};  // angle -1: to be computed
    OrientedBrief::create()->detectAndCompute(ramp, cv::noArray(), keypoints, descriptors, true);
    REQUIRE(keypoints.size() == 1);
    CHECK(std::abs(angle_difference(keypoints[0].angle, degrees)) < 1.0);
  }

  // Along +x (angle 0, the unturned pattern) and -x (180°, the pattern turned exactly),
  // a test is 1 when its first point lies further along the ramp, 0 on equal sums.
  const auto& pairs = OrientedBrief::pattern();
  for (const bool rising : {true, false}) {
    CAPTURE(rising);
    cv::Mat ramp(kCrop, kCrop, CV_8U);
    for (int x = 0; x < kCrop; ++x) ramp.col(x).setTo(cv::Scalar(rising ? x : kCrop - 1 - x));
    keypoints = {cv::KeyPoint(100.f, 100.f, 31.f), cv::KeyPoint(60.f, 140.f, 31.f)};
    OrientedBrief::create()->detectAndCompute(ramp, cv::noArray(), keypoints, descriptors, true);
    REQUIRE(keypoints.size() == 2);
    for (int k = 0; k < 2; ++k) {
      CHECK(keypoints[k].angle == (rising ? 0.f : 180.f));
      int tested = 0;
      for (int b = 0; b < 256; ++b) {
        CAPTURE(k, b);
        const int along = pairs[b].first.x - pairs[b].second.x;
        CHECK(bit(descriptors, k, b) == (along > 0));
        tested += along != 0;
      }
      CHECK(tested > 230);
    }
  }

  // A given angle is used as it is: the ramp along +x described at 180° flips every bit
  // whose points differ in x.
  cv::Mat ramp(kCrop, kCrop, CV_8U);
  for (int x = 0; x < kCrop; ++x) ramp.col(x).setTo(cv::Scalar(x));
  keypoints = {cv::KeyPoint(100.f, 100.f, 31.f, 180.f)};
  OrientedBrief::create()->detectAndCompute(ramp, cv::noArray(), keypoints, descriptors, true);
  REQUIRE(keypoints.size() == 1);
  CHECK(keypoints[0].angle == 180.f);
  for (int b = 0; b < 256; ++b) {
    CAPTURE(b);
    CHECK(bit(descriptors, 0, b) == (pairs[b].first.x < pairs[b].second.x));
  }
}

TEST_CASE("OrientedBrief: tests compare 5x5 sub-windows, steered by the nearest 12-degree bin") {
  // At 0° the pattern is used as drawn and at 180° exactly negated, so each bit is known:
  // the 5×5 sum around the first point exceeds the one around the second.
  const cv::Mat image = rotated_pair(0.0).a;
  auto window_sum = [&](cv::Point p) { return cv::sum(image(cv::Rect(p.x - 2, p.y - 2, 5, 5)))[0]; };
  const auto& pairs = OrientedBrief::pattern();
  const std::vector<cv::Point> centres{{100, 100}, {40, 150}, {160, 30}, {77, 121}};
  for (const float angle : {0.f, 180.f}) {
    std::vector<cv::KeyPoint> keypoints;
    for (const cv::Point& c : centres) keypoints.emplace_back(cv::Point2f(c), 31.f, angle);
    cv::Mat descriptors;
    OrientedBrief::create()->compute(image, keypoints, descriptors);
    REQUIRE(keypoints.size() == centres.size());
    const int sign = angle == 0.f ? 1 : -1;
    for (std::size_t k = 0; k < centres.size(); ++k)
      for (int b = 0; b < 256; ++b) {
        CAPTURE(angle, k, b);
        const double first = window_sum(centres[k] + sign * pairs[b].first);
        const double second = window_sum(centres[k] + sign * pairs[b].second);
        CHECK(bit(descriptors, static_cast<int>(k), b) == (first > second));
      }
  }

  // Given angles are taken modulo 360° and rounded to the nearest multiple of 12°.
  auto describe_at = [&](float angle) {
    std::vector<cv::KeyPoint> keypoints{cv::KeyPoint(cv::Point2f(centres[0]), 31.f, angle)};
    cv::Mat descriptors;
    OrientedBrief::create()->compute(image, keypoints, descriptors);
    REQUIRE(descriptors.rows == 1);
    return descriptors;
  };
  const cv::Mat at0 = describe_at(0.f), at12 = describe_at(12.f), at180 = describe_at(180.f);
  CHECK(cv::norm(at0, at12, cv::NORM_HAMMING) > 0.0);
  for (const float angle : {5.5f, 354.5f, 365.f, 720.f})
    CHECK(cv::norm(describe_at(angle), at0, cv::NORM_HAMMING) == 0.0);
  for (const float angle : {6.5f, 17.5f, 372.f}) CHECK(cv::norm(describe_at(angle), at12, cv::NORM_HAMMING) == 0.0);
  CHECK(cv::norm(describe_at(185.f), at180, cv::NORM_HAMMING) == 0.0);
}

TEST_CASE("OrientedBrief: orientation follows a rotation of the image") {
  for (const double degrees : {30.0, 90.0, 200.0}) {
    CAPTURE(degrees);
    const RotatedPair p = rotated_pair(degrees);
    const Features a = extract(p.a), b = extract(p.b);
    int paired = 0, agreeing = 0;
    for (const cv::KeyPoint& ka : a.keypoints) {
      const cv::Point2f truth = apply(p.a_to_b, ka.pt);
      for (const cv::KeyPoint& kb : b.keypoints) {
        if (cv::norm(kb.pt - truth) > 1.5) continue;
        ++paired;
        // The image turns counter-clockwise on screen: clockwise in the angles' y-down axes.
        if (std::abs(angle_difference(kb.angle, ka.angle - degrees)) <= 12.0) ++agreeing;
        break;
      }
    }
    INFO(agreeing << " of " << paired << " keypoints found again agree");
    REQUIRE(paired > 40);
    CHECK(agreeing >= 0.8 * paired);
  }
}

TEST_CASE("OrientedBrief: rotation invariant matching") {
  for (const double degrees : {30.0, 90.0}) {
    const RotatedPair p = rotated_pair(degrees);
    const Features a = extract(p.a), b = extract(p.b);
    const Matching m = match(a, b, p.a_to_b);
    INFO(degrees << "°: " << m.correct << " correct of " << m.accepted << " accepted, " << a.keypoints.size()
                 << " keypoints");
    CHECK(m.precision() >= 0.7);
    CHECK(m.correct > 0.4 * static_cast<double>(a.keypoints.size()));
  }
}

TEST_CASE("OrientedBrief: without steering a rotation breaks matching") {
  // The same keypoints described with the angle forced to 0 match when the image is not
  // turned, and mostly fail when it is turned by 90°.
  auto unsteered = [](const cv::Mat& image) {
    Features f = extract(image);
    for (cv::KeyPoint& k : f.keypoints) k.angle = 0.f;
    OrientedBrief::create()->compute(image, f.keypoints, f.descriptors);
    return f;
  };
  const RotatedPair still = rotated_pair(0.0);
  const Matching m0 = match(unsteered(still.a), unsteered(still.b), still.a_to_b);
  const RotatedPair turned = rotated_pair(90.0);
  const Matching m90 = match(unsteered(turned.a), unsteered(turned.b), turned.a_to_b);
  const Matching steered = match(extract(turned.a), extract(turned.b), turned.a_to_b);
  INFO("unsteered 0°: " << m0.correct << " / " << m0.accepted << ", 90°: " << m90.correct << " / " << m90.accepted
                        << "; steered 90°: " << steered.correct << " / " << steered.accepted);
  CHECK(m0.precision() >= 0.9);
  CHECK(m90.correct < 0.25 * steered.correct);
  CHECK(m90.precision() < 0.3);
}
