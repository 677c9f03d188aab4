// SPDX-License-Identifier: GPL-2.0-or-later
// The Cycles backend against the OpenGL renderer's exact geometry: the same camera model
// (off-centre principal point, non-square pixels), depth, normals and silhouettes; colour
// that is the lit object where the geometry is, reproducible by seed; motion blur along the
// camera's path, as the OpenGL backend blurs it. Needs Blender: without it every Cycles test
// exits with CTest's skip code.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "icgp/servo/blender_process.h"
#include "icgp/servo/scene_backend.h"
#include "icgp/visp/conversions.h"

using namespace icgp;
using namespace icgp::servo;

namespace {

/// CTest's code for a skipped test (SKIP_RETURN_CODE in tests/CMakeLists.txt).
constexpr int kSkipped = 77;

void skip_without_blender() {
  try {
    blender_executable();
  } catch (const std::exception& e) {
    std::printf("skipped: %s\n", e.what());
    std::exit(kSkipped);
  }
}

/// A small camera whose principal point is off centre and whose pixels are not square, so
/// that a wrong shift or aspect in Blender's camera moves or stretches the silhouette.
const Intrinsics kCamera{230.0, 210.0, 71.3, 50.6, 160, 120};

/// A flat red box tilted on all three axes, 0.4 m in front of the camera at the world origin.
Mesh red_box() { return box_mesh(Eigen::Vector3d(0.10, 0.08, 0.06), Eigen::Vector3f(0.8f, 0.15f, 0.1f)); }
const Pose kWorldTBox = Pose::from_rotation_vector(Eigen::Vector3d(0.35, 0.5, 0.2), Eigen::Vector3d(0.012, -0.008, 0.4));

std::unique_ptr<SceneBackend> backend(RendererKind kind, std::uint64_t seed = 1) {
  Scenario s;
  s.camera.renderer = kind;
  s.camera.cycles.samples = 4;
  std::unique_ptr<SceneBackend> scene = make_scene_backend(s, seed);
  LightState light;
  light.lamps.front().direction = Eigen::Vector3d(0.3, 0.4, 1.0).normalized();
  scene->set_light(light);
  const SceneBackend::BodyHandle box = scene->add_body(red_box(), 1);
  scene->set_body_pose(box, kWorldTBox);
  return scene;
}

/// Centre of the pixels the object covers in a colour image (its background is black).
cv::Point2d object_centroid(const cv::Mat& color) {
  cv::Mat grey, mask;
  cv::cvtColor(color, grey, cv::COLOR_BGR2GRAY);
  mask = grey > 8;
  const cv::Moments m = cv::moments(mask, true);
  REQUIRE(m.m00 > 100);
  return {m.m10 / m.m00, m.m01 / m.m00};
}

}  // namespace

TEST_CASE("cycles backend: depth, normals and silhouette are the OpenGL renderer's, to the pixel") {
  skip_without_blender();
  const RenderOutput gl = backend(RendererKind::kOpenGl)->render_geometry(kCamera, Pose(), true);
  const RenderOutput cy = backend(RendererKind::kCycles)->render_geometry(kCamera, Pose(), true);
  REQUIRE(cy.depth.size() == gl.depth.size());
  const cv::Mat in_gl = gl.depth > 0, in_cy = cy.depth > 0;
  const int both = cv::countNonZero(in_gl & in_cy), either = cv::countNonZero(in_gl | in_cy);
  INFO("object pixels: OpenGL " << cv::countNonZero(in_gl) << ", Cycles " << cv::countNonZero(in_cy) << ", both " << both);
  // Only pixels whose centre is within a hair of the outline may differ: the outline is
  // some 150 pixels long, the silhouette some 2500 pixels.
  CHECK(cv::countNonZero(in_gl) > 1500);
  CHECK(either - both < 40);
  int close_depth = 0, close_normal = 0;
  for (int row = 0; row < kCamera.height; ++row)
    for (int col = 0; col < kCamera.width; ++col) {
      if (!in_gl.at<uchar>(row, col) || !in_cy.at<uchar>(row, col)) continue;
      close_depth += std::abs(gl.depth.at<float>(row, col) - cy.depth.at<float>(row, col)) < 1e-4f;
      close_normal += gl.normals.at<cv::Vec3f>(row, col).dot(cy.normals.at<cv::Vec3f>(row, col)) > 0.999f;
    }
  CHECK(close_depth > 0.98 * both);
  CHECK(close_normal > 0.98 * both);
}

TEST_CASE("cycles backend: colour is the lit object where the geometry is, the same for the same seed") {
  skip_without_blender();
  const cv::Mat depth = backend(RendererKind::kOpenGl)->render_geometry(kCamera, Pose(), false).depth;
  const vpHomogeneousMatrix wMc;
  const cv::Mat first = backend(RendererKind::kCycles, 7)->render_color(kCamera, wMc, wMc, 0.0);
  const cv::Mat again = backend(RendererKind::kCycles, 7)->render_color(kCamera, wMc, wMc, 0.0);
  const cv::Mat other = backend(RendererKind::kCycles, 8)->render_color(kCamera, wMc, wMc, 0.0);
  REQUIRE(first.type() == CV_8UC3);
  CHECK(cv::norm(first, again, cv::NORM_INF) == 0.0);
  CHECK(cv::norm(first, other, cv::NORM_L1) > 0.0);  // another seed, other sampling noise
  // Away from the outline the object is red (BGR order), the background black.
  cv::Mat inside, outside;
  cv::erode(depth > 0, inside, cv::Mat(), cv::Point(-1, -1), 2);
  cv::dilate(depth > 0, outside, cv::Mat(), cv::Point(-1, -1), 2);
  const cv::Scalar object = cv::mean(first, inside);
  INFO("object BGR " << object);
  CHECK(object[2] > 60.0);
  CHECK(object[2] > 2.0 * object[1]);
  CHECK(object[2] > 2.0 * object[0]);
  CHECK(cv::norm(cv::mean(first, ~outside)) < 1.0);
}

/// Both backends blur a frame over the exposure's part of the camera's path, centred on its
/// middle; OpenGL by a few renders along it (one per pixel of motion).
void check_motion_blur(RendererKind kind) {
  std::unique_ptr<SceneBackend> scene = backend(kind);
  const vpHomogeneousMatrix end(0.0, 0.0, 0.0, 0, 0, 0), start(-0.03, 0.0, 0.0, 0, 0, 0);
  const cv::Point2d sharp_end = object_centroid(scene->render_color(kCamera, end, end, 0.0));
  const cv::Point2d sharp_start = object_centroid(scene->render_color(kCamera, start, start, 0.0));
  // The camera moved 3 cm to the right over the frame: the object 17 px to the left.
  CHECK(sharp_start.x - sharp_end.x == Approx(230.0 * 0.03 / 0.4).margin(1.5));
  const cv::Point2d blurred = object_centroid(scene->render_color(kCamera, end, start, 1.0));
  const cv::Point2d half = object_centroid(scene->render_color(kCamera, end, start, 0.5));
  CHECK(blurred.x == Approx((sharp_start.x + sharp_end.x) / 2).margin(1.5));
  CHECK(half.x == Approx((3 * sharp_end.x + sharp_start.x) / 4).margin(1.5));
  CHECK(blurred.y == Approx(sharp_end.y).margin(1.0));
}

TEST_CASE("opengl backend: motion blur spreads the object along the camera's path") {
  check_motion_blur(RendererKind::kOpenGl);
}

TEST_CASE("cycles backend: motion blur spreads the object along the camera's path") {
  skip_without_blender();
  check_motion_blur(RendererKind::kCycles);
}

TEST_CASE("cycles backend: each colour render takes the light last set") {
  skip_without_blender();
  std::unique_ptr<SceneBackend> scene = backend(RendererKind::kCycles);
  const cv::Mat depth = backend(RendererKind::kOpenGl)->render_geometry(kCamera, Pose(), false).depth;
  cv::Mat inside;
  cv::erode(depth > 0, inside, cv::Mat(), cv::Point(-1, -1), 2);
  const vpHomogeneousMatrix wMc;
  LightState off;
  off.ambient = off.lamps.front().strength = 0.0;
  scene->set_light(off);
  CHECK(cv::norm(cv::mean(scene->render_color(kCamera, wMc, wMc, 0.0), inside)) < 1.0);
  LightState on;
  on.lamps.front().direction = Eigen::Vector3d(0.3, 0.4, 1.0).normalized();
  scene->set_light(on);
  const double lit = cv::mean(scene->render_color(kCamera, wMc, wMc, 0.0), inside)[2];
  on.lamps.front().strength = 0.2;
  scene->set_light(on);
  const double dimmer = cv::mean(scene->render_color(kCamera, wMc, wMc, 0.0), inside)[2];
  INFO("red channel: lit " << lit << ", dimmer " << dimmer);
  CHECK(lit > 60.0);
  CHECK(dimmer < 0.9 * lit);
}
