// SPDX-License-Identifier: GPL-2.0-or-later
// Edge modality and the mesh edges it follows: creases and convexity of analytic meshes,
// samples on the box's creases that find them in a rendered frame at the true pose, the
// analytic gradient against numeric derivatives, a moving box followed with the edges alone,
// a start off the truth pulled back, an occluder that hides creases, the mug's own handle
// that hides its rim, and an image of another size.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>

#include "icgp/geometry/mesh_edges.h"
#include "icgp/io/mesh_loader.h"
#include "icgp/modality/edge_modality.h"
#include "icgp/render/renderer.h"
#include "icgp/tracker/tracker.h"
#include "test_gradients.h"
#include "test_scene.h"

using namespace icgp;

namespace {

/// An axis-aligned box of the given sides centred at the origin, two triangles a face,
/// counter-clockwise seen from outside.
Mesh box_mesh(float sx, float sy, float sz) {
  MeshPart part;
  for (int i = 0; i < 8; ++i)
    part.vertices.emplace_back((i & 1 ? 0.5f : -0.5f) * sx, (i & 2 ? 0.5f : -0.5f) * sy, (i & 4 ? 0.5f : -0.5f) * sz);
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    part.triangles.emplace_back(q[0], q[1], q[2]);
    part.triangles.emplace_back(q[0], q[2], q[3]);
  }
  Mesh mesh;
  mesh.parts.push_back(part);
  return mesh;
}

using Scene = test::MovingTexturedBox;

/// The largest distance (pixels) between the projections of the mesh's bounding-box corners
/// at `estimate` and at `truth`: what the edges observe. Seen from one camera, a box's
/// outline pins where it is in the image far better than its depth or a turn about its own
/// long axis (ViSP's edge tracker shares this), so the tests bound the image error. The
/// corner hidden behind the box moves most under those turns: the largest error is its.
double corner_error_px(const Mesh& mesh, const Intrinsics& k, const Pose& estimate, const Pose& truth) {
  Eigen::Vector3f lo, hi;
  mesh.bounds(lo, hi);
  double worst = 0.0;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d corner(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
    worst = std::max(worst, (k.project<double>(estimate * corner) - k.project<double>(truth * corner)).norm());
  }
  return worst;
}

/// A tracker with the edge cue alone on `mesh`, started at `pose` on `frame`.
struct EdgeTracker {
  Tracker tracker;
  Body* body;
  EdgeModality* edge;
  EdgeTracker(const Mesh& mesh, const Pose& pose, const Frame& frame, EdgeParams params = {}) {
    body = &tracker.add_body({"box", mesh, pose});
    auto cue = std::make_unique<EdgeModality>(*body, params, "Camera1");
    edge = cue.get();
    tracker.add_modality(std::move(cue));
    tracker.start(frame);
  }
};

/// Runs the cue's correspondences of iteration `corr_iter` on `frame` at its body's pose,
/// with the renders it asks for.
void find_correspondences(EdgeModality& edge, const Frame& frame, int corr_iter, const std::vector<BodyExtent>* scene,
                          const std::vector<const Body*>& bodies) {
  icgp::SceneRenderer renderer;
  Renders renders;
  renderer.render(bodies, edge.render_requests(frame, {Stage::kCorrespondences, corr_iter, scene}), renders);
  edge.correspondences(frame, renders, corr_iter);
}

/// Starts the cue on `frame` at its body's pose, with the renders it asks for.
void start_cue(EdgeModality& edge, const Frame& frame, const std::vector<BodyExtent>* scene,
               const std::vector<const Body*>& bodies) {
  icgp::SceneRenderer renderer;
  Renders renders;
  renderer.render(bodies, edge.render_requests(frame, {Stage::kStart, 0, scene}), renders);
  edge.start(frame, renders);
}

double distance_to_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double s = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (p - (a + s * (b - a))).norm();
}

}  // namespace

TEST_CASE("mesh edges: a triangulated box has its 12 sides as creases, its face diagonals not") {
  const Mesh box = box_mesh(0.1f, 0.2f, 0.3f);
  const std::vector<MeshEdge> edges = mesh_edges(box, 30.0);
  REQUIRE(edges.size() == 18);  // 12 sides + 6 diagonals
  int creases = 0;
  for (const MeshEdge& e : edges) {
    const double length = (e.b - e.a).norm();
    const bool side = std::abs(length - 0.1) < 1e-6 || std::abs(length - 0.2) < 1e-6 || std::abs(length - 0.3) < 1e-6;
    CHECK(e.crease == side);
    if (e.crease) {
      ++creases;
      CHECK(std::abs(e.normal_1.dot(e.normal_2)) < 1e-9);  // faces at right angles
    } else {
      CHECK(e.normal_1.dot(e.normal_2) > 1.0 - 1e-9);  // one face's two triangles
    }
  }
  CHECK(creases == 12);
  // Faces at 90° are no crease at a crease angle above 90°.
  for (const MeshEdge& e : mesh_edges(box, 95.0)) CHECK_FALSE(e.crease);
}

TEST_CASE("mesh edges: a box is convex, a mug with a handle is not") {
  CHECK(is_convex(box_mesh(0.1f, 0.2f, 0.3f)));
  CHECK(is_convex(load_mesh(ICGP_MODELS_DIR "/textured_box/textured_box.obj")));
  CHECK_FALSE(is_convex(load_mesh(ICGP_MODELS_DIR "/textureless_mug/textureless_mug.obj")));
  // Two boxes side by side along x, one twice as tall: an L step, not convex.
  Mesh step = box_mesh(0.1f, 0.1f, 0.1f);
  Mesh tall = box_mesh(0.1f, 0.2f, 0.1f);
  for (Eigen::Vector3f& v : tall.parts[0].vertices) v += Eigen::Vector3f(0.1f, 0.05f, 0.f);
  step.append(tall);
  CHECK_FALSE(is_convex(step));
}

TEST_CASE("edge modality: at the true pose its samples lie on visible creases and find them in the image") {
  Scene s;
  const Frame frame = s.renderer.render(s.start);
  Body body{"box", s.mesh, s.start};
  EdgeModality edge(body, {}, "Camera1");
  start_cue(edge, frame, nullptr, {&body});
  for (int corr_iter = 0; corr_iter < 5; ++corr_iter) find_correspondences(edge, frame, corr_iter, nullptr, {&body});
  REQUIRE(edge.samples().size() >= 100);
  const std::vector<MeshEdge> edges = mesh_edges(s.mesh, 30.0);
  const Eigen::Vector3d camera_in_body = s.start.inverse().translation();
  int matched = 0;
  std::vector<double> distances;
  for (const EdgeModality::Sample& sample : edge.samples()) {
    // On a crease with a face towards the camera.
    const Eigen::Vector3d p = sample.body_point.cast<double>();
    bool on_visible_crease = false;
    for (const MeshEdge& e : edges)
      if (e.crease && distance_to_segment(p, e.a, e.b) < 1e-6)
        on_visible_crease = on_visible_crease || e.normal_1.dot(camera_in_body - p) > 0.0 ||
                            e.normal_2.dot(camera_in_body - p) > 0.0;
    CHECK(on_visible_crease);
    if (sample.polarity == 0.f) continue;
    ++matched;
    const Eigen::Vector2d projected = s.color_k.project<double>(s.start * p);
    distances.push_back(std::abs(sample.normal.cast<double>().dot(projected - sample.found.cast<double>())));
  }
  // The box's faces are shaded apart and textured: most creases show; where they show, the
  // step is within a pixel of where the crease projects (antialiasing blurs it by a pixel).
  std::sort(distances.begin(), distances.end());
  INFO(matched << " of " << edge.samples().size() << " samples matched; median distance "
               << distances[distances.size() / 2] << " px");
  CHECK(matched >= static_cast<int>(0.7 * edge.samples().size()));
  CHECK(distances[distances.size() / 2] < 1.0);
}

TEST_CASE("edge modality: gradient is the derivative of its log-likelihood") {
  Scene s;
  Body body{"box", s.mesh, s.start};
  EdgeModality edge(body, {}, "Camera1");
  const Frame moved = s.renderer.render(s.at(3));
  start_cue(edge, moved, nullptr, {&body});
  for (int corr_iter = 0; corr_iter < 4; ++corr_iter) {
    find_correspondences(edge, moved, corr_iter, nullptr, {&body});
    if (corr_iter != 0 && corr_iter != 3) continue;
    const CueTerms terms = edge.gradient_hessian(corr_iter, 0);
    const Vec6 numeric = test::numeric_gradient(edge, corr_iter);
    INFO("corr_iter " << corr_iter << "\nanalytic " << terms.gradient.transpose() << "\nnumeric  "
                      << numeric.transpose());
    CHECK(terms.n_correspondences > 50);
    CHECK(terms.gradient.norm() > 0.0);
    CHECK((terms.gradient - numeric).norm() < 2e-3 * numeric.norm());
    CHECK(terms.hessian.eigenvalues().real().maxCoeff() < 1e-9 * terms.hessian.norm());
  }
}

TEST_CASE("edge modality: the edges alone follow a moving box in front of clutter") {
  Scene s;
  EdgeTracker t(s.mesh, s.at(0), s.renderer.render(s.at(0)));
  constexpr int kFrames = 15;
  double worst_px = 0.0;
  for (int i = 1; i <= kFrames; ++i) {
    const auto results = t.tracker.track(s.renderer.render(s.at(i)));
    worst_px = std::max(worst_px, corner_error_px(s.mesh, s.color_k, t.body->reference_T_body, s.at(i)));
    CHECK(results[0].tracked);
  }
  // A frozen pose would be off by the last frame's motion.
  INFO("worst corner error " << worst_px << " px; a frozen pose's "
                             << corner_error_px(s.mesh, s.color_k, s.at(0), s.at(kFrames)) << " px");
  CHECK(worst_px < 4.0);
}

TEST_CASE("edge modality: a jump of 4 mm and 2 degrees is followed") {
  Scene s;
  const Pose jumped = Pose(exp_so3<double>(Eigen::Vector3d(0.3, -0.8, 0.5).normalized() * 2.0 * M_PI / 180.0) *
                               s.start.rotation(),
                           s.start.translation() + Eigen::Vector3d(0.003, -0.002, 0.002));
  EdgeTracker t(s.mesh, jumped, s.renderer.render(jumped));
  t.tracker.track(s.renderer.render(jumped));  // the creases' steps are known from here
  const Frame frame = s.renderer.render(s.start);
  for (int i = 0; i < 3; ++i) t.tracker.track(frame);
  const double error = corner_error_px(s.mesh, s.color_k, t.body->reference_T_body, s.start);
  INFO("corner error " << error << " px; before the jump " << corner_error_px(s.mesh, s.color_k, jumped, s.start) << " px");
  CHECK(error < 4.0);
}

TEST_CASE("edge modality: another body in front hides the creases behind it") {
  Scene s;
  const Frame frame = s.renderer.render(s.start);
  Body box{"box", s.mesh, s.start};
  // A plate between the camera and the box, covering the image's left half of the box.
  const Eigen::Vector3d box_centre = s.start.translation();
  const Body plate{"plate", box_mesh(0.2f, 0.3f, 0.002f),
                   Pose(Eigen::Matrix3d::Identity(), box_centre + Eigen::Vector3d(-0.1, 0.0, -0.12))};
  const double plate_right = s.color_k.project<double>(plate.reference_T_body * Eigen::Vector3d(0.1, 0.0, 0.0)).x();
  EdgeModality edge(box, {}, "Camera1");
  const std::vector<BodyExtent> scene = {{"box", box_centre, 0.1}, {"plate", plate.reference_T_body.translation(), 0.2}};
  start_cue(edge, frame, &scene, {&box, &plate});
  find_correspondences(edge, frame, 0, &scene, {&box, &plate});
  REQUIRE(edge.samples().size() >= 50);
  for (const EdgeModality::Sample& sample : edge.samples())
    CHECK(s.color_k.project<double>(s.start * sample.body_point.cast<double>()).x() > plate_right - 2.0);
  // Without the plate, creases on the left are sampled.
  EdgeModality alone(box, {}, "Camera1");
  start_cue(alone, frame, nullptr, {&box});
  find_correspondences(alone, frame, 0, nullptr, {&box});
  const auto left = std::count_if(alone.samples().begin(), alone.samples().end(), [&](const EdgeModality::Sample& sample) {
    return s.color_k.project<double>(s.start * sample.body_point.cast<double>()).x() < plate_right - 10.0;
  });
  CHECK(left > 20);
}

TEST_CASE("edge modality: a body's own parts hide its creases (the mug's handle and far rim)") {
  const Mesh mug = load_mesh(ICGP_MODELS_DIR "/textureless_mug/textureless_mug.obj");
  const Intrinsics k{600.0, 600.0, 320.0, 240.0, 640, 480};
  // Looking down at the mug from the side of its handle.
  const Pose pose = Pose::from_rotation_vector(Eigen::Vector3d(1.9, 0.0, 0.0), Eigen::Vector3d(0.0, 0.0, 0.35));
  Renderer renderer;
  const Renderer::BodyHandle handle = renderer.add_body(mug, 1);
  renderer.set_body_pose(handle, pose);
  const cv::Mat depth = renderer.render(k, Pose(), kRenderDepth).depth;
  Frame frame;
  frame.colors.push_back({"Camera1", k, Pose(), renderer.render(k, Pose(), kRenderColor).color});

  Body body{"mug", mug, pose};
  EdgeModality edge(body, {}, "Camera1");
  start_cue(edge, frame, nullptr, {&body});
  find_correspondences(edge, frame, 0, nullptr, {&body});
  REQUIRE(edge.samples().size() >= 20);
  int hidden = 0;
  for (const EdgeModality::Sample& sample : edge.samples()) {
    const Eigen::Vector3d X = pose * sample.body_point.cast<double>();
    const Eigen::Vector2d x = k.project<double>(X);
    const int u = static_cast<int>(std::lround(x.x())), v = static_cast<int>(std::lround(x.y()));
    if (u < 0 || v < 0 || u >= depth.cols || v >= depth.rows) continue;
    // The nearest surface within a pixel is at the sample's depth: nothing of the mug is
    // well in front of it.
    float nearest = 1e9f;
    for (int dv = -1; dv <= 1; ++dv)
      for (int du = -1; du <= 1; ++du) {
        const float d = depth.at<float>(std::clamp(v + dv, 0, depth.rows - 1), std::clamp(u + du, 0, depth.cols - 1));
        if (d > 0.f) nearest = std::min(nearest, d);
      }
    if (nearest < X.z() - 0.005) ++hidden;
  }
  CHECK(hidden == 0);
}

TEST_CASE("edge modality: an image of another size and a grey image are read afresh") {
  Scene s;
  EdgeTracker t(s.mesh, s.at(0), s.renderer.render(s.at(0)));
  t.tracker.track(s.renderer.render(s.at(1)));
  // The same camera at half the resolution, then grey.
  const Intrinsics half_k = s.color_k.scaled(320, 240);
  test::SceneRenderer half(s.mesh, half_k, s.depth_k.scaled(320, 240), s.depth_T_color);
  t.tracker.track(half.render(s.at(2)));
  for (const EdgeModality::Sample& sample : t.edge->samples())
    if (sample.polarity != 0.f) CHECK(half_k.contains(sample.found.x(), sample.found.y()));
  CHECK(corner_error_px(s.mesh, half_k, t.body->reference_T_body, s.at(2)) < 2.5);
  Frame grey = half.render(s.at(3));
  cv::cvtColor(grey.colors[0].image, grey.colors[0].image, cv::COLOR_BGR2GRAY);
  t.tracker.track(grey);
  CHECK(corner_error_px(s.mesh, half_k, t.body->reference_T_body, s.at(3)) < 2.5);
}

TEST_CASE("edge modality: bad parameters and a frame without its camera are named") {
  Scene s;
  Body body{"box", s.mesh, s.start};
  EdgeParams no_step;
  no_step.sample_step = 0.0;
  CHECK_THROWS_WITH(EdgeModality(body, no_step, "Camera1"), Catch::Contains("sample_step"));
  EdgeModality edge(body, {}, "Camera3");
  CHECK_THROWS_WITH(edge.correspondences(s.renderer.render(s.start), {}, 0), Catch::Contains("Camera3"));
}
