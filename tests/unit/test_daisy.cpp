// SPDX-License-Identifier: GPL-2.0-or-later
// The DAISY descriptor against truth computed here: its grid, a direct evaluation of the
// paper's formula, step edges of known normal, and matching under rotation and scale.
#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

#include "icgp/features/daisy.h"

using namespace icgp;

namespace {

constexpr double kDegree = CV_PI / 180.0;

/// Seeded random grey blocks of 3..16 px, blurred: texture at every point.
cv::Mat textured_image(int size, unsigned seed) {
  cv::RNG rng(seed);
  cv::Mat image(size, size, CV_8U, cv::Scalar(128));
  for (int i = 0; i < size * size / 40; ++i) {
    const cv::Point corner(rng.uniform(-8, size), rng.uniform(-8, size));
    const cv::Size extent(rng.uniform(3, 17), rng.uniform(3, 17));
    cv::rectangle(image, cv::Rect(corner, extent), cv::Scalar(rng.uniform(0, 256)), cv::FILLED);
  }
  cv::GaussianBlur(image, image, cv::Size(), 1.0);
  return image;
}

std::vector<cv::Point2f> random_points(int count, cv::Point2f centre, float radius, unsigned seed) {
  cv::RNG rng(seed);
  std::vector<cv::Point2f> points;
  while (static_cast<int>(points.size()) < count) {
    const cv::Point2f offset(rng.uniform(-radius, radius), rng.uniform(-radius, radius));
    if (std::hypot(offset.x, offset.y) <= radius) points.push_back(centre + offset);
  }
  return points;
}

cv::Mat describe(Daisy& daisy, const cv::Mat& image, std::vector<cv::KeyPoint>& keypoints) {
  cv::Mat descriptors;
  daisy.compute(image, keypoints, descriptors);
  return descriptors;
}

struct MatchStats {
  double accuracy;      // nearest neighbour is the true one and passes the 0.7 ratio test
  double median_true;   // median L2 distance between corresponding descriptors
  double median_false;  // ... and between non-corresponding ones
};

/// Row i of `a` corresponds to row i of `b`.
MatchStats match(const cv::Mat& a, const cv::Mat& b) {
  REQUIRE(a.rows == b.rows);
  int correct = 0;
  std::vector<double> true_distances, false_distances;
  for (int i = 0; i < a.rows; ++i) {
    double best = std::numeric_limits<double>::infinity(), second = best;
    int best_index = -1;
    for (int j = 0; j < b.rows; ++j) {
      const double d = cv::norm(a.row(i), b.row(j), cv::NORM_L2);
      (i == j ? true_distances : false_distances).push_back(d);
      if (d < best) {
        second = best;
        best = d;
        best_index = j;
      } else if (d < second) {
        second = d;
      }
    }
    if (best_index == i && best < 0.7 * second) ++correct;
  }
  const auto median = [](std::vector<double>& v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  return {static_cast<double>(correct) / a.rows, median(true_distances), median(false_distances)};
}

/// Every histogram of H values has unit L2 norm or is zero.
void check_histograms(const cv::Mat& descriptors, int orientations) {
  for (int r = 0; r < descriptors.rows; ++r)
    for (int h = 0; h < descriptors.cols / orientations; ++h) {
      const cv::Mat histogram = descriptors.row(r).colRange(h * orientations, (h + 1) * orientations);
      REQUIRE(cv::checkRange(histogram));
      const double norm = cv::norm(histogram);
      CHECK((norm == Approx(1.0).epsilon(1e-4) || norm == 0.0));
    }
}

/// The paper's descriptor evaluated straight from its definition, in double precision and
/// with untruncated Gaussians over the whole image: histogram k of H values at
/// centre + s·rot(θ)·offset_k, bin o summing max(cos(θ + 2πo/H) I_x + sin(...) I_y, 0),
/// with central differences (the border pixel repeated).
std::vector<double> reference_descriptor(const cv::Mat& image, const cv::KeyPoint& kp,
                                         const std::vector<cv::Point2d>& offsets, const std::vector<double>& sigmas,
                                         double scale, double angle, int orientations) {
  const auto at = [&](int x, int y) {
    return static_cast<double>(
        image.at<std::uint8_t>(std::clamp(y, 0, image.rows - 1), std::clamp(x, 0, image.cols - 1)));
  };
  std::vector<double> descriptor;
  for (std::size_t k = 0; k < offsets.size(); ++k) {
    const double px = kp.pt.x + scale * (std::cos(angle) * offsets[k].x - std::sin(angle) * offsets[k].y);
    const double py = kp.pt.y + scale * (std::sin(angle) * offsets[k].x + std::cos(angle) * offsets[k].y);
    const double sigma = scale * sigmas[k];
    std::vector<double> histogram(orientations, 0.0);
    for (int y = 0; y < image.rows; ++y)
      for (int x = 0; x < image.cols; ++x) {
        const double gx = 0.5 * (at(x + 1, y) - at(x - 1, y)), gy = 0.5 * (at(x, y + 1) - at(x, y - 1));
        const double w = std::exp(-((x - px) * (x - px) + (y - py) * (y - py)) / (2 * sigma * sigma));
        for (int o = 0; o < orientations; ++o) {
          const double a = angle + 2 * CV_PI * o / orientations;
          histogram[o] += w * std::max(std::cos(a) * gx + std::sin(a) * gy, 0.0);
        }
      }
    double norm = 0;
    for (double v : histogram) norm += v * v;
    for (double v : histogram) descriptor.push_back(norm > 0 ? v / std::sqrt(norm) : 0.0);
  }
  return descriptor;
}

}  // namespace

TEST_CASE("DAISY reference layout: centre plus 3 rings of 8, 25 unit histograms of 8 bins") {
  const cv::Ptr<Daisy> daisy = Daisy::create();
  CHECK(daisy->descriptorSize() == 200);
  CHECK(daisy->descriptorType() == CV_32F);
  CHECK(daisy->defaultNorm() == cv::NORM_L2);

  // R = 15, Q = 3, T = 8: ring i at 15·i/3 px, point j at 45°·j, σ = ring radius / 2.
  std::vector<cv::Point2d> offsets{{0, 0}};
  std::vector<double> sigmas{2.5};
  for (int ring = 1; ring <= 3; ++ring)
    for (int j = 0; j < 8; ++j) {
      offsets.emplace_back(5.0 * ring * std::cos(45 * j * kDegree), 5.0 * ring * std::sin(45 * j * kDegree));
      sigmas.push_back(2.5 * ring);
    }
  const auto& grid = daisy->grid();
  REQUIRE(grid.size() == 25);
  for (std::size_t k = 0; k < grid.size(); ++k) {
    INFO("histogram " << k);
    CHECK(grid[k].offset.x == Approx(offsets[k].x).margin(1e-5));
    CHECK(grid[k].offset.y == Approx(offsets[k].y).margin(1e-5));
    CHECK(grid[k].sigma == Approx(sigmas[k]));
  }

  // The descriptor is that grid sampled as the paper defines it, also scaled and rotated
  // (by a bin's 45° and by 30°, between bins). The margins cover cutting the Gaussians, the
  // halved resolutions and the interpolation between directions.
  const cv::Mat image = textured_image(120, 7);
  std::vector<cv::KeyPoint> keypoints{cv::KeyPoint(60.f, 60.f, Daisy::kReferenceKeypointSize, -1.f),
                                      cv::KeyPoint(59.3f, 60.6f, 1.5f * Daisy::kReferenceKeypointSize, 45.f),
                                      cv::KeyPoint(60.4f, 59.8f, Daisy::kReferenceKeypointSize, 30.f)};
  const cv::Mat descriptors = describe(*daisy, image, keypoints);
  REQUIRE(descriptors.rows == 3);
  REQUIRE(descriptors.cols == 200);
  check_histograms(descriptors, 8);
  for (int r = 0; r < descriptors.rows; ++r) {
    const double scale = keypoints[r].size / Daisy::kReferenceKeypointSize;
    const double angle = std::max(keypoints[r].angle, 0.f) * kDegree;
    const std::vector<double> expected = reference_descriptor(image, keypoints[r], offsets, sigmas, scale, angle, 8);
    double worst = 0, mean = 0;
    for (int i = 0; i < 200; ++i) {
      const double error = std::abs(expected[i] - descriptors.at<float>(r, i));
      worst = std::max(worst, error);
      mean += error / 200;
    }
    INFO("keypoint " << r << ": worst " << worst << ", mean " << mean);
    CHECK(worst < 0.02);
    CHECK(mean < 0.005);
  }
}

TEST_CASE("DAISY: a straight step edge peaks in the bin of its normal") {
  struct Case {
    int orientations;
    std::vector<double> normals_deg;
  };
  // 8 bins of 45° (the paper's) and 5 of 72° (an odd count), normals on and between bins.
  for (const Case& c : {Case{8, {0.0, 30.0, 100.0, 135.0, 200.0, 290.0}}, Case{5, {0.0, 30.0, 144.0, 216.0, 288.0}}}) {
    const int h = c.orientations;
    const cv::Ptr<Daisy> daisy = Daisy::create(15.f, 3, 8, h);
    const cv::Point2f centre(50.f, 50.f);
    for (const double normal_deg : c.normals_deg) {
      // Bright where (p - centre)·n > 0: the gradient points along n.
      const cv::Point2d n(std::cos(normal_deg * kDegree), std::sin(normal_deg * kDegree));
      cv::Mat image(101, 101, CV_8U);
      for (int y = 0; y < image.rows; ++y)
        for (int x = 0; x < image.cols; ++x)
          image.at<std::uint8_t>(y, x) = (x - centre.x) * n.x + (y - centre.y) * n.y > 0 ? 200 : 50;
      for (const float keypoint_angle : {-1.f, 10.f, 60.f}) {
        // Bin o looks along the keypoint angle + o·360°/H: the nearest to the normal wins.
        const double relative = normal_deg - std::max(keypoint_angle, 0.f);
        const int expected_bin = static_cast<int>((std::lround(relative / (360.0 / h)) % h + h) % h);
        std::vector<cv::KeyPoint> keypoints{cv::KeyPoint(centre, 31.f, keypoint_angle)};
        const cv::Mat descriptors = describe(*daisy, image, keypoints);
        REQUIRE(descriptors.rows == 1);
        int nonzero = 0;
        for (int k = 0; k < 25; ++k) {
          const cv::Mat histogram = descriptors.colRange(h * k, h * k + h);
          if (cv::norm(histogram) == 0) continue;
          ++nonzero;
          cv::Point peak;
          cv::minMaxLoc(histogram, nullptr, nullptr, nullptr, &peak);
          INFO(h << " bins, normal " << normal_deg << "°, keypoint angle " << keypoint_angle << "°, histogram " << k);
          CHECK(peak.x == expected_bin);
        }
        CHECK(nonzero > 0);
      }
    }
  }
}

TEST_CASE("DAISY with keypoint orientation matches a rotated image") {
  const cv::Ptr<Daisy> daisy = Daisy::create();
  const int size = 240;
  const cv::Mat image = textured_image(size, 11);
  const cv::Point2f centre(0.5f * (size - 1), 0.5f * (size - 1));
  // Points whose whole support (37.5 px) stays in the disc both images share.
  const std::vector<cv::Point2f> points = random_points(150, centre, 75.f, 3);
  for (const double rotation_deg : {30.0, 45.0, 90.0}) {
    const double c = std::cos(rotation_deg * kDegree), s = std::sin(rotation_deg * kDegree);
    // x' = centre + rot(α)(x - centre), in image axes like cv::KeyPoint::angle.
    const cv::Matx23d to_rotated(c, -s, centre.x - c * centre.x + s * centre.y, s, c,
                                 centre.y - s * centre.x - c * centre.y);
    cv::Mat rotated;
    cv::warpAffine(image, rotated, to_rotated, image.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
    std::vector<cv::KeyPoint> original, turned;
    for (const cv::Point2f& p : points) {
      original.emplace_back(p, 31.f, 0.f);
      turned.emplace_back(
          cv::Point2f(static_cast<float>(to_rotated(0, 0) * p.x + to_rotated(0, 1) * p.y + to_rotated(0, 2)),
                      static_cast<float>(to_rotated(1, 0) * p.x + to_rotated(1, 1) * p.y + to_rotated(1, 2))),
          31.f, static_cast<float>(rotation_deg));
    }
    const cv::Mat a = describe(*daisy, image, original), b = describe(*daisy, rotated, turned);
    REQUIRE(a.rows == 150);
    REQUIRE(b.rows == 150);
    const MatchStats stats = match(a, b);
    INFO("rotation " << rotation_deg << "°: accuracy " << stats.accuracy << ", median distance " << stats.median_true
                     << " (corresponding) vs " << stats.median_false);
    CHECK(stats.median_true < 0.1 * stats.median_false);
    CHECK(stats.accuracy > 0.9);
  }
}

TEST_CASE("DAISY with keypoint scale matches a 1.5x enlarged image") {
  const cv::Ptr<Daisy> daisy = Daisy::create();
  const cv::Mat image = textured_image(200, 5);
  cv::Mat enlarged;
  cv::resize(image, enlarged, cv::Size(300, 300), 0, 0, cv::INTER_LINEAR);
  const std::vector<cv::Point2f> points = random_points(150, {99.5f, 99.5f}, 60.f, 4);
  std::vector<cv::KeyPoint> original, scaled;
  for (const cv::Point2f& p : points) {
    original.emplace_back(p, 31.f, 0.f);
    // Pixel centres: x' + 0.5 = 1.5 (x + 0.5).
    scaled.emplace_back((p + cv::Point2f(0.5f, 0.5f)) * 1.5f - cv::Point2f(0.5f, 0.5f), 1.5f * 31.f, 0.f);
  }
  const cv::Mat a = describe(*daisy, image, original), b = describe(*daisy, enlarged, scaled);
  REQUIRE(a.rows == 150);
  REQUIRE(b.rows == 150);
  const MatchStats stats = match(a, b);
  INFO("scale 1.5: accuracy " << stats.accuracy << ", median distance " << stats.median_true << " (corresponding) vs "
                              << stats.median_false);
  CHECK(stats.median_true < 0.1 * stats.median_false);
  CHECK(stats.accuracy > 0.8);
}

TEST_CASE("DAISY handles border keypoints, odd keypoints and empty input") {
  const cv::Ptr<Daisy> daisy = Daisy::create();
  const cv::Mat image = textured_image(64, 2);
  const float nan = std::numeric_limits<float>::quiet_NaN();

  SECTION("keypoints at and beyond the border") {
    std::vector<cv::KeyPoint> keypoints{{0.f, 0.f, 31.f, 10.f},   {63.f, 63.f, 31.f, 200.f}, {0.f, 40.f, 31.f},
                                        {63.f, 0.f, 80.f, 300.f}, {-5.f, 10.f, 31.f},        {10.f, 64.5f, 31.f},
                                        {nan, 5.f, 31.f},         {5.f, 5.f, 1e30f, nan},    {6.f, 6.f, 0.f, -1.f},
                                        {7.f, 7.f, nan, 1e30f},   {32.f, 32.f, 1e-30f, 45.f}};
    const cv::Mat descriptors = describe(*daisy, image, keypoints);
    CHECK(keypoints.size() == 8);  // the three centres outside the image are removed
    REQUIRE(descriptors.rows == static_cast<int>(keypoints.size()));
    check_histograms(descriptors, 8);
    // A corner keypoint still sees the texture through its centre histogram.
    CHECK(cv::norm(descriptors.row(0).colRange(0, 8)) == Approx(1.0));
  }
  SECTION("a tiny, a colour and a float image") {
    std::vector<cv::KeyPoint> keypoints{{0.f, 0.f, 31.f}};
    CHECK(describe(*daisy, cv::Mat(1, 1, CV_8U, cv::Scalar(9)), keypoints).rows == 1);
    cv::Mat colour, floating;
    cv::cvtColor(image, colour, cv::COLOR_GRAY2BGR);
    image.convertTo(floating, CV_32F, 1.0 / 255);
    std::vector<cv::KeyPoint> centre{{32.f, 32.f, 31.f, 20.f}};
    const cv::Mat from_grey = describe(*daisy, image, centre);
    CHECK(cv::norm(describe(*daisy, colour, centre), from_grey, cv::NORM_INF) < 1e-4);
    CHECK(cv::norm(describe(*daisy, floating, centre), from_grey, cv::NORM_INF) < 1e-4);
  }
  SECTION("empty image or no keypoints") {
    std::vector<cv::KeyPoint> keypoints{{5.f, 5.f, 31.f}};
    CHECK(describe(*daisy, cv::Mat(), keypoints).empty());  // cv::Feature2D::compute stops here
    cv::Mat descriptors(3, 3, CV_32F);
    daisy->detectAndCompute(cv::Mat(), cv::noArray(), keypoints, descriptors, true);
    CHECK(descriptors.empty());
    CHECK(keypoints.empty());
    CHECK(describe(*daisy, image, keypoints).empty());
    std::vector<cv::KeyPoint> outside{{-1.f, -1.f, 31.f}};
    CHECK(describe(*daisy, image, outside).empty());
    CHECK(outside.empty());
  }
  SECTION("it describes, it does not detect; parameters are checked") {
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    CHECK_THROWS_AS(daisy->detectAndCompute(image, cv::noArray(), keypoints, descriptors), cv::Exception);
    CHECK_THROWS_AS(Daisy::create(0.f), std::invalid_argument);
    CHECK_THROWS_AS(Daisy::create(15.f, 0), std::invalid_argument);
    CHECK(Daisy::create(10.f, 2, 6, 4)->descriptorSize() == (1 + 2 * 6) * 4);
  }
  SECTION("without use_keypoint_orientation / _scale, angle / size change nothing") {
    const cv::Ptr<Daisy> fixed = Daisy::create(15.f, 3, 8, 8, false, false);
    std::vector<cv::KeyPoint> plain{{32.f, 32.f, 31.f, -1.f}}, turned{{32.f, 32.f, 50.f, 70.f}};
    CHECK(cv::norm(describe(*fixed, image, plain), describe(*fixed, image, turned), cv::NORM_INF) == 0.0);
    CHECK(cv::norm(describe(*daisy, image, plain), describe(*daisy, image, turned), cv::NORM_INF) > 0.1);
  }
}

// Not part of the suite (hidden tag); run: test_daisy "[.benchmark]"
TEST_CASE("DAISY time for ORB's 300 keypoints on a 200x200 crop", "[.benchmark]") {
  const cv::Mat crop = textured_image(200, 21);
  std::vector<cv::KeyPoint> detected;
  cv::ORB::create(300, 1.2f, 3)->detect(crop, detected);
  const cv::Ptr<Daisy> daisy = Daisy::create();
  std::vector<double> milliseconds;
  for (int run = 0; run < 51; ++run) {
    std::vector<cv::KeyPoint> keypoints = detected;
    cv::Mat descriptors;
    const auto start = std::chrono::steady_clock::now();
    daisy->compute(crop, keypoints, descriptors);
    milliseconds.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::nth_element(milliseconds.begin(), milliseconds.begin() + 25, milliseconds.end());
  WARN(detected.size() << " keypoints: median " << milliseconds[25] << " ms");
}
