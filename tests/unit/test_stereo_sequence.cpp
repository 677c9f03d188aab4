// SPDX-License-Identifier: GPL-2.0-or-later
// Rendered sequences with a second colour camera (SequenceWriterOptions::stereo): written,
// read back as "Camera3", checked against an independent render and against the geometry.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "icgp/eval/sequence.h"
#include "icgp/eval/sequence_writer.h"
#include "icgp/io/mesh_loader.h"
#include "icgp/render/renderer.h"
#include "test_temp_dir.h"

using namespace icgp;
using Catch::Matchers::Contains;
using icgp::test::files_under;
using icgp::test::read_bytes;
using icgp::test::TempDir;
namespace fs = std::filesystem;

namespace {

const std::string kBoxModel = std::string(ICGP_MODELS_DIR) + "/textured_box/textured_box.obj";

Pose box_world_pose() {
  return Pose::from_rotation_vector(Eigen::Vector3d(0.2, -0.3, 0.1), Eigen::Vector3d(0.005, -0.01, 0.0));
}

/// 3 frames of the textured box at 160 x 120 with a second colour camera.
SequenceWriterOptions stereo_options(const Pose& stereo_T_color, const Intrinsics& stereo_intrinsics) {
  SequenceWriterOptions o;
  o.frame_count = 3;
  o.seed = 11;
  o.color_intrinsics = o.depth_intrinsics = Intrinsics::centred(160, 120, 200.0);
  o.depth_T_color = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.025, 0.0, 0.0));
  o.stereo = true;
  o.stereo_intrinsics = stereo_intrinsics;
  o.stereo_T_color = stereo_T_color;
  o.motion.speed = 3.0;
  o.progress = false;
  return o;
}

SequenceWriter box_writer(const SequenceWriterOptions& options) {
  SequenceWriter writer(options);
  writer.add_object("textured_box", load_mesh(kBoxModel), box_world_pose());
  return writer;
}

/// A rectified pair: the stereo camera is the colour camera moved `baseline` metres along
/// its x axis (what `icgp make-sequence --stereo-baseline` writes).
Pose rectified(double baseline) { return Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-baseline, 0.0, 0.0)); }

/// Sum of squared grey differences of the (2r+1)^2 patches centred on (u1, v) of `a` and
/// (u2, v) of `b`.
double patch_ssd(const cv::Mat& a, const cv::Mat& b, int u1, int u2, int v, int r) {
  double ssd = 0.0;
  for (int dv = -r; dv <= r; ++dv)
    for (int du = -r; du <= r; ++du) {
      const double d = double(a.at<uchar>(v + dv, u1 + du)) - double(b.at<uchar>(v + dv, u2 + du));
      ssd += d * d;
    }
  return ssd;
}

}  // namespace

TEST_CASE("stereo sequence: Camera3 is an exact render from stereo_T_color * color_T_world") {
  TempDir dir("icgp_test_stereo_exact");
  // Not a rectified pair: other intrinsics, turned and shifted, to see each recorded as given.
  Intrinsics k3 = Intrinsics::centred(150, 110, 185.0);
  k3.pu = 75.2;
  const Pose stereo_T_color = Pose::from_rotation_vector(Eigen::Vector3d(0.01, -0.04, 0.02), Eigen::Vector3d(-0.07, 0.004, 0.002));
  SequenceWriterOptions options = stereo_options(stereo_T_color, k3);
  options.background.enabled = false;  // the scene is the box alone, for the independent render
  const SequenceWriter writer = box_writer(options);
  writer.write(dir.path().string());
  REQUIRE(fs::is_regular_file(dir.path() / "color2" / "000002.png"));

  const Sequence sequence = Sequence::open(dir.path().string());
  REQUIRE(sequence.has_stereo());
  CHECK(sequence.stereo_T_color().matrix() == stereo_T_color.matrix());
  CHECK(sequence.stereo_intrinsics().fu == 185.0);
  CHECK(sequence.stereo_intrinsics().pu == 75.2);
  CHECK(sequence.stereo_intrinsics().width == 150);

  Renderer renderer;
  const Renderer::BodyHandle box = renderer.add_body(load_mesh(kBoxModel), 1);
  renderer.set_body_pose(box, box_world_pose());
  for (int i = 0; i < sequence.size(); ++i) {
    INFO("frame " << i);
    const Frame frame = sequence.load(i);
    REQUIRE(frame.colors.size() == 2);
    CHECK(frame.colors[0].camera == "Camera1");
    CHECK(frame.colors[0].camera_T_reference.matrix() == Pose().matrix());
    REQUIRE(frame.depths.size() == 1);
    CHECK(frame.depths[0].camera == "Camera2");
    const ColorImage* stereo = frame.find_color("Camera3");
    REQUIRE(stereo == &frame.colors[1]);
    CHECK(stereo->camera_T_reference.matrix() == stereo_T_color.matrix());
    CHECK(stereo->intrinsics.fu == k3.fu);
    REQUIRE(stereo->image.type() == CV_8UC3);
    REQUIRE(stereo->image.size() == cv::Size(150, 110));

    const cv::Mat expected =
        renderer.render(k3, stereo_T_color * writer.color_T_world(i), kRenderColor).color;
    CHECK(cv::norm(stereo->image, expected, cv::NORM_INF) == 0.0);
    // The object is in view (the comparison is not of two empty images).
    cv::Mat grey;
    cv::cvtColor(expected, grey, cv::COLOR_BGR2GRAY);
    CHECK(cv::countNonZero(grey) > 500);
    // And it is not the colour camera's image.
    const cv::Mat color_view = renderer.render(k3, writer.color_T_world(i), kRenderColor).color;
    CHECK(cv::norm(stereo->image, color_view, cv::NORM_INF) > 0.0);
  }

  // A monocular grey load makes the stereo camera grey too.
  SequenceOptions grey;
  grey.grey_without_depth = true;
  const Frame grey_frame = Sequence::open(dir.path().string(), grey).load(0);
  REQUIRE(grey_frame.colors.size() == 2);
  CHECK(grey_frame.colors[1].image.type() == CV_8UC1);
  CHECK(grey_frame.depths.empty());
}

TEST_CASE("stereo sequence: a point of the object projects consistently in both cameras") {
  TempDir dir("icgp_test_stereo_geometry");
  constexpr double kBaseline = 0.06;
  SequenceWriterOptions options = stereo_options(rectified(kBaseline), Intrinsics());
  options.color_intrinsics = options.depth_intrinsics = options.stereo_intrinsics = Intrinsics::centred(320, 240, 400.0);
  options.noise.color_sigma = 2.0;
  options.antialias_samples = 4;
  box_writer(options).write(dir.path().string());

  const Sequence sequence = Sequence::open(dir.path().string());
  REQUIRE(sequence.has_stereo());
  // Face centres of the box (0.08 x 0.16 x 0.06) and their outward normals.
  const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> faces = {
      {{0.04, 0, 0}, {1, 0, 0}},  {{-0.04, 0, 0}, {-1, 0, 0}}, {{0, 0.08, 0}, {0, 1, 0}},
      {{0, -0.08, 0}, {0, -1, 0}}, {{0, 0, 0.03}, {0, 0, 1}},   {{0, 0, -0.03}, {0, 0, -1}}};
  for (int i = 0; i < sequence.size(); ++i) {
    INFO("frame " << i);
    const Frame frame = sequence.load(i);
    const Pose* truth = frame.truth("textured_box");
    REQUIRE(truth != nullptr);
    const ColorImage& c1 = frame.colors[0];
    const ColorImage& c3 = frame.colors[1];

    // The face seen most frontally by both cameras, and its centre in each camera.
    double best = 0.0;
    Eigen::Vector3d X1 = Eigen::Vector3d::Zero();
    for (const auto& [centre, normal] : faces) {
      const Eigen::Vector3d X = *truth * centre;
      const Eigen::Vector3d n = truth->rotation() * normal;
      const Eigen::Vector3d X3 = c3.camera_T_reference * X;
      const double facing = std::min(-n.dot(X.normalized()), -(c3.camera_T_reference.rotation() * n).dot(X3.normalized()));
      if (facing > best) best = facing, X1 = X;
    }
    REQUIRE(best > 0.3);
    const Eigen::Vector3d X3 = c3.camera_T_reference * X1;
    const Eigen::Vector2d p1 = c1.intrinsics.project(X1), p3 = c3.intrinsics.project(X3);
    REQUIRE(c1.intrinsics.contains(p1.x(), p1.y()));
    REQUIRE(c3.intrinsics.contains(p3.x(), p3.y()));
    // Rectified pair: the same row, and the disparity of a camera `baseline` to the right.
    const double disparity = c1.intrinsics.fu * kBaseline / X1.z();
    CHECK(p3.y() == Approx(p1.y()).margin(1e-9));
    CHECK(p1.x() - p3.x() == Approx(disparity).margin(1e-9));

    // The images agree with that geometry: the point's patch in Camera1 is found in Camera3
    // along the row at the predicted disparity (to a pixel), not elsewhere.
    cv::Mat g1, g3;
    cv::cvtColor(c1.image, g1, cv::COLOR_BGR2GRAY);
    cv::cvtColor(c3.image, g3, cv::COLOR_BGR2GRAY);
    constexpr int r = 5, search = 25;
    const int u1 = int(std::lround(p1.x())), v = int(std::lround(p1.y()));
    const double predicted = u1 - disparity;
    REQUIRE(v - r >= 0);
    REQUIRE(v + r < g1.rows);
    cv::Scalar mean, stddev;
    cv::meanStdDev(g1(cv::Rect(u1 - r, v - r, 2 * r + 1, 2 * r + 1)), mean, stddev);
    REQUIRE(stddev[0] > 8.0);  // textured enough for the match to mean something
    int best_u = -1;
    double best_ssd = std::numeric_limits<double>::infinity();
    for (int u = int(predicted) - search; u <= int(predicted) + search; ++u) {
      if (u - r < 0 || u + r >= g3.cols) continue;
      const double ssd = patch_ssd(g1, g3, u1, u, v, r);
      if (ssd < best_ssd) best_ssd = ssd, best_u = u;
    }
    INFO("predicted u " << predicted << ", best match " << best_u << ", disparity " << disparity);
    CHECK(std::abs(best_u - predicted) <= 1.0);
  }
}

TEST_CASE("stereo sequence: the stereo camera changes no other file and is deterministic") {
  SequenceWriterOptions options = stereo_options(rectified(0.08), Intrinsics::centred(160, 120, 200.0));
  options.noise.color_sigma = 3.0;
  options.noise.depth_sigma_at_1m = 0.002;
  options.antialias_samples = 4;
  options.motion_blur.samples = 2;
  SequenceWriterOptions mono = options;
  mono.stereo = false;
  TempDir a("icgp_test_stereo_a"), b("icgp_test_stereo_b"), m("icgp_test_stereo_mono");
  box_writer(options).write(a.path().string());
  box_writer(options).write(b.path().string());
  box_writer(mono).write(m.path().string());

  // The same seed, byte-identical files.
  const std::vector<fs::path> files = files_under(a.path());
  REQUIRE(files == files_under(b.path()));
  CHECK(files.size() == 1 + 3 * 3 + 1);  // sequence.yaml, color, color2, depth, poses
  for (const fs::path& file : files) {
    INFO(file);
    CHECK(read_bytes(a.path() / file) == read_bytes(b.path() / file));
  }
  // Without the stereo camera: the same files but color2/ and the YAML's stereo lines.
  for (const fs::path& file : files_under(m.path())) {
    INFO(file);
    if (file == "sequence.yaml") continue;
    CHECK(read_bytes(a.path() / file) == read_bytes(m.path() / file));
  }
  const std::string yaml = read_bytes(a.path() / "sequence.yaml"), mono_yaml = read_bytes(m.path() / "sequence.yaml");
  CHECK(mono_yaml.find("stereo") == std::string::npos);
  CHECK_THAT(yaml, Contains("stereo_camera: {name: Camera3, width: 160, height: 120"));
  CHECK_THAT(yaml, Contains("stereo_T_color: [1, 0, 0, -0.08, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]"));
  CHECK(!Sequence::open(m.path().string()).has_stereo());
  CHECK(Sequence::open(m.path().string()).load(0).colors.size() == 1);
  // color2/ holds the stereo camera's own images, not copies of the colour camera's.
  CHECK(read_bytes(a.path() / "color2/000000.png") != read_bytes(a.path() / "color/000000.png"));

  // Writing a mono sequence over a stereo one removes color2/.
  box_writer(mono).write(b.path().string());
  CHECK(!fs::exists(b.path() / "color2"));
  CHECK(!Sequence::open(b.path().string()).has_stereo());

  SECTION("errors name the file and what is missing") {
    std::string broken = yaml;
    const std::size_t begin = broken.find("stereo_camera:");
    broken.erase(begin, broken.find('\n', begin) + 1 - begin);
    a.write("sequence.yaml", broken);
    REQUIRE_THROWS_WITH(Sequence::open(a.path().string()), Contains("sequence.yaml") && Contains("stereo_camera"));
    a.write("sequence.yaml", yaml);
    fs::remove(a.path() / "color2/000001.png");
    REQUIRE_THROWS_WITH(Sequence::open(a.path().string()),
                        Contains("000001.png") && Contains("missing stereo colour image"));
  }
}
