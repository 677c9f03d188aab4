// SPDX-License-Identifier: GPL-2.0-or-later
// The FREAK descriptor: its pattern and pairs against the paper's description, the
// orientation and bits on linear ramps (known answers), and matching under known
// rotations and scalings of a synthetic texture.
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>
#include <set>

#include "icgp/features/freak.h"
#include "test_noise.h"

using namespace icgp;

namespace {

/// Random grey rectangles, slightly blurred: corners for ORB at every scale.
cv::Mat textured_image(int size, std::uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat image(size, size, CV_8U, cv::Scalar(128));
  for (int i = 0; i < size * size / 150; ++i) {
    const int w = rng.uniform(3, 40), h = rng.uniform(3, 40);
    const cv::Point corner(rng.uniform(-w, size), rng.uniform(-h, size));
    cv::rectangle(image, cv::Rect(corner, cv::Size(w, h)), cv::Scalar(rng.uniform(0, 256)), cv::FILLED);
  }
  cv::GaussianBlur(image, image, cv::Size(), 1.0);
  return image;
}

/// I = g · (x, y) in float. Box means follow the ramp up to the pixels' staircase, which
/// shifts the smallest fields by hundredths of a grey level.
cv::Mat ramp_image(int size, double angle_deg) {
  const double gx = std::cos(angle_deg * CV_PI / 180.0), gy = std::sin(angle_deg * CV_PI / 180.0);
  cv::Mat image(size, size, CV_32F);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) image.at<float>(y, x) = static_cast<float>(1000.0 + gx * x + gy * y);
  return image;
}

std::vector<cv::KeyPoint> orb_keypoints(const cv::Mat& image) {
  std::vector<cv::KeyPoint> keypoints;
  cv::ORB::create(400)->detect(image, keypoints);
  return keypoints;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

struct Matching {
  int described = 0;        ///< keypoints kept in both images
  double matched_bits = 0;  ///< median Hamming distance between corresponding keypoints
  double other_bits = 0;    ///< median between non-corresponding ones
  double precision = 0;     ///< correct among the nearest neighbours that pass the ratio test
  double recall = 0;        ///< correct ratio-test matches among all described keypoints
};

/// Describes keypoints_a[i] in a and keypoints_b[i] (the same scene point) in b, then
/// matches each kept a-descriptor to its nearest b-descriptor with Lowe's ratio test (0.8).
Matching match(Freak& freak, const cv::Mat& a, std::vector<cv::KeyPoint> keypoints_a, const cv::Mat& b,
               std::vector<cv::KeyPoint> keypoints_b) {
  for (std::size_t i = 0; i < keypoints_a.size(); ++i) keypoints_a[i].class_id = keypoints_b[i].class_id = static_cast<int>(i);
  cv::Mat descriptors_a, descriptors_b;
  freak.compute(a, keypoints_a, descriptors_a);
  freak.compute(b, keypoints_b, descriptors_b);
  std::map<int, int> row_b;
  for (std::size_t j = 0; j < keypoints_b.size(); ++j) row_b[keypoints_b[j].class_id] = static_cast<int>(j);
  cv::Mat da, db;
  for (std::size_t i = 0; i < keypoints_a.size(); ++i) {
    const auto found = row_b.find(keypoints_a[i].class_id);
    if (found == row_b.end()) continue;
    da.push_back(descriptors_a.row(static_cast<int>(i)));
    db.push_back(descriptors_b.row(found->second));
  }
  Matching m;
  m.described = da.rows;
  if (da.rows < 2) return m;
  std::vector<double> matched, other;
  for (int i = 0; i < da.rows; ++i) {
    matched.push_back(cv::norm(da.row(i), db.row(i), cv::NORM_HAMMING));
    other.push_back(cv::norm(da.row(i), db.row((i + da.rows / 2) % da.rows), cv::NORM_HAMMING));
  }
  std::vector<std::vector<cv::DMatch>> knn;
  cv::BFMatcher(cv::NORM_HAMMING).knnMatch(da, db, knn, 2);
  int accepted = 0, correct = 0;
  for (int i = 0; i < da.rows; ++i) {
    if (!(knn[i][0].distance < 0.8f * knn[i][1].distance)) continue;
    ++accepted;
    if (knn[i][0].trainIdx == i) ++correct;
  }
  m.matched_bits = median(matched);
  m.other_bits = median(other);
  m.precision = accepted > 0 ? static_cast<double>(correct) / accepted : 0.0;
  m.recall = static_cast<double>(correct) / da.rows;
  return m;
}

/// The central size × size crops of a texture and of the texture turned by `degrees`
/// about its centre (both fully textured; the turned one noisy), with a's ORB keypoints
/// and their images in b.
struct RotatedPair {
  cv::Mat a, b;
  std::vector<cv::KeyPoint> keypoints_a, keypoints_b;
};

RotatedPair rotated_pair(const cv::Mat& texture, int size, double degrees) {
  const cv::Point2f centre(0.5f * (texture.cols - 1), 0.5f * (texture.rows - 1));
  const cv::Mat turn = cv::getRotationMatrix2D(centre, degrees, 1.0);
  cv::Mat turned;
  cv::warpAffine(texture, turned, turn, texture.size(), cv::INTER_LINEAR);
  const cv::Rect crop((texture.cols - size) / 2, (texture.rows - size) / 2, size, size);
  RotatedPair p{texture(crop).clone(), test::with_noise(turned(crop), 4.0, 7), {}, {}};
  p.keypoints_a = orb_keypoints(p.a);
  const cv::Matx23d m = turn;
  for (cv::KeyPoint k : p.keypoints_a) {
    const cv::Point2d big(k.pt.x + crop.x, k.pt.y + crop.y);
    k.pt = cv::Point2f(static_cast<float>(m(0, 0) * big.x + m(0, 1) * big.y + m(0, 2) - crop.x),
                       static_cast<float>(m(1, 0) * big.x + m(1, 1) * big.y + m(1, 2) - crop.y));
    p.keypoints_b.push_back(k);
  }
  return p;
}

std::string describe(const Matching& m) {
  return "described " + std::to_string(m.described) + ", median matched " + std::to_string(m.matched_bits) +
         " bits, other " + std::to_string(m.other_bits) + " bits, precision " + std::to_string(m.precision) +
         ", recall " + std::to_string(m.recall);
}

const cv::Mat& texture() {
  static const cv::Mat image = textured_image(900, 20240611);
  return image;
}

}  // namespace

TEST_CASE("FREAK: 512-bit binary descriptor compared by Hamming distance") {
  const cv::Ptr<Freak> freak = Freak::create();
  CHECK(freak->descriptorSize() == 64);
  CHECK(freak->descriptorType() == CV_8U);
  CHECK(freak->defaultNorm() == cv::NORM_HAMMING);

  const cv::Mat image = texture()(cv::Rect(0, 0, 320, 240));
  std::vector<cv::KeyPoint> keypoints = orb_keypoints(image);
  REQUIRE(keypoints.size() > 50);
  cv::Mat descriptors;
  freak->compute(image, keypoints, descriptors);
  REQUIRE(!keypoints.empty());
  CHECK(descriptors.rows == static_cast<int>(keypoints.size()));
  CHECK(descriptors.cols == 64);
  CHECK(descriptors.type() == CV_8UC1);
}

TEST_CASE("FREAK: retinal pattern of 43 fields on 7 exponentially growing rings") {
  const auto& fields = Freak::pattern();
  const auto radius = [&](int ring) { return std::hypot(fields[ring * 6].offset.x, fields[ring * 6].offset.y); };
  CHECK(fields[42].offset == cv::Point2f(0.f, 0.f));
  CHECK(fields[42].ring == 7);
  for (int ring = 0; ring < 7; ++ring) {
    std::set<long> angles;
    for (int j = 0; j < 6; ++j) {
      const Freak::Field& f = fields[ring * 6 + j];
      CHECK(f.ring == ring);
      CHECK(std::hypot(f.offset.x, f.offset.y) == Approx(radius(ring)));
      CHECK(f.half_size == Approx(fields[ring * 6].half_size));
      angles.insert(std::lround(std::atan2(f.offset.y, f.offset.x) * 180.0 / CV_PI + 360.0) % 360);
    }
    // Six fields 60° apart; odd rings are turned by 30°.
    const std::set<long> expected = ring % 2 == 0 ? std::set<long>{0, 60, 120, 180, 240, 300}
                                                  : std::set<long>{30, 90, 150, 210, 270, 330};
    CHECK(angles == expected);
    if (ring > 0) {
      CHECK(radius(ring) / radius(ring - 1) == Approx(radius(1) / radius(0)));  // geometric radii
      CHECK(fields[ring * 6].half_size / radius(ring) == Approx(fields[0].half_size / radius(0)));
      CHECK(radius(ring) < radius(ring - 1));
    }
  }
  CHECK(radius(0) == Approx(1.f));
}

TEST_CASE("FREAK: 512 distinct pairs in 4 cascades from the periphery to the centre") {
  const auto& fields = Freak::pattern();
  const auto& pairs = Freak::descriptorPairs();
  std::set<std::pair<int, int>> distinct;
  for (const auto& [a, b] : pairs) {
    REQUIRE(a < 43);
    REQUIRE(b < 43);
    REQUIRE(a != b);
    distinct.insert({std::min(a, b), std::max(a, b)});
  }
  CHECK(distinct.size() == 512);
  std::set<int> used;
  double previous_mean_ring = -1.0;
  for (int cascade = 0; cascade < 4; ++cascade) {
    double ring_sum = 0.0;
    for (int b = cascade * 128; b < (cascade + 1) * 128; ++b) {
      ring_sum += fields[pairs[b].first].ring + fields[pairs[b].second].ring;
      used.insert(pairs[b].first);
      used.insert(pairs[b].second);
    }
    const double mean_ring = ring_sum / 256.0;
    CAPTURE(cascade, mean_ring);
    CHECK(mean_ring > previous_mean_ring + 0.5);
    previous_mean_ring = mean_ring;
  }
  CHECK(used.size() == 43);  // every field contributes
}

TEST_CASE("FREAK: orientation and bits on a linear ramp") {
  // For I = g · p the paper's orientation sum is a positive multiple of g, whatever the
  // scale, and after turning the pattern onto g a pair's bit says which field lies further
  // along g, i.e. which has the larger x in the unturned pattern.
  const auto& fields = Freak::pattern();
  const auto& pairs = Freak::descriptorPairs();
  for (const double angle : {0.0, 37.0, 135.0, 250.0}) {
    CAPTURE(angle);
    const cv::Mat ramp = ramp_image(200, angle);
    std::vector<cv::KeyPoint> keypoints{cv::KeyPoint(100.f, 100.f, 31.f), cv::KeyPoint(99.3f, 101.6f, 50.f)};
    cv::Mat descriptors;
    Freak::create()->compute(ramp, keypoints, descriptors);
    REQUIRE(keypoints.size() == 2);
    for (int k = 0; k < 2; ++k) {
      CHECK(keypoints[k].angle == Approx(angle).margin(0.05));
      for (int b = 0; b < 512; ++b) {
        const float along = fields[pairs[b].first].offset.x - fields[pairs[b].second].offset.x;
        if (std::abs(along) < 1e-3f) continue;  // equal intensities: rounding decides
        CAPTURE(k, b);
        CHECK(((descriptors.at<std::uint8_t>(k, b / 8) >> (b % 8)) & 1) == (along > 0.f ? 1 : 0));
      }
    }
  }
}

TEST_CASE("FREAK: deterministic") {
  const cv::Mat image = texture()(cv::Rect(100, 100, 400, 300));
  const std::vector<cv::KeyPoint> keypoints = orb_keypoints(image);
  std::vector<cv::KeyPoint> k1 = keypoints, k2 = keypoints;
  cv::Mat d1, d2;
  Freak::create()->compute(image, k1, d1);
  Freak::create()->compute(image.clone(), k2, d2);
  REQUIRE(d1.rows > 0);
  REQUIRE(k1.size() == k2.size());
  CHECK(cv::norm(d1, d2, cv::NORM_HAMMING) == 0.0);
  for (std::size_t i = 0; i < k1.size(); ++i) CHECK(k1[i].angle == k2[i].angle);
}

TEST_CASE("FREAK: rotation invariance") {
  const cv::Ptr<Freak> freak = Freak::create();
  for (const double degrees : {30.0, 60.0, 90.0}) {
    const RotatedPair p = rotated_pair(texture(), 480, degrees);
    const Matching m = match(*freak, p.a, p.keypoints_a, p.b, p.keypoints_b);
    INFO(degrees << "°: " << describe(m));
    REQUIRE(m.described > 100);
    CHECK(m.matched_bits < 0.25 * 512);
    CHECK(m.other_bits > 2 * m.matched_bits);
    CHECK(m.precision > 0.9);
    CHECK(m.recall > 0.6);
  }
}

TEST_CASE("FREAK: scale invariance") {
  const cv::Ptr<Freak> freak = Freak::create();
  const cv::Mat a = texture()(cv::Rect(150, 150, 600, 600));
  const std::vector<cv::KeyPoint> keypoints_a = orb_keypoints(a);
  for (const double factor : {1.5, 0.7}) {
    cv::Mat b;
    cv::resize(a, b, cv::Size(), factor, factor, factor > 1 ? cv::INTER_LINEAR : cv::INTER_AREA);
    b = test::with_noise(b, 4.0, 11);
    std::vector<cv::KeyPoint> keypoints_b;
    for (cv::KeyPoint k : keypoints_a) {
      // cv::resize maps pixel centres: x' + 0.5 = factor (x + 0.5).
      k.pt = (k.pt + cv::Point2f(0.5f, 0.5f)) * static_cast<float>(factor) - cv::Point2f(0.5f, 0.5f);
      k.size *= static_cast<float>(factor);
      keypoints_b.push_back(k);
    }
    const Matching m = match(*freak, a, keypoints_a, b, keypoints_b);
    INFO(factor << "×: " << describe(m));
    REQUIRE(m.described > 100);
    CHECK(m.matched_bits < 0.25 * 512);
    CHECK(m.other_bits > 2 * m.matched_bits);
    CHECK(m.precision > 0.9);
    CHECK(m.recall > 0.6);
  }
}

TEST_CASE("FREAK: without orientation normalisation rotations break matching") {
  const cv::Ptr<Freak> fixed = Freak::create(false);
  for (const double degrees : {60.0, 90.0}) {
    const RotatedPair p = rotated_pair(texture(), 480, degrees);
    const Matching m = match(*fixed, p.a, p.keypoints_a, p.b, p.keypoints_b);
    INFO(degrees << "°: " << describe(m));
    REQUIRE(m.described > 100);
    CHECK(m.matched_bits > 0.35 * 512);
    CHECK(m.recall < 0.2);
  }
  // Unrotated, the same descriptor matches: the failure above is the rotation's.
  const RotatedPair p = rotated_pair(texture(), 480, 0.0);
  const Matching m = match(*fixed, p.a, p.keypoints_a, p.b, p.keypoints_b);
  INFO("0°: " << describe(m));
  CHECK(m.recall > 0.9);
}

TEST_CASE("FREAK: border keypoints removed, empty input handled") {
  const cv::Ptr<Freak> freak = Freak::create();
  const cv::Mat image = texture()(cv::Rect(0, 0, 200, 160));
  // At the reference size the outer ring (22 px) plus its half side (11 px) reaches 33 px.
  std::vector<cv::KeyPoint> keypoints{cv::KeyPoint(100.f, 80.f, 31.f), cv::KeyPoint(2.f, 80.f, 31.f),
                                      cv::KeyPoint(100.f, 158.f, 31.f), cv::KeyPoint(40.f, 80.f, 31.f),
                                      cv::KeyPoint(100.f, 80.f, 31.f * 3),  // reaches 99 px
                                      cv::KeyPoint(-50.f, -50.f, 31.f), cv::KeyPoint(NAN, 80.f, 31.f)};
  cv::Mat descriptors;
  freak->compute(image, keypoints, descriptors);
  REQUIRE(keypoints.size() == 2);
  CHECK(keypoints[0].pt == cv::Point2f(100.f, 80.f));
  CHECK(keypoints[1].pt == cv::Point2f(40.f, 80.f));
  CHECK(descriptors.rows == 2);

  std::vector<cv::KeyPoint> none;
  freak->compute(image, none, descriptors);
  CHECK(none.empty());
  CHECK(descriptors.empty());

  std::vector<cv::KeyPoint> some{cv::KeyPoint(100.f, 80.f, 31.f)};
  freak->detectAndCompute(cv::Mat(), cv::noArray(), some, descriptors, true);
  CHECK(some.empty());
  CHECK(descriptors.empty());
  some = {cv::KeyPoint(100.f, 80.f, 31.f)};
  freak->compute(cv::Mat(), some, descriptors);
  CHECK(descriptors.empty());

  CHECK_THROWS(freak->detect(image, keypoints));
  CHECK_THROWS_AS(Freak::create(true, true, 0.f), std::invalid_argument);
}
