// SPDX-License-Identifier: GPL-2.0-or-later
// Flow modality on rendered frames with known poses: corners lifted onto the box, the
// analytic gradient against numeric derivatives, a moving box followed with the flow alone,
// a glint that stays put while the box moves, and an image of another size.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>

#include "icgp/modality/flow_modality.h"
#include "icgp/tracker/tracker.h"
#include "test_gradients.h"
#include "test_scene.h"

using namespace icgp;

namespace {

using Scene = test::MovingTexturedBox;

void start_cue(FlowModality& flow, const Frame& frame) {
  icgp::SceneRenderer renderer;
  Renders renders;
  renderer.render({&flow.body()}, flow.render_requests(frame, {Stage::kStart}), renders);
  flow.start(frame, renders);
}

double translation_error_mm(const Pose& a, const Pose& b) { return 1e3 * (a.translation() - b.translation()).norm(); }
double rotation_error_deg(const Pose& a, const Pose& b) {
  return rotation_angle_between(a.rotation(), b.rotation()) * 180.0 / M_PI;
}

/// A tracker with the flow cue alone on the box, started at `pose` on `frame`.
struct FlowTracker {
  Tracker tracker;
  Body* body;
  FlowModality* flow;
  FlowTracker(const Scene& s, const Frame& frame, FlowParams params = {}) {
    body = &tracker.add_body({"box", s.mesh, s.start});
    auto cue = std::make_unique<FlowModality>(*body, params, "Camera1", "Camera2");
    flow = cue.get();
    tracker.add_modality(std::move(cue));
    tracker.start(frame);
  }
};

}  // namespace

TEST_CASE("flow modality: corners lie on the box and project onto where they were found") {
  Scene s;
  const Frame frame = s.renderer.render(s.start);
  Body body{"box", s.mesh, s.start};
  FlowModality flow(body, {}, "Camera1", "Camera2");
  start_cue(flow, frame);
  INFO(flow.matches().size() << " corners");
  // ViSP's KLT density at its default settings: over a hundred corners on this box of ~200 px.
  REQUIRE(flow.matches().size() >= 100);
  const Eigen::Vector3f half(0.04f, 0.08f, 0.03f);  // the box's half extents
  double worst_px = 0.0, worst_surface_mm = 0.0, worst_normal_deg = 0.0;
  for (const FlowModality::Match& m : flow.matches()) {
    const Eigen::Vector2d x = s.color_k.project<double>(s.start * m.body_point.cast<double>());
    worst_px = std::max(worst_px, (x - m.image_point.cast<double>()).norm());
    const Eigen::Vector3f outside = (m.body_point.cwiseAbs() - half).cwiseMax(0.f);
    const Eigen::Vector3f to_faces = (m.body_point.cwiseAbs() - half).cwiseAbs();
    int face = 0;
    const float to_face = to_faces.minCoeff(&face);
    worst_surface_mm = std::max(worst_surface_mm, 1e3 * std::max(outside.norm(), to_face));
    // The normal of the face the corner is on, pointing out of the box.
    if (m.body_normal.isZero()) continue;
    Eigen::Vector3f face_normal = Eigen::Vector3f::Zero();
    face_normal[face] = m.body_point[face] > 0.f ? 1.f : -1.f;
    worst_normal_deg = std::max(worst_normal_deg, std::acos(std::clamp(m.body_normal.dot(face_normal), -1.f, 1.f)) *
                                                      180.0 / M_PI);
  }
  INFO("worst reprojection " << worst_px << " px, distance to the surface " << worst_surface_mm
                             << " mm, normal " << worst_normal_deg << " deg");
  CHECK(worst_px < 0.01);  // lifted exactly where it was found
  CHECK(worst_surface_mm < 1.0);
  CHECK(worst_normal_deg < 5.0);
}

TEST_CASE("flow modality: gradient is the derivative of its log-likelihood") {
  Scene s;
  Body body{"box", s.mesh, s.start};
  FlowModality flow(body, {}, "Camera1", "Camera2");
  start_cue(flow, s.renderer.render(s.start));
  const Frame moved = s.renderer.render(s.at(3));
  for (int corr_iter : {0, 2}) {
    flow.correspondences(moved, {}, corr_iter);
    const CueTerms terms = flow.gradient_hessian(corr_iter, 0);
    const Vec6 numeric = test::numeric_gradient(flow, corr_iter);
    INFO("corr_iter " << corr_iter << "\nanalytic " << terms.gradient.transpose() << "\nnumeric  "
                      << numeric.transpose());
    CHECK(terms.gradient.norm() > 0.0);
    CHECK((terms.gradient - numeric).norm() < 2e-3 * numeric.norm());
    CHECK(terms.hessian.eigenvalues().real().maxCoeff() < 1e-9 * terms.hessian.norm());
  }
}

TEST_CASE("flow modality: the flow alone follows a moving box") {
  Scene s;
  FlowTracker t(s, s.renderer.render(s.at(0)));
  constexpr int kFrames = 15;
  double worst_mm = 0.0, worst_deg = 0.0;
  std::size_t fewest = 100000;
  for (int i = 1; i <= kFrames; ++i) {
    const auto results = t.tracker.track(s.renderer.render(s.at(i)));
    worst_mm = std::max(worst_mm, translation_error_mm(t.body->reference_T_body, s.at(i)));
    worst_deg = std::max(worst_deg, rotation_error_deg(t.body->reference_T_body, s.at(i)));
    fewest = std::min(fewest, t.flow->matches().size());
    // The first frame's corners were lifted at the start pose: the cue vouches from the second.
    if (i > 1) CHECK(results[0].tracked);
  }
  // A frozen pose would be 15 mm and 9° off by the last frame.
  INFO("worst error " << worst_mm << " mm, " << worst_deg << " deg; fewest points " << fewest);
  CHECK(worst_mm < 1.5);
  CHECK(worst_deg < 0.6);
  CHECK(fewest >= 100);
}

TEST_CASE("flow modality: a glint that stays put while the box moves is dropped") {
  Scene s;
  // A bright square on the box's image at a fixed place of every frame: a reflection of a
  // lamp, which does not move with the surface. Its four corners are strong corners.
  const auto with_glint = [&](Frame frame) {
    const cv::Point2i centre(cvRound(s.color_k.project<double>(s.start.translation()).x()),
                             cvRound(s.color_k.project<double>(s.start.translation()).y()));
    cv::rectangle(frame.colors[0].image, cv::Rect(centre.x - 4, centre.y - 4, 9, 9), cv::Scalar(255, 255, 255),
                  cv::FILLED);
    return frame;
  };
  const Eigen::Vector2f glint = s.color_k.project<double>(s.start.translation()).cast<float>();
  FlowTracker t(s, with_glint(s.renderer.render(s.at(0))));
  double worst_mm = 0.0, worst_deg = 0.0;
  for (int i = 1; i <= 10; ++i) {
    t.tracker.track(with_glint(s.renderer.render(s.at(i))));
    worst_mm = std::max(worst_mm, translation_error_mm(t.body->reference_T_body, s.at(i)));
    worst_deg = std::max(worst_deg, rotation_error_deg(t.body->reference_T_body, s.at(i)));
  }
  // Points still at the glint follow the glint, not the box: none may weigh in.
  int at_glint = 0;
  for (const FlowModality::Match& m : t.flow->matches())
    if ((m.image_point - glint).norm() < 8.f && m.weight > 0.f) ++at_glint;
  INFO("worst error " << worst_mm << " mm, " << worst_deg << " deg; weighted points at the glint " << at_glint);
  CHECK(at_glint == 0);
  CHECK(worst_mm < 1.5);
  CHECK(worst_deg < 0.6);
}

TEST_CASE("flow modality: an image of another size restarts the flow") {
  Scene s;
  FlowTracker t(s, s.renderer.render(s.at(0)));
  t.tracker.track(s.renderer.render(s.at(1)));
  REQUIRE_FALSE(t.flow->matches().empty());
  // The same camera at half the resolution: the points of the last image cannot be followed.
  const Intrinsics half_k = s.color_k.scaled(320, 240);
  test::SceneRenderer half(s.mesh, half_k, s.depth_k.scaled(320, 240), s.depth_T_color);
  t.tracker.track(half.render(s.at(2)));
  // The corners are found again in the new image, on the box.
  REQUIRE(t.flow->matches().size() >= 20);
  for (const FlowModality::Match& m : t.flow->matches()) {
    CHECK(half_k.contains(m.image_point.x(), m.image_point.y()));
    CHECK((half_k.project<double>(t.body->reference_T_body * m.body_point.cast<double>()) -
           m.image_point.cast<double>()).norm() < 0.01);
  }
  // And they are followed from there.
  t.tracker.track(half.render(s.at(3)));
  CHECK(translation_error_mm(t.body->reference_T_body, s.at(3)) < 2.0);
  CHECK(rotation_error_deg(t.body->reference_T_body, s.at(3)) < 1.0);
}
