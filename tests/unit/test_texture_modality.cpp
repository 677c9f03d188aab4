// SPDX-License-Identifier: GPL-2.0-or-later
// Texture modality on rendered frames with known poses: keyframe lifting, matching, the
// analytic gradient against numeric derivatives, convergence, and frames without the object.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <optional>
#include <unistd.h>

#include "icgp/io/mesh_loader.h"
#include "icgp/modality/reprojection_terms.h"
#include "icgp/modality/texture_modality.h"
#include "icgp/tracker/tracker.h"
#include "icgp/tracker/tracker_builder.h"
#include "test_gradients.h"
#include "test_meshes.h"
#include "test_scene.h"

using namespace icgp;

namespace {

/// `pose` turned by `deg` about the body origin and moved by `mm`.
Pose perturbed(const Pose& pose, double mm, double deg) {
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.8, 0.5).normalized();
  const Eigen::Vector3d direction = Eigen::Vector3d(-0.6, 0.2, 0.77).normalized();
  return Pose(exp_so3<double>(axis * deg * M_PI / 180.0) * pose.rotation(), pose.translation() + direction * mm * 1e-3);
}

/// Starts the cue as the tracker does: with the render of the scene it asks for.
void start_cue(TextureModality& texture, const Frame& frame) {
  icgp::SceneRenderer renderer;
  Renders renders;
  renderer.render({&texture.body()}, texture.render_requests(frame, {Stage::kStart}), renders);
  texture.start(frame, renders);
}

double translation_error_mm(const Pose& a, const Pose& b) { return 1e3 * (a.translation() - b.translation()).norm(); }
double rotation_error_deg(const Pose& a, const Pose& b) {
  return rotation_angle_between(a.rotation(), b.rotation()) * 180.0 / M_PI;
}

}  // namespace

TEST_CASE("texture modality: keyframe points lie on the box and project onto their keypoints") {
  test::MovingTexturedBox s;  // at its start pose
  const Frame frame = s.renderer.render(s.start);
  Body body{"box", s.mesh, s.start};
  TextureModality texture(body, {});
  start_cue(texture, frame);
  const Keyframe& keyframe = texture.keyframe();
  INFO("keyframe points " << keyframe.body_points.size());
  REQUIRE(keyframe.body_points.size() >= 50);
  CHECK(keyframe.descriptors.rows == static_cast<int>(keyframe.body_points.size()));
  const Eigen::Vector3f half(0.04f, 0.08f, 0.03f);  // the box's half extents
  double worst_px = 0.0, worst_surface_mm = 0.0;
  for (std::size_t i = 0; i < keyframe.body_points.size(); ++i) {
    const Eigen::Vector3f& X = keyframe.body_points[i];
    const Eigen::Vector2d x = s.color_k.project<double>(s.start * X.cast<double>());
    worst_px = std::max(worst_px, (x - Eigen::Vector2d(keyframe.image_points[i].x, keyframe.image_points[i].y)).norm());
    // On the surface: inside the box and on one of its faces.
    const Eigen::Vector3f outside = (X.cwiseAbs() - half).cwiseMax(0.f);
    const float to_face = (X.cwiseAbs() - half).cwiseAbs().minCoeff();
    worst_surface_mm = std::max(worst_surface_mm, 1e3 * std::max(outside.norm(), to_face));
  }
  INFO("worst reprojection " << worst_px << " px, worst distance to the surface " << worst_surface_mm << " mm");
  CHECK(worst_px < 1.0);
  CHECK(worst_surface_mm < 1.0);
}

TEST_CASE("texture modality: matches recover a known image-plane shift") {
  test::MovingTexturedBox s;  // at its start pose
  for (const Descriptor descriptor : {Descriptor::kOrientedBrief, Descriptor::kOrb}) {
    INFO(to_string(descriptor));
    Body body{"box", s.mesh, s.start};
    TextureParams params;
    params.descriptor = descriptor;
    TextureModality texture(body, params);
    start_cue(texture, s.renderer.render(s.start));
    // 5 px to the right and 3 px down at the object's depth.
    const double z = s.start.translation().z();
    const Eigen::Vector2d shift_px(5.0, 3.0);
    const Pose shifted(s.start.rotation(), s.start.translation() + Eigen::Vector3d(shift_px.x() * z / s.color_k.fu,
                                                                                    shift_px.y() * z / s.color_k.fv, 0.0));
    texture.correspondences(s.renderer.render(shifted), {}, 0);
    REQUIRE(texture.matches().size() >= 30);
    // The matches that agree with the shift to within 1.5 px (keypoints sit on a 200 px
    // crop's grid, about 0.7 px here), and their mean displacement. The others pair
    // look-alike places of the print (stripes, checks); the Tukey norm leaves them out.
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    int n_agree = 0;
    for (const TextureModality::Match& m : texture.matches()) {
      const cv::Point2f& before = texture.keyframe().image_points[m.keyframe_index];
      const Eigen::Vector2d moved = m.image_point.cast<double>() - Eigen::Vector2d(before.x, before.y);
      if ((moved - shift_px).norm() > 1.5) continue;
      mean += moved;
      ++n_agree;
    }
    mean /= std::max(1, n_agree);
    INFO(texture.matches().size() << " matches of " << texture.keyframe().body_points.size() << " keyframe points, "
                                  << n_agree << " agree with the shift, their mean displacement " << mean.transpose());
    CHECK(n_agree >= 0.6 * texture.matches().size());
    CHECK((mean - shift_px).norm() < 0.25);
  }
}

TEST_CASE("texture modality: a pose uncertainty's spread of the reprojection errors, in closed form") {
  // Identity rotation, points at depth z: a body-frame shift δt moves a point by δt, its
  // image by (f/z)·δt in u and v. A covariance of s² in x alone spreads u by (f s / z)²,
  // v by 0: per coordinate the mean of the two.
  const Intrinsics k{600.0, 600.0, 320.0, 240.0, 640, 480};
  const Posef camera_T_body = Posef::identity();
  const float z = 0.5f, s = 0.002f;
  std::vector<TextureModality::Match> matches;
  for (int i = 0; i < 4; ++i) matches.push_back({Eigen::Vector3f(0.f, 0.f, z), Eigen::Vector2f(320.f, 240.f), i, 1.f});
  Eigen::Matrix<float, 6, 6> covariance = Eigen::Matrix<float, 6, 6>::Zero();
  covariance(3, 3) = s * s;
  const double expected = std::pow(600.0 * s / z, 2) / 2.0;
  CHECK(reprojection_spread(matches, camera_T_body, k, covariance) == Approx(expected).epsilon(1e-5));
  // A match weighted 0 and one behind the camera do not count; a half weight counts half.
  matches.push_back({Eigen::Vector3f(0.f, 0.f, z), Eigen::Vector2f(0.f, 0.f), 4, 0.f});
  matches.push_back({Eigen::Vector3f(0.f, 0.f, -z), Eigen::Vector2f(0.f, 0.f), 5, 1.f});
  matches.push_back({Eigen::Vector3f(0.f, 0.f, 2 * z), Eigen::Vector2f(320.f, 240.f), 6, 0.5f});
  const double with_far = (4 * expected + 0.5 * expected / 4) / 4.5;
  CHECK(reprojection_spread(matches, camera_T_body, k, covariance) == Approx(with_far).epsilon(1e-5));
  CHECK(reprojection_spread(std::vector<TextureModality::Match>{}, camera_T_body, k, covariance) == 0.0);
}

TEST_CASE("texture modality: gradient is the derivative of its log-likelihood") {
  test::MovingTexturedBox s;  // at its start pose
  Body body{"box", s.mesh, s.start};
  TextureModality texture(body, {});
  start_cue(texture, s.renderer.render(s.start));
  const Frame moved = s.renderer.render(perturbed(s.start, 3.0, 2.0));
  for (int corr_iter : {0, 2}) {
    texture.correspondences(moved, {}, corr_iter);
    const CueTerms terms = texture.gradient_hessian(corr_iter, 0);
    const Vec6& g = terms.gradient;
    const Mat66& H = terms.hessian;
    const Vec6 numeric = test::numeric_gradient(texture, corr_iter);
    INFO("corr_iter " << corr_iter << "\nanalytic " << g.transpose() << "\nnumeric  " << numeric.transpose());
    CHECK(g.norm() > 0.0);
    CHECK((g - numeric).norm() < 2e-3 * numeric.norm());
    CHECK(H.eigenvalues().real().maxCoeff() < 1e-9 * H.norm());
  }
}

TEST_CASE("texture modality: texture alone converges from 3 mm / 3 deg") {
  test::MovingTexturedBox s;  // at its start pose
  Tracker tracker;
  Body& body = tracker.add_body({"box", s.mesh, s.start});
  tracker.add_modality(std::make_unique<TextureModality>(body, TextureParams{}));
  tracker.start(s.renderer.render(s.start));  // keyframe at the true pose
  const Pose moved = perturbed(s.start, 3.0, 3.0);
  const Frame frame = s.renderer.render(moved);  // the object moved; tracking starts where it was
  std::vector<BodyResult> results;
  std::vector<double> ms;
  for (int i = 0; i < 3; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    results = tracker.track(frame);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  const double t_mm = translation_error_mm(body.reference_T_body, moved);
  const double r_deg = rotation_error_deg(body.reference_T_body, moved);
  INFO("error " << t_mm << " mm, " << r_deg << " deg, quality " << results[0].quality << ", median "
                << ms[ms.size() / 2] << " ms per frame");
  CHECK(t_mm < 1.0);
  CHECK(r_deg < 0.5);
  CHECK(results[0].quality > 0.3);
}

TEST_CASE("texture modality: frames without the object give quality 0") {
  test::MovingTexturedBox s;  // at its start pose
  const Pose away(s.start.rotation(), Eigen::Vector3d(1.0, 0.0, 0.45));  // far outside the view
  const Frame empty = s.renderer.render(away);
  Tracker tracker;
  Body& body = tracker.add_body({"box", s.mesh, s.start});
  tracker.add_modality(std::make_unique<TextureModality>(body, TextureParams{}));

  SECTION("the object left the view after the start") {
    tracker.start(s.renderer.render(s.start));
    tracker.track(s.renderer.render(s.start));  // the start frame: the keyframe is made
    const auto results = tracker.track(empty);
    CHECK(results[0].modalities[0].score == 0.0);
    CHECK_FALSE(results[0].tracked);
    CHECK(body.reference_T_body.translation().allFinite());
  }
  SECTION("started where the object is out of view: an empty keyframe, the pose kept") {
    body.reference_T_body = away;
    tracker.start(empty);
    tracker.track(empty);  // the start frame
    const auto results = tracker.track(empty);
    CHECK(results[0].modalities[0].score == 0.0);
    CHECK(results[0].modalities[0].n_valid == 0);
    CHECK((body.reference_T_body.translation() - away.translation()).norm() < 1e-12);
  }
  SECTION("the body behind the camera") {
    tracker.start(s.renderer.render(s.start));
    body.reference_T_body = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, -0.5));
    const auto results = tracker.track(empty);
    CHECK(results[0].modalities[0].score == 0.0);
  }
}

TEST_CASE("texture modality: descriptors by name, built by the tracker from a configuration") {
  for (const char* name : {"oriented_brief", "orb", "brisk", "sift", "akaze", "freak", "daisy"}) {
    INFO(name);
    const std::optional<Descriptor> descriptor = parse_descriptor(name);
    REQUIRE(descriptor);
    CHECK(to_string(*descriptor) == name);
    CHECK(make_descriptor(*descriptor));
  }
  CHECK_FALSE(parse_descriptor("surf"));
  const std::string yaml = "/tmp/icgp-texture-config-" + std::to_string(::getpid()) + ".yaml";
  std::ofstream(yaml) << "modalities: [texture]\ntexture: {descriptor: brisk, standard_deviations: [5.0, 1.0]}\n";
  const TrackerConfig config = load_tracker_config(yaml);
  std::remove(yaml.c_str());
  CHECK(config.texture.descriptor == Descriptor::kBrisk);
  CHECK(config.texture.standard_deviations == std::vector<double>{5.0, 1.0});
  CHECK(config.texture.orb_n_features == 300);
  const auto tracker = build_tracker(config, load_mesh(ICGP_MODELS_DIR "/textured_box/textured_box.obj"), "box");
  REQUIRE(tracker->bodies().size() == 1);
}

TEST_CASE("texture modality: on an object without texture it abstains and leaves the quality to the others") {
  test::MovingTexturedBox s;  // at its start pose
  const Mesh plain = test::make_box(0.08f, 0.16f, 0.06f);  // no texture: one flat colour
  test::SceneRenderer renderer(plain, s.color_k, s.depth_k, s.depth_T_color);
  const Frame frame = renderer.render(s.start);
  Tracker tracker;
  Body& body = tracker.add_body({"box", plain, s.start});
  auto texture = std::make_unique<TextureModality>(body, TextureParams{});
  const TextureModality& modality = *texture;
  tracker.add_modality(std::move(texture));
  tracker.start(frame);
  // On the start frame nothing speaks against the given pose; after it, the cue alone cannot
  // vouch for anything.
  CHECK(tracker.track(frame)[0].quality == 1.0);
  const auto results = tracker.track(frame);
  INFO("keyframe points " << modality.keyframe().body_points.size());
  CHECK(results[0].modalities[0].abstained);
  CHECK(results[0].quality == 0.0);
}
