// SPDX-License-Identifier: GPL-2.0-or-later
// Rendering realism of the synthetic sequences: multisample antialiasing, motion blur over
// the exposure (with the ground truth at its middle) and depth holes along depth edges.
#include <catch2/catch.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "icgp/eval/sequence.h"
#include "icgp/eval/sequence_writer.h"
#include "icgp/render/renderer.h"
#include "icgp/render/sensor_effects.h"
#include "test_meshes.h"
#include "test_temp_dir.h"

using namespace icgp;

namespace {

/// A white box on black, unshaded, so that a pixel's grey level is the box's coverage.
Mesh white_box() {
  Mesh box = test::make_box(0.1f, 0.1f, 0.1f);
  box.parts[0].material.diffuse_rgb = {1.f, 1.f, 1.f};
  return box;
}

Lighting flat_white_lighting() {
  Lighting lighting;
  lighting.ambient = 1.f;
  lighting.diffuse = 0.f;
  return lighting;
}

/// Half a metre in front of the camera, turned about the optical axis so its edges are
/// oblique to the pixel grid.
Pose oblique_box_pose() { return Pose::from_rotation_vector(Eigen::Vector3d(0.0, 0.0, 0.35), Eigen::Vector3d(0.003, 0.0, 0.5)); }

cv::Mat grey(const cv::Mat& bgr) {
  cv::Mat g;
  cv::cvtColor(bgr, g, cv::COLOR_BGR2GRAY);
  return g;
}

}  // namespace

TEST_CASE("renderer: multisampled colour blends edge pixels, the other targets stay exact") {
  const Intrinsics k = Intrinsics::centred(160, 120, 150.0);
  Renderer renderer;
  renderer.set_lighting(flat_white_lighting());
  renderer.set_body_pose(renderer.add_body(white_box(), 1), oblique_box_pose());

  const RenderOutput sharp = renderer.render(k, Pose(), kRenderColor | kRenderDepth);
  const cv::Mat sharp_grey = grey(sharp.color);
  const cv::Mat sharp_blends = (sharp_grey > 0) & (sharp_grey < 255);
  CHECK(cv::countNonZero(sharp_blends) == 0);  // without antialiasing: box or background

  renderer.set_color_antialiasing(4);
  CHECK(renderer.color_antialiasing() == 4);
  const RenderOutput smooth = renderer.render(k, Pose(), kRenderColor | kRenderDepth);
  const cv::Mat smooth_grey = grey(smooth.color);
  const cv::Mat blends = (smooth_grey > 0) & (smooth_grey < 255);
  // About 30 px sides: most of the ~120 outline pixels are partly covered.
  CHECK(cv::countNonZero(blends) > 60);

  // Blends lie on the outline only: within a pixel of both box and background of the sharp render.
  cv::Mat box_near, background_near;
  const cv::Mat kernel = cv::Mat::ones(3, 3, CV_8UC1);
  cv::dilate(sharp_grey == 255, box_near, kernel);
  cv::dilate(sharp_grey == 0, background_near, kernel);
  CHECK(cv::countNonZero(blends & ~(box_near & background_near)) == 0);
  // Coverage is conserved: the total brightness is the box's area either way.
  CHECK(cv::sum(smooth_grey)[0] == Approx(cv::sum(sharp_grey)[0]).epsilon(0.02));
  // Depth is not blended.
  CHECK(cv::norm(smooth.depth, sharp.depth, cv::NORM_INF) == 0.0);

  CHECK_THROWS_WITH(renderer.set_color_antialiasing(1), Catch::Matchers::Contains("must be 0 (off) or 2.."));
  renderer.set_color_antialiasing(0);
  CHECK(cv::norm(grey(renderer.render(k, Pose(), kRenderColor).color), sharp_grey, cv::NORM_INF) == 0.0);
}

TEST_CASE("sequence writer: a blurred frame is the mean of renders over the exposure, the truth its middle") {
  SequenceWriterOptions o;
  o.frame_count = 2;
  o.seed = 5;
  o.color_intrinsics = o.depth_intrinsics = Intrinsics::centred(160, 120, 150.0);
  o.motion.speed = 5.0;  // fast: the box's edges move several pixels during the exposure
  o.motion.distance = 0.4;
  o.motion.distance_variation = 0.05;
  o.background.enabled = false;
  o.motion_blur = MotionBlur{4, 0.8};
  o.progress = false;
  SequenceWriter writer(o);
  writer.add_object("box", white_box());
  test::TempDir dir("icgp_test_motion_blur");
  writer.write(dir.path().string());

  const double frame_time = 1.0 / o.frame_rate;
  double mean_time = 0.0;
  for (int s = 0; s < 4; ++s) mean_time += writer.exposure_time(frame_time, s) / 4.0;
  CHECK(mean_time == Approx(frame_time).margin(1e-12));
  CHECK(writer.exposure_time(frame_time, 3) - writer.exposure_time(frame_time, 0) ==
        Approx(0.8 * 0.75 / o.frame_rate));

  // The same four renders, made and averaged here.
  const OrbitTrajectory trajectory(o.motion, o.seed);
  Renderer renderer;
  renderer.add_body(white_box(), 1);
  cv::Mat sum = cv::Mat::zeros(120, 160, CV_32FC3);
  for (int s = 0; s < 4; ++s)
    cv::accumulate(renderer.render(o.color_intrinsics, trajectory.camera_T_world(writer.exposure_time(frame_time, s)),
                                   kRenderColor)
                       .color,
                   sum);
  cv::Mat expected;
  sum.convertTo(expected, CV_8UC3, 0.25);

  const Sequence sequence = Sequence::open(dir.path().string());
  const Frame frame = sequence.load(1);
  const cv::Mat& written = frame.colors[0].image;
  CHECK(cv::norm(written, expected, cv::NORM_INF) <= 1.0);
  // It is blurred: the sharp render at the frame's time differs along the moving edges.
  const cv::Mat sharp = renderer.render(o.color_intrinsics, writer.color_T_world(1), kRenderColor).color;
  cv::Mat difference;
  cv::absdiff(grey(written), grey(sharp), difference);
  CHECK(cv::countNonZero(difference > 8) > 20);

  // Ground truth and depth at the middle of the exposure.
  const Pose* truth = frame.truth("box");
  REQUIRE(truth != nullptr);
  CHECK((truth->matrix() - writer.color_T_world(1).matrix()).cwiseAbs().maxCoeff() <= 1e-12);
  const cv::Mat sharp_depth = renderer.render(o.depth_intrinsics, writer.color_T_world(1), kRenderDepth).depth;
  cv::Mat depth_difference;
  cv::absdiff(frame.depths[0].depth, sharp_depth, depth_difference);
  CHECK(cv::countNonZero(depth_difference > 1e-4f) == 0);  // within the 0.1 mm quantisation
}

TEST_CASE("sensor effects: depth holes along depth edges and at grazing angles") {
  cv::Mat depth(40, 40, CV_32FC1, cv::Scalar(0.5f));
  depth.colRange(20, 40).setTo(1.0f);  // a step from 0.5 to 1 m between columns 19 and 20
  remove_depth_edges(depth, 2);
  for (int c = 0; c < 40; ++c) {
    INFO("column " << c);
    const bool near_step = c >= 17 && c <= 21;
    CHECK((cv::countNonZero(depth.col(c)) == 0) == near_step);
  }

  // A surface turned 80 degrees from the viewing ray loses its depth below an 75 degree
  // limit, a fronto-parallel one keeps it.
  const Intrinsics k = Intrinsics::centred(8, 8, 10.0);
  cv::Mat flat(8, 8, CV_32FC1, cv::Scalar(1.f));
  cv::Mat normals(8, 8, CV_32FC3, cv::Scalar(0.f, 0.f, -1.f));
  normals.colRange(4, 8).setTo(cv::Scalar(std::sin(80.0 * 3.14159265 / 180.0), 0.f, -std::cos(80.0 * 3.14159265 / 180.0)));
  remove_grazing_depth(flat, normals, k, 75.0);
  CHECK(cv::countNonZero(flat.colRange(0, 4)) == 32);
  CHECK(cv::countNonZero(flat.colRange(4, 8)) == 0);
}

TEST_CASE("sensor effects: a sensor's depth is the render without its grazing and edge holes") {
  const Intrinsics k = Intrinsics::centred(160, 120, 150.0);
  Renderer renderer;
  // Turned 77 degrees about the vertical: one face is seen at a grazing angle, one nearly head-on.
  const Pose camera_T_box = Pose::from_rotation_vector(Eigen::Vector3d(0.0, 1.35, 0.0), Eigen::Vector3d(0.0, 0.0, 0.5));
  renderer.set_body_pose(renderer.add_body(white_box(), 1), camera_T_box);

  const RenderOutput rendered = renderer.render(k, Pose(), kRenderDepth | kRenderNormals);
  cv::Mat expected = rendered.depth.clone();
  remove_grazing_depth(expected, rendered.normals, k, 75.0);
  remove_depth_edges(expected, 1);
  SensorNoise holes;
  holes.grazing_angle_deg = 75.0;
  holes.depth_edge_holes_px = 1;
  const cv::Mat measured = render_sensor_depth(renderer, k, Pose(), holes);
  CHECK(cv::countNonZero(measured != expected) == 0);
  CHECK(cv::countNonZero(measured) < cv::countNonZero(rendered.depth));

  // Without holes it is the plain depth render.
  CHECK(cv::countNonZero(render_sensor_depth(renderer, k, Pose(), SensorNoise{}) != rendered.depth) == 0);
}
