// SPDX-License-Identifier: GPL-2.0-or-later
// Region and depth modalities and the tracker on rendered frames with known poses:
// analytic gradients against numeric derivatives of the log-likelihoods, convergence from
// a perturbed pose, and bad input.
#include <Eigen/Eigenvalues>
#include <atomic>
#include <catch2/catch.hpp>
#include <filesystem>
#include <limits>
#include <thread>
#include <utility>
#include <opencv2/imgproc.hpp>

#include "icgp/io/mesh_loader.h"
#include "icgp/model/model_cache.h"
#include "icgp/model/viewpoint_model_generator.h"
#include "icgp/modality/depth_modality.h"
#include "icgp/modality/region_modality.h"
#include "icgp/modality/texture_modality.h"
#include "icgp/tracker/tracker.h"
#include "icgp/tracker/tracker_builder.h"
#include "test_gradients.h"
#include "test_scene.h"

using namespace icgp;

namespace {

ViewpointModelParams coarse_model_params() {
  ViewpointModelParams p;
  p.n_divides = 2;
  p.image_size = 400;
  p.n_points = 100;
  return p;
}

struct Fixture {
  Mesh mesh = load_mesh(ICGP_MODELS_DIR "/textured_box/textured_box.obj");
  std::shared_ptr<const ViewpointModel> region_model, depth_model;
  Intrinsics color_k{650.0, 648.0, 321.3, 238.9, 640, 480};
  Intrinsics depth_k{580.0, 580.0, 318.2, 243.1, 640, 480};
  Pose depth_T_color{Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.05, 0.002, 0.001)};
  Pose truth = Pose::from_rotation_vector(Eigen::Vector3d(0.5, -0.6, 0.3), Eigen::Vector3d(0.01, -0.015, 0.45));

  Fixture() {
    // Cached in the build tree: every test case is a process of its own.
    ModelGenerationOptions quiet;
    quiet.print_progress = false;
    auto models = load_or_generate(
        mesh, {{ViewpointModel::Kind::kRegion, coarse_model_params()}, {ViewpointModel::Kind::kDepth, coarse_model_params()}},
        ICGP_TEST_CACHE_DIR, quiet);
    region_model = std::make_shared<ViewpointModel>(std::move(models[0]));
    depth_model = std::make_shared<ViewpointModel>(std::move(models[1]));
  }

  static Fixture& instance() {
    static Fixture fixture;
    return fixture;
  }
};

Pose perturbed(const Pose& pose, double mm, double deg) {
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.8, 0.5).normalized();
  const Eigen::Vector3d direction = Eigen::Vector3d(-0.6, 0.2, 0.77).normalized();
  return Pose::from_rotation_vector(axis * deg * M_PI / 180.0, direction * mm * 1e-3) * pose;
}

void check_gradient(Modality& modality, const Frame& frame, int corr_iter) {
  modality.correspondences(frame, {}, corr_iter);
  const CueTerms terms = modality.gradient_hessian(corr_iter, 0);
  const Vec6& g = terms.gradient;
  const Mat66& H = terms.hessian;
  const Vec6 numeric = test::numeric_gradient(modality, corr_iter);
  INFO(modality.name() << " corr_iter " << corr_iter << "\nanalytic " << g.transpose() << "\nnumeric  "
                       << numeric.transpose());
  CHECK(g.norm() > 0.0);
  CHECK((g - numeric).norm() < 2e-3 * numeric.norm());
  // A Newton step needs a negative semi-definite Hessian (one view of a box may leave a
  // direction unobserved by depth alone).
  CHECK(H.eigenvalues().real().maxCoeff() < 1e-9 * H.norm());
}

/// Tracks `frame` three times with region + depth after learning the colour statistics at
/// the true pose (where tracking would have left the object) and throwing the pose off by
/// 5 mm and 5 degrees; checks the result against the truth and returns it.
Pose check_convergence(const Frame& frame) {
  Fixture& f = Fixture::instance();
  Tracker tracker;
  Body& body = tracker.add_body({"box", f.mesh, f.truth});
  tracker.add_modality(std::make_unique<RegionModality>(body, f.region_model, RegionParams{}));
  tracker.add_modality(std::make_unique<DepthModality>(body, f.depth_model, DepthParams{}));
  tracker.start(frame);
  body.reference_T_body = perturbed(f.truth, 5.0, 5.0);
  std::vector<BodyResult> results;
  for (int i = 0; i < 3; ++i) results = tracker.track(frame);
  const double t_mm = 1e3 * (body.reference_T_body.translation() - f.truth.translation()).norm();
  const double r_deg = rotation_angle_between(body.reference_T_body.rotation(), f.truth.rotation()) * 180 / M_PI;
  INFO("error " << t_mm << " mm, " << r_deg << " deg, quality " << results[0].quality);
  CHECK(t_mm < 0.5);
  CHECK(r_deg < 0.2);
  CHECK(results[0].tracked);
  return body.reference_T_body;
}

}  // namespace

TEST_CASE("depth modality: gradient is the derivative of its log-likelihood") {
  Fixture& f = Fixture::instance();
  test::SceneRenderer scene(f.mesh, f.color_k, f.depth_k, f.depth_T_color);
  const Frame frame = scene.render(f.truth);
  Body body{"box", f.mesh, perturbed(f.truth, 6.0, 4.0)};
  DepthModality depth(body, f.depth_model, {});
  depth.start(frame, {});
  for (int corr_iter : {0, 2}) check_gradient(depth, frame, corr_iter);
}

TEST_CASE("region modality: gradient is the derivative of its log-likelihood") {
  Fixture& f = Fixture::instance();
  test::SceneRenderer scene(f.mesh, f.color_k, f.depth_k, f.depth_T_color);
  const Frame frame = scene.render(f.truth);
  // Iteration 0 uses the Gaussian approximation, later ones the discrete distribution,
  // read between its positions in either form (ContourPosterior).
  for (const bool subpixel : {true, false}) {
    INFO((subpixel ? "sub-pixel posterior" : "discrete posterior"));
    Body body{"box", f.mesh, perturbed(f.truth, 3.0, 2.0)};
    RegionParams params;
    params.subpixel_posterior = subpixel;
    RegionModality region(body, f.region_model, params);
    region.start(frame, {});
    for (int corr_iter : {0, 3}) check_gradient(region, frame, corr_iter);
  }
}

TEST_CASE("tracker: region + depth converge from 5 mm / 5 deg to the rendered pose") {
  Fixture& f = Fixture::instance();
  test::SceneRenderer scene(f.mesh, f.color_k, f.depth_k, f.depth_T_color);
  check_convergence(scene.render(f.truth));
}

TEST_CASE("tracker: bad depth and images give a lost quality or a clear error") {
  Fixture& f = Fixture::instance();
  test::SceneRenderer scene(f.mesh, f.color_k, f.depth_k, f.depth_T_color);
  Frame frame = scene.render(f.truth);
  Tracker tracker;
  Body& body = tracker.add_body({"box", f.mesh, f.truth});
  tracker.add_modality(std::make_unique<DepthModality>(body, f.depth_model, DepthParams{}));
  tracker.start(frame);

  SECTION("empty depth: nothing to fit, reported lost, pose unchanged") {
    frame.depths[0].depth.setTo(0.f);
    const auto results = tracker.track(frame);
    CHECK_FALSE(results[0].tracked);
    CHECK(results[0].modalities[0].n_valid == 0);
    CHECK((body.reference_T_body.translation() - f.truth.translation()).norm() < 1e-9);
  }
  SECTION("NaN depth: ignored, no crash") {
    frame.depths[0].depth.setTo(std::numeric_limits<float>::quiet_NaN());
    const auto results = tracker.track(frame);
    CHECK_FALSE(results[0].tracked);
    CHECK(body.reference_T_body.translation().allFinite());
  }
  SECTION("a depth image of the wrong size is refused with both sizes named") {
    frame.depths[0].depth = cv::Mat::zeros(240, 320, CV_32FC1);
    CHECK_THROWS_WITH(tracker.track(frame), Catch::Contains("640x480") && Catch::Contains("320x240"));
  }
  SECTION("a missing camera is named") {
    frame.depths[0].camera = "Camera3";
    CHECK_THROWS_WITH(tracker.track(frame), Catch::Contains("Camera2"));
  }
  SECTION("object behind the camera: lost, not a crash") {
    body.reference_T_body = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, -0.5));
    const auto results = tracker.track(frame);
    CHECK_FALSE(results[0].tracked);
  }
}

TEST_CASE("region modality: started with the object out of view it abstains, and the object is lost") {
  Fixture& f = Fixture::instance();
  test::SceneRenderer scene(f.mesh, f.color_k, f.depth_k, f.depth_T_color);
  const Frame frame = scene.render(f.truth);
  const Pose behind(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, -0.5));
  Tracker tracker;
  Body& body = tracker.add_body({"box", f.mesh, behind});
  tracker.add_modality(std::make_unique<RegionModality>(body, f.region_model, RegionParams{}));
  REQUIRE_NOTHROW(tracker.start(frame));
  const std::vector<BodyResult> results = tracker.track(frame);
  CHECK(results[0].modalities[0].abstained);
  CHECK_FALSE(results[0].tracked);
  CHECK((body.reference_T_body.translation() - behind.translation()).norm() < 1e-9);
}

TEST_CASE("tracker: region + depth converge on a grey image too") {
  Fixture& f = Fixture::instance();
  test::SceneRenderer scene(f.mesh, f.color_k, f.depth_k, f.depth_T_color);
  Frame frame = scene.render(f.truth);
  cv::cvtColor(frame.colors[0].image, frame.colors[0].image, cv::COLOR_BGR2GRAY);
  check_convergence(frame);
}

/// Makes `image` convert its pixels on read from the points `point_of(row, col)`, one at a
/// time or many at once, counting the pixels read each way.
template <class PointOf, class Count>
void set_counting_point_reader(DepthImage& image, PointOf point_of, Count& single_reads, Count& many_reads) {
  image.source.set_point_reader(
      [point_of, &single_reads](int row, int col) {
        ++single_reads;
        return point_of(row, col);
      },
      [point_of, &many_reads](const std::vector<cv::Point>& pixels, std::vector<Eigen::Vector3f>& points) {
        many_reads += static_cast<int>(pixels.size());
        for (const cv::Point& p : pixels) points.push_back(point_of(p.y, p.x));
      });
}

TEST_CASE("depth image: pixels not converted are read once from their source, then kept") {
  DepthImage image{"Camera2", Intrinsics{500.0, 500.0, 2.0, 1.5, 4, 3}, Pose(),
                   cv::Mat(3, 4, CV_32FC1, cv::Scalar(DepthImage::kNotConverted))};
  image.depth.at<float>(0, 0) = 0.7f;  // converted already: the source is not asked
  const cv::Mat source = (cv::Mat_<float>(3, 4) << 0.f, 0.5f, -2.f, 1.f,  //
                          std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(), 0.8f, 2.f,
                          3.f, 3.f, 3.f, 3.f);
  int reads = 0;
  image.source.set_reader([&](int row, int col) {
    ++reads;
    return source.at<float>(row, col);
  });

  CHECK(image.at(0, 0) == 0.7f);
  CHECK(image.at(0, 1) == 0.5f);
  CHECK(image.at(0, 1) == 0.5f);
  CHECK(reads == 1);
  // Anything but a positive finite depth is "no measurement".
  CHECK(image.at(0, 2) == 0.f);
  CHECK(image.at(1, 0) == 0.f);
  CHECK(image.at(1, 1) == 0.f);
  CHECK(image.at(1, 2) == 0.8f);
  CHECK(reads == 5);

  SECTION("unconvert: exactly the converted pixels are read again") {
    image.source.unconvert(image.depth);
    CHECK(image.depth.at<float>(0, 0) == 0.7f);
    for (const auto& [row, col] : {std::pair{0, 1}, {0, 2}, {1, 0}, {1, 1}, {1, 2}})
      CHECK(std::isnan(image.depth.at<float>(row, col)));  // kNotConverted
    CHECK(image.at(0, 1) == 0.5f);
    CHECK(reads == 6);
  }
  SECTION("without a reader, pixels not converted read as no measurement and stay unconverted") {
    image.source.drop_reader();
    CHECK(image.at(2, 3) == 0.f);
    CHECK(std::isnan(image.depth.at<float>(2, 3)));
    CHECK(image.at(0, 1) == 0.5f);
  }
}

TEST_CASE("depth image: a source that reads many pixels at once reads ahead what the last frame read") {
  const Intrinsics k{500.0, 500.0, 2.0, 1.5, 4, 3};
  DepthImage image{"Camera2", k, Pose(), cv::Mat(3, 4, CV_32FC1, cv::Scalar(DepthImage::kNotConverted))};
  // Points off the pinhole rays: the rays are read ahead with the depths.
  const auto point_of = [](int row, int col) {
    if (row == 2) return Eigen::Vector3f(0.f, 0.f, 0.f);  // no measurement
    return Eigen::Vector3f(0.01f * col, -0.02f * row, 0.5f + 0.1f * col);
  };
  int single_reads = 0, many_reads = 0;
  const auto start_frame = [&] {
    set_counting_point_reader(image, point_of, single_reads, many_reads);
    image.rays.create(image.depth.size(), CV_32FC2);
    image.source.read_ahead(image.depth, image.rays);
  };
  const auto end_frame = [&] { image.source.unconvert(image.depth); };
  const auto check_pixel = [&](int row, int col) {
    const Eigen::Vector3f P = point_of(row, col);
    const float z = image.at(row, col);
    CHECK(z == P.z());
    if (z > 0.f) CHECK((image.point(row, col, z) - P).norm() < 1e-6f);
  };

  start_frame();
  check_pixel(0, 1);
  check_pixel(2, 3);
  CHECK(single_reads == 2);
  CHECK(many_reads == 0);
  end_frame();

  // The next frame reads both ahead at once, and the cues find the same values...
  start_frame();
  CHECK(many_reads == 2);
  check_pixel(0, 1);
  check_pixel(2, 3);
  check_pixel(1, 2);  // ...and a new pixel is read alone
  CHECK(single_reads == 3);
  // read_soon reads the pixels not converted yet, at once.
  image.read_soon({cv::Point(0, 0), cv::Point(2, 1), cv::Point(0, 0)});  // (x, y): (1, 2) is converted
  CHECK(many_reads == 4);
  check_pixel(0, 0);
  CHECK(single_reads == 3);
  end_frame();

  SECTION("a pixel a frame did not read is not read ahead in the next") {
    start_frame();  // reads ahead (0, 1), (2, 3), (1, 2), (0, 0): once, though asked for twice
    CHECK(many_reads == 8);
    check_pixel(1, 2);
    end_frame();
    start_frame();
    CHECK(many_reads == 9);
    CHECK(image.depth.at<float>(1, 2) < 0.f);  // read ahead: not converted until read
    CHECK(std::isnan(image.depth.at<float>(0, 1)));
    check_pixel(0, 1);
    CHECK(single_reads == 4);
  }
  SECTION("without its reader, a pixel read ahead and not read is no measurement") {
    start_frame();
    image.source.drop_reader();
    CHECK(image.at(0, 1) == 0.f);
  }
  SECTION("an image of another size drops what falls outside it") {
    image.depth = cv::Mat(2, 2, CV_32FC1, cv::Scalar(DepthImage::kNotConverted));
    start_frame();  // (2, 3) and (1, 2) are outside; (0, 1) and (0, 0) inside
    CHECK(many_reads == 4 + 2);
    check_pixel(0, 1);
    check_pixel(0, 0);
    CHECK(single_reads == 3);
  }
}

TEST_CASE("depth image: several threads read one image converted on read, each pixel once from its source") {
  const Intrinsics k{500.0, 500.0, 32.0, 24.0, 64, 48};
  DepthImage image{"Camera2", k, Pose(), cv::Mat(48, 64, CV_32FC1, cv::Scalar(DepthImage::kNotConverted))};
  const auto point_of = [](int row, int col) {
    if ((row + col) % 7 == 0) return Eigen::Vector3f(0.f, 0.f, 0.f);  // no measurement
    return Eigen::Vector3f(0.001f * col, -0.002f * row, 0.5f + 0.01f * col + 0.001f * row);
  };
  std::atomic<int> single_reads{0}, many_reads{0};
  const auto start_frame = [&] {
    set_counting_point_reader(image, point_of, single_reads, many_reads);
    image.rays.create(image.depth.size(), CV_32FC2);
    image.source.read_ahead(image.depth, image.rays);
  };
  // Each thread reads every other pixel of the lower half, then all of it, in its own
  // order, and gathers read_soon on its first rows: the threads meet on most pixels.
  const auto read_concurrently = [&] {
    std::atomic<int> wrong{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
      threads.emplace_back([&, t] {
        std::vector<cv::Point> soon;
        for (int col = 0; col < 64; ++col) soon.emplace_back(col, t);
        image.read_soon(soon);
        for (int pass = 0; pass < 2; ++pass)
          for (int i = 0; i < 48 * 64; i += pass == 0 ? 2 : 1) {
            const int j = t % 2 == 0 ? i : 48 * 64 - 1 - i;
            const int row = j / 64, col = j % 64;
            if (pass == 0 && row < 24) continue;
            const Eigen::Vector3f P = point_of(row, col);
            const float z = image.at(row, col);
            if (z != P.z() || (z > 0.f && (image.point(row, col, z) - P).norm() > 1e-6f)) ++wrong;
          }
      });
    for (std::thread& thread : threads) thread.join();
    return wrong.load();
  };

  start_frame();
  CHECK(read_concurrently() == 0);
  CHECK(single_reads + many_reads == 48 * 64);  // no pixel asked of the source twice
  image.source.unconvert(image.depth);

  // The next frame reads every pixel ahead; the threads race to take them.
  start_frame();
  CHECK(many_reads == 2 * 48 * 64 - single_reads);
  const int single_before = single_reads;
  CHECK(read_concurrently() == 0);
  CHECK(single_reads == single_before);
  image.source.unconvert(image.depth);
  for (int row = 0; row < 48; ++row)
    for (int col = 0; col < 64; ++col) CHECK(std::isnan(image.depth.at<float>(row, col)));
}

TEST_CASE("tracker: depth converted on read tracks exactly as the dense image, reading few pixels") {
  Fixture& f = Fixture::instance();
  test::SceneRenderer scene(f.mesh, f.color_k, f.depth_k, f.depth_T_color);
  const Frame dense = scene.render(f.truth);
  Frame lazy = dense;
  const cv::Mat measured = dense.depths[0].depth;
  lazy.depths[0].depth = cv::Mat(measured.size(), CV_32FC1, cv::Scalar(DepthImage::kNotConverted));
  int reads = 0;
  lazy.depths[0].source.set_reader([&](int row, int col) {
    ++reads;
    return measured.at<float>(row, col);
  });

  const Pose from_dense = check_convergence(dense);
  const Pose from_lazy = check_convergence(lazy);
  CHECK((from_dense.matrix() - from_lazy.matrix()).norm() == 0.0);
  // Each pixel is read once, and the cues read a small part of the image.
  const cv::Mat& after = lazy.depths[0].depth;
  CHECK(reads == cv::countNonZero(after == after));  // kNotConverted is NaN
  INFO(reads << " of " << measured.total() << " pixels read");
  CHECK(reads < static_cast<int>(measured.total()) / 20);
}

namespace {

/// models/two_region tracked with one region modality per colour region (and `modalities`'
/// other cues), coarse models, with a renderer of its scenes in the fixture's cameras.
struct TwoRegionTracker {
  Mesh object = load_mesh(ICGP_MODELS_DIR "/two_region/object.obj");
  std::unique_ptr<Tracker> tracker;
  Body* body;
  test::SceneRenderer scene;
  explicit TwoRegionTracker(const std::vector<std::string>& modalities)
      : scene(object, Fixture::instance().color_k, Fixture::instance().depth_k, Fixture::instance().depth_T_color) {
    TrackerConfig config;
    config.modalities = modalities;
    config.region_model = config.depth_model = coarse_model_params();
    config.regions = {ICGP_MODELS_DIR "/two_region/region_body.obj", ICGP_MODELS_DIR "/two_region/region_lid.obj"};
    config.cache_dir = (std::filesystem::temp_directory_path() / "icgp-test-multi-region-cache").string();
    tracker = build_tracker(config, object, "two_region");
    body = &tracker->body("two_region");
  }
};

/// The body within `max_mm` and `max_deg` of the fixture's truth, and tracked.
void check_at_truth(const Body& body, const BodyResult& result, double max_mm, double max_deg) {
  const Pose& truth = Fixture::instance().truth;
  const double t_mm = 1e3 * (body.reference_T_body.translation() - truth.translation()).norm();
  const double r_deg = rotation_angle_between(body.reference_T_body.rotation(), truth.rotation()) * 180 / M_PI;
  INFO("error " << t_mm << " mm, " << r_deg << " deg, quality " << result.quality);
  CHECK(t_mm < max_mm);
  CHECK(r_deg < max_deg);
  CHECK(result.tracked);
}

}  // namespace

TEST_CASE("build_tracker: one region modality per region of a multi-region object") {
  TwoRegionTracker two_region({cue::kRegion, cue::kDepth});
  Tracker* tracker = two_region.tracker.get();
  Body& body = *two_region.body;
  Fixture& f = Fixture::instance();
  const Frame frame = two_region.scene.render(f.truth, "two_region");
  body.reference_T_body = f.truth;
  tracker->start(frame);
  body.reference_T_body = perturbed(f.truth, 3.0, 3.0);
  std::vector<BodyResult> results;
  for (int i = 0; i < 3; ++i) results = tracker->track(frame);
  REQUIRE(results[0].modalities.size() == 3);  // region_body, region_lid, depth
  check_at_truth(body, results[0], 1.0, 0.5);
}

TEST_CASE("multi-region: a region out of view at the start abstains, then learns its colours when it comes into view") {
  TwoRegionTracker two_region({cue::kRegion});
  Tracker* tracker = two_region.tracker.get();
  Body& body = *two_region.body;
  Fixture& f = Fixture::instance();
  test::SceneRenderer& scene = two_region.scene;

  // Seen from the front, 16 cm down: the lid (y 0.015 .. 0.04 m) lies below the image's
  // last row (y/z > 0.37), the body's top half is in view.
  const Pose low(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.16, 0.45));
  const Frame low_frame = scene.render(low, "two_region");
  body.reference_T_body = low;
  REQUIRE_NOTHROW(tracker->start(low_frame));
  std::vector<BodyResult> results = tracker->track(low_frame);
  REQUIRE(results[0].modalities.size() == 2);  // region_body, region_lid
  CHECK_FALSE(results[0].modalities[0].abstained);
  CHECK(results[0].modalities[1].abstained);

  // In view, the lid learns its colours on the first frame and measures from the next.
  const Frame frame = scene.render(f.truth, "two_region");
  body.reference_T_body = f.truth;
  results = tracker->track(frame);
  CHECK(results[0].modalities[1].abstained);
  body.reference_T_body = perturbed(f.truth, 3.0, 3.0);
  for (int i = 0; i < 3; ++i) results = tracker->track(frame);
  CHECK_FALSE(results[0].modalities[1].abstained);
  CHECK(results[0].modalities[1].score > 0.5);
  check_at_truth(body, results[0], 1.0, 0.5);
}

namespace {

/// Region + depth with the defaults, started at the truth of `frame`.
struct FusedTracker {
  Tracker tracker;
  Body* body;
  explicit FusedTracker(const Frame& frame) {
    Fixture& f = Fixture::instance();
    body = &tracker.add_body({"box", f.mesh, f.truth});
    tracker.add_modality(std::make_unique<RegionModality>(*body, f.region_model, RegionParams{}));
    tracker.add_modality(std::make_unique<DepthModality>(*body, f.depth_model, DepthParams{}));
    tracker.start(frame);
  }
  double t_mm() const { return 1e3 * (body->reference_T_body.translation() - Fixture::instance().truth.translation()).norm(); }
  double r_deg() const {
    return rotation_angle_between(body->reference_T_body.rotation(), Fixture::instance().truth.rotation()) * 180 / M_PI;
  }
};

}  // namespace

TEST_CASE("tracker: without depth measurements the depth cue abstains and region keeps the pose") {
  Fixture& f = Fixture::instance();
  test::SceneRenderer scene(f.mesh, f.color_k, f.depth_k, f.depth_T_color);
  Frame frame = scene.render(f.truth);
  FusedTracker fused(frame);
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), 0.f, -1.f, std::numeric_limits<float>::infinity()}) {
    INFO("depth " << bad);
    frame.depths[0].depth.setTo(bad);
    fused.body->reference_T_body = perturbed(f.truth, 2.0, 1.0);
    std::vector<BodyResult> results;
    for (int i = 0; i < 3; ++i) results = fused.tracker.track(frame);
    INFO("error " << fused.t_mm() << " mm, " << fused.r_deg() << " deg, quality " << results[0].quality);
    CHECK(results[0].modalities[1].abstained);  // says the depth had nothing to measure
    CHECK_FALSE(results[0].modalities[0].abstained);
    CHECK(results[0].tracked);  // the region cue alone vouches for the pose
    CHECK(fused.t_mm() < 3.0);
    CHECK(fused.r_deg() < 1.0);
  }
}

TEST_CASE("region modality: colours registered a few pixels off the depth still agree with the fused pose") {
  // An RGB-D sensor's colour and depth cameras, each calibrated apart, put the same edge a
  // few pixels apart; the depth cue holds the fused pose, so the colours' contour lies that
  // far from the projected one. The region cue must not call such a pose wrong, nor take
  // colours far off the pose for agreement.
  Fixture& f = Fixture::instance();
  test::SceneRenderer scene(f.mesh, f.color_k, f.depth_k, f.depth_T_color);
  const Frame frame = scene.render(f.truth);
  const auto shifted = [&](const Frame& source, double du, double dv) {
    Frame moved = source;
    const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, du, 0, 1, dv);
    cv::warpAffine(source.colors[0].image, moved.colors[0].image, shift, source.colors[0].image.size(),
                   cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    return moved;
  };
  const auto region_score = [&](const Frame& seen) {
    FusedTracker fused(frame);
    std::vector<BodyResult> results;
    for (int i = 0; i < 3; ++i) results = fused.tracker.track(seen);
    INFO("fused pose " << fused.t_mm() << " mm from the truth, region " << results[0].modalities[0].score
                       << ", depth " << results[0].modalities[1].score);
    CHECK(fused.t_mm() < 3.0);  // the depth held the pose
    return results[0].modalities[0].score;
  };
  const double registered = region_score(frame);
  const double off = region_score(shifted(frame, 3.0, -2.0));
  INFO("region score registered " << registered << ", 3 px right and 2 px up " << off);
  CHECK(registered > 0.8);
  // Above what the detector accepts (0.6); at 0.47 before the score allowed for a shift,
  // under the tracker's lost threshold (0.5).
  CHECK(off > 0.65);
  const double far_off = region_score(shifted(frame, 12.0, -8.0));
  INFO("12 px right and 8 px up " << far_off);
  CHECK(far_off < 0.5);  // lost
}

TEST_CASE("tracker: an object that left the image is reported lost, not tracked into the background") {
  Fixture& f = Fixture::instance();
  test::SceneRenderer scene(f.mesh, f.color_k, f.depth_k, f.depth_T_color);
  FusedTracker fused(scene.render(f.truth));
  const Pose away(f.truth.rotation(), f.truth.translation() + Eigen::Vector3d(0.6, 0.0, 0.0));
  const auto results = fused.tracker.track(scene.render(away));
  INFO("quality " << results[0].quality);
  CHECK_FALSE(results[0].tracked);
}

TEST_CASE("tracker: a glint in the depth on a quarter of the object leaves the pose to the good data") {
  Fixture& f = Fixture::instance();
  test::SceneRenderer scene(f.mesh, f.color_k, f.depth_k, f.depth_T_color);
  Frame frame = scene.render(f.truth);
  // A patch of the object's depth reads 1.5 cm too close: less than the occlusion threshold,
  // so only the robust weights can tell it from the object.
  cv::Mat& depth = frame.depths[0].depth;
  const double background = f.truth.translation().z() + 0.2;
  std::vector<cv::Point> object;
  for (int row = 0; row < depth.rows; ++row)
    for (int col = 0; col < depth.cols; ++col)
      if (depth.at<float>(row, col) > 0.f && depth.at<float>(row, col) < background) object.emplace_back(col, row);
  REQUIRE(object.size() > 1000);
  const cv::Rect box = cv::boundingRect(object);
  const cv::Rect glint(box.x, box.y, box.width / 2, box.height / 2);
  int n_glint = 0;
  for (int row = glint.y; row < glint.y + glint.height; ++row)
    for (int col = glint.x; col < glint.x + glint.width; ++col) {
      float& z = depth.at<float>(row, col);
      if (z > 0.f && z < background) {
        z -= 0.015f;
        ++n_glint;
      }
    }
  INFO("glint on " << n_glint << " of " << object.size() << " object pixels");
  REQUIRE(n_glint > static_cast<int>(object.size() / 8));
  FusedTracker fused(frame);
  fused.body->reference_T_body = perturbed(f.truth, 3.0, 2.0);
  std::vector<BodyResult> results;
  for (int i = 0; i < 3; ++i) results = fused.tracker.track(frame);
  INFO("error " << fused.t_mm() << " mm, " << fused.r_deg() << " deg");
  CHECK(fused.t_mm() < 1.0);
  CHECK(fused.r_deg() < 0.5);
  CHECK(results[0].tracked);
}

TEST_CASE("region modality: clutter of the object's colours beside part of its contour leaves the pose to the rest") {
  Fixture& f = Fixture::instance();
  test::SceneRenderer scene(f.mesh, f.color_k, f.depth_k, f.depth_T_color);
  const Frame clean = scene.render(f.truth);
  // The object's silhouette in the colour camera (the clutter plane is 0.3 m behind it).
  const cv::Mat depth = scene.renderer().render(f.color_k, Pose(), kRenderDepth).depth;
  const cv::Mat object = (depth > 0.f) & (depth < f.truth.translation().z() + 0.2);
  // Beside a stretch of the silhouette's left side, 6 px of background take the object's
  // colours, mirrored across its edge: there the contour seems 6 px further out.
  const cv::Rect box = cv::boundingRect(object);
  Frame cluttered = clean;
  cluttered.colors[0].image = clean.colors[0].image.clone();
  cv::Mat& image = cluttered.colors[0].image;
  int n_clutter = 0;
  for (int row = box.y + box.height / 4; row < box.y + box.height / 2; ++row)
    for (int col = std::max(0, box.x - 6); col < box.x + box.width / 2; ++col) {
      if (object.at<std::uint8_t>(row, col)) break;  // the edge: only the 6 px before it
      const int edge = col + 6 < image.cols && object.at<std::uint8_t>(row, col + 6) ? col + 6 : -1;
      for (int e = col + 1; e <= col + 6 && edge < 0 && e < image.cols; ++e)
        if (object.at<std::uint8_t>(row, e)) {
          image.at<cv::Vec3b>(row, col) = image.at<cv::Vec3b>(row, std::min(image.cols - 1, 2 * e - col));
          ++n_clutter;
          break;
        }
      if (edge >= 0) {
        image.at<cv::Vec3b>(row, col) = image.at<cv::Vec3b>(row, std::min(image.cols - 1, 2 * edge - col));
        ++n_clutter;
      }
    }
  REQUIRE(n_clutter > 100);

  // At the true pose, in the last (one-pixel) correspondence pass: the lines that see the
  // contour beside the clutter are far beyond the others' scatter, and get no weight.
  auto lines_at_truth = [&](bool robust, std::vector<double>& residuals, std::vector<double>& weights) {
    Body body{"box", f.mesh, f.truth};
    RegionParams params;
    params.noise.robust = robust;
    RegionModality region(body, f.region_model, params);
    region.start(clean, {});
    region.correspondences(cluttered, {}, 3);
    region.append_residuals(residuals, weights);
  };
  std::vector<double> residuals, weights, plain_residuals, plain_weights;
  lines_at_truth(true, residuals, weights);
  lines_at_truth(false, plain_residuals, plain_weights);
  REQUIRE(residuals == plain_residuals);
  int n_far = 0, n_near = 0;
  double far_weight = 0.0, plain_far_weight = 0.0, near_weight = 0.0, plain_near_weight = 0.0;
  for (std::size_t i = 0; i < residuals.size(); ++i) {
    if (std::abs(residuals[i]) > 4.0) {
      ++n_far;
      far_weight += weights[i];
      plain_far_weight += plain_weights[i];
    } else if (std::abs(residuals[i]) < 1.0) {
      ++n_near;
      near_weight += weights[i];
      plain_near_weight += plain_weights[i];
    }
  }
  INFO(n_far << " lines beyond 4 px: weight " << far_weight << " (without robust weights " << plain_far_weight << "); "
             << n_near << " within 1 px: " << near_weight << " (" << plain_near_weight << ")");
  CHECK(n_far >= 5);
  CHECK(n_near > 5 * n_far);
  CHECK(far_weight < 0.02 * plain_far_weight);
  CHECK(near_weight > 0.5 * plain_near_weight);
}

TEST_CASE("tracker: started beside the object, ICG+ reports lost from the first frame") {
  Fixture& f = Fixture::instance();
  test::SceneRenderer scene(f.mesh, f.color_k, f.depth_k, f.depth_T_color);
  const Frame frame = scene.render(f.truth);
  // 5 cm to the side: the texture cue's first keyframe is lifted at this wrong pose, so it
  // would match itself perfectly on the first frame; it must not vouch for the pose.
  const Pose beside(f.truth.rotation(), f.truth.translation() + Eigen::Vector3d(0.05, 0.0, 0.0));
  Tracker tracker;
  Body& body = tracker.add_body({"box", f.mesh, beside});
  tracker.add_modality(std::make_unique<RegionModality>(body, f.region_model, RegionParams{}));
  tracker.add_modality(std::make_unique<DepthModality>(body, f.depth_model, DepthParams{}));
  tracker.add_modality(std::make_unique<TextureModality>(body, TextureParams{}));
  tracker.start(frame);
  for (int i = 0; i < 3; ++i) {
    const std::vector<BodyResult> results = tracker.track(frame);
    const double t_mm = 1e3 * (body.reference_T_body.translation() - f.truth.translation()).norm();
    INFO("frame " << i << ": " << t_mm << " mm from the truth, quality " << results[0].quality << " (texture "
                  << results[0].modalities[2].score << (results[0].modalities[2].abstained ? ", abstained" : "")
                  << ")");
    CHECK(results[0].modalities[2].abstained == (i == 0));
    if (t_mm > 10.0) CHECK_FALSE(results[0].tracked);
  }
}

TEST_CASE("tracker: a texture keyframe lifted at a guessed pose does not hold ICG+'s rotation there") {
  // A restart at a guessed pose (in the servo loop, the last trusted one) lifts the texture
  // cue's keyframe there. The next frames match that keyframe almost exactly, so the scatter
  // of its residuals is tiny however wrong the guess: estimated about the fused pose, its σ
  // fell to the floor and held the pose at the guess (1.16 mm, 0.50° after 10 frames here).
  // Measured at the pose region and depth give, the residuals show the keyframe's error.
  Fixture& f = Fixture::instance();
  test::SceneRenderer scene(f.mesh, f.color_k, f.depth_k, f.depth_T_color);
  const Frame frame = scene.render(f.truth);
  Tracker tracker;
  Body& body = tracker.add_body({"box", f.mesh, f.truth});
  tracker.add_modality(std::make_unique<RegionModality>(body, f.region_model, RegionParams{}));
  tracker.add_modality(std::make_unique<DepthModality>(body, f.depth_model, DepthParams{}));
  auto texture_cue = std::make_unique<TextureModality>(body, TextureParams{});
  TextureModality& texture = *texture_cue;
  tracker.add_modality(std::move(texture_cue));
  tracker.start(frame);  // region's colours at the true pose
  // The texture cue alone restarted 2 mm and 0.5° off, turned about the box's centre.
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.8, 0.5).normalized();
  const Eigen::Vector3d direction = Eigen::Vector3d(-0.6, 0.2, 0.77).normalized();
  body.reference_T_body =
      Pose(f.truth.rotation() * exp_so3<double>(axis * 0.5 * M_PI / 180.0), f.truth.translation() + direction * 2e-3);
  icgp::SceneRenderer renderer;
  Renders renders;
  renderer.render({&body}, texture.render_requests(frame, {Stage::kStart}), renders);
  texture.start(frame, renders);
  std::vector<BodyResult> results;
  for (int i = 0; i < 10; ++i) results = tracker.track(frame);
  const double t_mm = 1e3 * (body.reference_T_body.translation() - f.truth.translation()).norm();
  const double r_deg = rotation_angle_between(body.reference_T_body.rotation(), f.truth.rotation()) * 180 / M_PI;
  INFO("after 10 frames: " << t_mm << " mm, " << r_deg << " deg from the truth; " << texture.matches().size()
                           << " texture matches");
  REQUIRE(texture.matches().size() > 20);  // the keyframe is in use
  CHECK(r_deg < 0.05);  // 0.004° measured
  // Translation is only partly recovered (0.93 mm measured): at σ ≈ 3 px, its distance from
  // the other cues' pose, the keyframe still outweighs the region cue across the image.
  // With the papers' fixed σ (5 px) it would end 0.003 mm off; docs/accuracy.md.
  CHECK(t_mm < 1.1);
  CHECK(results[0].tracked);
}
