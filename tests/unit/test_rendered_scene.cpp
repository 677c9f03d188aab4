// SPDX-License-Identifier: GPL-2.0-or-later
// Modeled occlusions and region checking (ALGORITHMS.md §6, §7) against geometry: a box
// behind another, rendered by the tracker's SceneRenderer, and points whose visibility
// follows from where they lie.
#include <catch2/catch.hpp>

#include "icgp/modality/rendered_scene.h"
#include "icgp/render/scene_renderer.h"
#include "test_meshes.h"

using namespace icgp;

namespace {

/// A 0.1 m box at 0.6 m and a 0.04 m wide bar at 0.4 m in front of its left half; a
/// focused render of the box's crop in a 640 x 480 camera.
struct TwoBoxes {
  Intrinsics k = Intrinsics::centred(640, 480, 600.0);
  Body box{"box", test::make_box(0.1f, 0.1f, 0.1f), Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 0.6))};
  Body bar{"bar", test::make_box(0.04f, 0.3f, 0.02f), Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.03, 0, 0.4))};
  SceneRenderer renderer;
  Renders renders;
  RenderedScene scene;

  TwoBoxes() {
    const RenderRequest request =
        *focused_render_request("Camera1", k, Pose(), box.reference_T_body, bounding_sphere(box.mesh), 200);
    renderer.render({&box, &bar}, {request}, renders);
    scene = RenderedScene(renders.at(request), renders.id("box"));
  }

  /// A point on the box's front face (z = -0.05 in the box) at (x, y) in the box frame, in
  /// the camera frame.
  Eigen::Vector3f front(float x, float y) const {
    return (box.reference_T_body * Eigen::Vector3d(x, y, -0.05)).cast<float>();
  }
};

}  // namespace

TEST_CASE("modeled occlusion: points behind another body are hidden, others are not") {
  TwoBoxes s;
  // The bar covers box x in [-0.05, -0.01] at y = 0 (it is in front, its projection wider).
  CHECK(s.scene.hidden(s.front(-0.03f, 0.0f), 0.f, 0.01, 0.03));
  CHECK_FALSE(s.scene.hidden(s.front(0.03f, 0.0f), 0.f, 0.01, 0.03));
  // Just inside the bar's shadow (its edge projects to box x = -0.014): hidden; two radii
  // right of it: not.
  CHECK(s.scene.hidden(s.front(-0.02f, 0.0f), 0.f, 0.01, 0.03));
  CHECK_FALSE(s.scene.hidden(s.front(0.01f, 0.0f), 0.f, 0.01, 0.03));
  // The bar is 0.2 m nearer: a threshold beyond that hides nothing.
  CHECK_FALSE(s.scene.hidden(s.front(-0.03f, 0.0f), 0.f, 0.01, 0.25));
  // The box's own surface never hides its points, whatever the threshold.
  CHECK_FALSE(s.scene.hidden(s.front(0.03f, 0.0f) + Eigen::Vector3f(0, 0, 0.2f), 0.f, 0.01, 0.0));
}

TEST_CASE("region checking: a contour point is valid on the free silhouette, not where another body covers it") {
  TwoBoxes s;
  const Eigen::Vector2f right(1.f, 0.f), left(-1.f, 0.f), down(0.f, 1.f);
  // The box's right edge (x = +0.05) is free: inside is the box, outside the background.
  CHECK(s.scene.on_silhouette(s.front(0.05f, 0.0f), right, true));
  // Its left edge lies under the bar: inside is the bar.
  CHECK_FALSE(s.scene.on_silhouette(s.front(-0.05f, 0.0f), left, true));
  // A point in the middle of the face is no contour: its outside is the box itself, which
  // only a cue on a region of a larger body accepts.
  CHECK_FALSE(s.scene.on_silhouette(s.front(0.03f, 0.0f), right, true));
  CHECK(s.scene.on_silhouette(s.front(0.03f, 0.0f), right, false));
  // The bottom edge right of the bar is free.
  CHECK(s.scene.on_silhouette(s.front(0.03f, 0.05f), down, true));
  // An empty scene (no other body) rules nothing out.
  CHECK(RenderedScene().on_silhouette(s.front(0.03f, 0.0f), right, true));
  CHECK_FALSE(RenderedScene().hidden(s.front(-0.03f, 0.0f), 0.f, 0.01, 0.03));
}

TEST_CASE("a cue asks for the scene's render only when another body may cover its body") {
  const Intrinsics k = Intrinsics::centred(640, 480, 600.0);
  const Body box{"box", test::make_box(0.1f, 0.1f, 0.1f), Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 0.6))};
  const Sphere sphere = bounding_sphere(box.mesh);
  const SceneCrop crop(box, "Camera1", 200);
  auto request_with_other_at = [&](const Eigen::Vector3d& centre, Stage::Kind kind = Stage::kCorrespondences,
                                   int corr_iter = 0) {
    const std::vector<BodyExtent> scene = {{"box", box.reference_T_body * sphere.centre, sphere.radius},
                                           {"bar", centre, 0.05}};
    return crop.request({kind, corr_iter, &scene}, k, Pose());
  };
  // In front of the box, overlapping it in the image: a render of the box's crop.
  const std::optional<RenderRequest> request = request_with_other_at({0.05, 0.0, 0.4});
  REQUIRE(request);
  CHECK(request->size == 200);
  CHECK(*request == *focused_render_request("Camera1", k, Pose(), box.reference_T_body, sphere, 200));
  // Far to the side: nothing can hide the box, no render.
  CHECK_FALSE(request_with_other_at({0.5, 0.0, 0.6}));
  // Reaching the camera's plane: it may cover anything.
  CHECK(request_with_other_at({0.5, 0.0, 0.02}));
  // Only at the first correspondence iteration of a frame.
  CHECK_FALSE(request_with_other_at({0.05, 0.0, 0.4}, Stage::kCorrespondences, 1));
  CHECK_FALSE(request_with_other_at({0.05, 0.0, 0.4}, Stage::kFinish));
  // The body alone: no render.
  CHECK_FALSE(crop.request({Stage::kCorrespondences, 0, nullptr}, k, Pose()));
}
