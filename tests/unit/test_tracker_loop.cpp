// SPDX-License-Identifier: GPL-2.0-or-later
// The tracker loop against analytic truth: the optimizer's per-cue parts and their sum, a
// cue written outside the library (docs/architecture.md's example), and the render step
// that hands each cue the renders it asked for.
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>

#include "example_position_cue.h"
#include "icgp/optimizer/optimizer.h"
#include "icgp/tracker/tracker.h"
#include "test_gradients.h"
#include "test_meshes.h"

using namespace icgp;

namespace {

Pose some_pose() {
  return Pose::from_rotation_vector(Eigen::Vector3d(0.3, -0.2, 0.5), Eigen::Vector3d(0.02, -0.01, 0.6));
}

/// Asks for a focused depth render of the whole image in every correspondence iteration
/// and reads it where the body's origin projects.
class OriginProbe final : public Modality {
 public:
  OriginProbe(Body& body, const Intrinsics& k) : Modality(body), k_(k) {}

  std::string name() const override { return "origin probe"; }
  const std::string& camera() const override { return camera_; }
  std::vector<RenderRequest> render_requests(const Frame&, Stage stage) const override {
    if (stage.kind != Stage::kCorrespondences) return {};
    ++n_requests;
    return {request()};
  }
  void start(const Frame&, const Renders&) override {}
  void correspondences(const Frame&, const Renders& renders, int) override {
    const FocusedRender& r = renders.at(request());
    const Eigen::Vector2d x = r.intrinsics.project<double>(body().reference_T_body.translation());
    const int col = static_cast<int>(std::lround(x.x())), row = static_cast<int>(std::lround(x.y()));
    depth_at_origin = r.depth.at<float>(row, col);
    id_at_origin = r.ids.at<std::uint8_t>(row, col);
    own_id = renders.id(body().name);
    ++n_renders_read;
  }
  CueTerms gradient_hessian(int, int) override { return {}; }
  double log_likelihood(int) const override { return 0.0; }
  void finish(const Frame&, const Renders&) override {}
  ModalityQuality quality() const override { return {1.0, 1.0, 1, false, 0.0}; }
  void append_residuals(std::vector<double>&, std::vector<double>&) const override {}

  mutable int n_requests = 0;
  int n_renders_read = 0;
  float depth_at_origin = 0.f;
  std::uint8_t id_at_origin = 0, own_id = 0;

 private:
  RenderRequest request() const { return {camera_, k_, Pose(), ImageSquare{0.0, 0.0, 200.0}, 200}; }

  Intrinsics k_;
  std::string camera_ = "Camera1";
};

}  // namespace

TEST_CASE("example cue: its gradient is the derivative of its log-likelihood") {
  Body body{"object", Mesh{}, some_pose()};
  example::PositionCue cue(body, Eigen::Vector3d(0.05, 0.03, 0.55), 0.002);
  const CueTerms terms = cue.gradient_hessian(0, 0);
  const Vec6 numeric = test::numeric_gradient(cue, 0);
  INFO("analytic " << terms.gradient.transpose() << "\nnumeric  " << numeric.transpose());
  CHECK((terms.gradient - numeric).norm() < 1e-6 * numeric.norm());
  CHECK(terms.n_correspondences == 1);
}

TEST_CASE("example cue: registered with a tracker, it alone moves the body onto its measurement") {
  Tracker tracker;
  Body& body = tracker.add_body({"object", Mesh{}, some_pose()});
  const Eigen::Vector3d measured(0.05, 0.03, 0.55);
  tracker.add_modality(std::make_unique<example::PositionCue>(body, measured, 0.001));
  const Eigen::Matrix3d R = body.reference_T_body.rotation();
  tracker.start(Frame{});
  const BodyResult result = tracker.track(Frame{}).front();
  // Each update solves (1/σ² + λ_t) θ_t = e/σ²: the error shrinks by λ_t σ² / (1 + λ_t σ²)
  // ≈ 0.029 per update, 10 updates in all.
  const double expected = 0.08 * std::pow(30000.0 * 1e-6 / (1.0 + 30000.0 * 1e-6), 10);
  CHECK((result.reference_T_body.translation() - measured).norm() < 2.0 * expected);
  CHECK(rotation_angle_between(result.reference_T_body.rotation(), R) < 1e-12);
  CHECK(result.tracked);
  CHECK(result.quality > 0.99);

  // The optimizer kept the cue's part of the last update, and the sum is that part.
  const std::vector<CueTerms>& parts = tracker.last_cue_terms("object");
  REQUIRE(parts.size() == 1);
  CHECK(parts.front().n_correspondences == 1);
  CHECK(tracker.last_hessian("object") == parts.front().hessian);
  CHECK(parts.front().hessian(3, 3) == Approx(-1e6));
}

TEST_CASE("optimizer: keeps each cue's part and sums them; the step is the regularised Newton step") {
  Body body{"object", Mesh{}, some_pose()};
  example::PositionCue a(body, Eigen::Vector3d(0.05, 0.03, 0.55), 0.002);
  example::PositionCue b(body, Eigen::Vector3d(0.01, -0.02, 0.62), 0.004);
  const Pose before = body.reference_T_body;
  const CueTerms ta = a.gradient_hessian(0, 0), tb = b.gradient_hessian(0, 0);
  const Optimizer optimizer({1000.0, 30000.0});
  CueTermSum terms;
  optimizer.step(body, {&a, &b}, terms, 0, 0);
  REQUIRE(terms.per_cue().size() == 2);
  CHECK(terms.per_cue()[0].gradient == ta.gradient);
  CHECK(terms.per_cue()[1].gradient == tb.gradient);
  CHECK(terms.total().gradient.isApprox(ta.gradient + tb.gradient));
  CHECK(terms.total().hessian.isApprox(ta.hessian + tb.hessian));
  CHECK(terms.total().n_correspondences == 2);
  // θ_t = (1/σa² + 1/σb² + λ_t)⁻¹ Σ g_t, and no rotation.
  const Eigen::Vector3d theta_t = (ta.gradient + tb.gradient).tail<3>() / (1 / 4e-6 + 1 / 16e-6 + 30000.0);
  const Eigen::Vector3d moved = body.reference_T_body.translation() - before.translation();
  CHECK((moved - before.rotation() * theta_t).norm() < 1e-12);
  CHECK_THROWS_WITH(Optimizer({-1.0, 0.0}), Catch::Contains("non-negative"));
}

namespace {

/// A position cue that asks where the other cues would take the body (as the texture cue
/// does, Modality::weighs_against_others) and keeps what it is told.
class AskingCue final : public Modality {
 public:
  AskingCue(Body& body, const Eigen::Vector3d& measured, double sigma) : Modality(body), cue_(body, measured, sigma) {}
  std::string name() const override { return "asking position"; }
  const std::string& camera() const override { return cue_.camera(); }
  void start(const Frame& frame, const Renders& renders) override { cue_.start(frame, renders); }
  void correspondences(const Frame& frame, const Renders& renders, int c) override {
    cue_.correspondences(frame, renders, c);
  }
  CueTerms gradient_hessian(int c, int u) override { return cue_.gradient_hessian(c, u); }
  double log_likelihood(int c) const override { return cue_.log_likelihood(c); }
  void finish(const Frame& frame, const Renders& renders) override { cue_.finish(frame, renders); }
  ModalityQuality quality() const override { return cue_.quality(); }
  void append_residuals(std::vector<double>& r, std::vector<double>& w) const override { cue_.append_residuals(r, w); }
  bool weighs_against_others() const override { return true; }
  void others_estimate(const Vec6& step, const Mat66& covariance) override {
    told.push_back(step);
    covariances.push_back(covariance);
  }

  std::vector<Vec6> told;
  std::vector<Mat66> covariances;

 private:
  example::PositionCue cue_;
};

}  // namespace

TEST_CASE("optimizer: a cue that asks is told the step from the updated pose to the other cues' own step, and its covariance") {
  Body body{"object", Mesh{}, some_pose()};
  AskingCue a(body, Eigen::Vector3d(0.05, 0.03, 0.55), 0.002);
  example::PositionCue b(body, Eigen::Vector3d(0.01, -0.02, 0.62), 0.004);
  const CueTerms ta = a.gradient_hessian(0, 0), tb = b.gradient_hessian(0, 0);
  const Optimizer optimizer({1000.0, 30000.0});
  CueTermSum terms;
  optimizer.step(body, {&a, &b}, terms, 0, 0);
  REQUIRE(a.told.size() == 1);
  // Both steps are translations of the body frame: the sum's (1/σa² + 1/σb² + λ_t)⁻¹ Σ g_t,
  // and b's alone (1/σb² + λ_t)⁻¹ g_b,t.
  const Eigen::Vector3d both = (ta.gradient + tb.gradient).tail<3>() / (1 / 4e-6 + 1 / 16e-6 + 30000.0);
  const Eigen::Vector3d b_alone = tb.gradient.tail<3>() / (1 / 16e-6 + 30000.0);
  INFO("told " << a.told.front().transpose());
  CHECK(a.told.front().head<3>().norm() < 1e-12);
  CHECK((a.told.front().tail<3>() - (b_alone - both)).norm() < 1e-9);
  // It points away from a's measurement, towards b's: the cues disagree by several mm.
  CHECK(a.told.front().tail<3>().norm() > 1e-3);
  // b constrains the position alone: the rotation is only as sure as the regularisation.
  Mat66 covariance = Mat66::Zero();
  covariance.diagonal() << Eigen::Vector3d::Constant(1 / 1000.0), Eigen::Vector3d::Constant(1 / (1 / 16e-6 + 30000.0));
  INFO("covariance\n" << a.covariances.front());
  CHECK((a.covariances.front() - covariance).norm() < 1e-12);
  // Alone on its body, a cue is told to step back to where it was: without it, nothing
  // would have moved the body.
  AskingCue alone(body, Eigen::Vector3d(0.05, 0.03, 0.55), 0.002);
  optimizer.step(body, {&alone}, terms, 0, 0);
  REQUIRE(alone.told.size() == 1);
  const Eigen::Vector3d own_step = terms.total().gradient.tail<3>() / (1 / 4e-6 + 30000.0);
  CHECK((alone.told.front().tail<3>() + own_step).norm() < 1e-9);
}

TEST_CASE("render step: each correspondence iteration renders every body once for the cues that ask") {
  const Intrinsics k{300.0, 300.0, 99.5, 99.5, 200, 200};
  Tracker tracker(TrackerParams{}, std::make_shared<icgp::SceneRenderer>());
  // A 10 cm box 0.5 m straight ahead (front face at 0.45 m), and a 4 cm box at 0.3 m in
  // front of its centre (front face at 0.28 m).
  Body& far = tracker.add_body({"far", test::make_box(0.1f, 0.1f, 0.1f),
                                Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.0, 0.5))});
  auto probe = std::make_unique<OriginProbe>(far, k);
  OriginProbe& far_probe = *probe;
  tracker.add_modality(std::move(probe));
  tracker.start(Frame{});
  tracker.track(Frame{});
  CHECK(far_probe.n_requests == tracker.params().n_corr_iterations);
  CHECK(far_probe.n_renders_read == tracker.params().n_corr_iterations);
  CHECK(far_probe.depth_at_origin == Approx(0.45f).margin(1e-5));
  CHECK(far_probe.id_at_origin == far_probe.own_id);

  Body& near = tracker.add_body({"near", test::make_box(0.04f, 0.04f, 0.04f),
                                 Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.0, 0.3))});
  tracker.track(Frame{});
  // The render shows every body: the near box hides the far one's centre.
  CHECK(far_probe.depth_at_origin == Approx(0.28f).margin(1e-5));
  CHECK(far_probe.id_at_origin != far_probe.own_id);
  CHECK(far_probe.id_at_origin == tracker.renderer().id(near.name));
}

TEST_CASE("render step: a render nobody asked for is a clear error") {
  Renders renders;
  RenderRequest request;
  request.camera = "Camera1";
  CHECK_THROWS_WITH(renders.at(request), Catch::Contains("no render of camera 'Camera1'"));
  CHECK_THROWS_WITH(renders.id("box"), Catch::Contains("'box' was not rendered"));
}

namespace {

/// The example cue, slowed down by `ms_per_call` in each gradient_hessian: a cue whose cost
/// the profile must find.
class SlowPositionCue final : public Modality {
 public:
  SlowPositionCue(Body& body, double ms_per_call)
      : Modality(body), cue_(body, Eigen::Vector3d(0.05, 0.03, 0.55), 0.001), ms_per_call_(ms_per_call) {}
  std::string name() const override { return "slow"; }
  const std::string& camera() const override { return cue_.camera(); }
  void start(const Frame& f, const Renders& r) override { cue_.start(f, r); }
  void correspondences(const Frame& f, const Renders& r, int c) override { cue_.correspondences(f, r, c); }
  CueTerms gradient_hessian(int c, int u) override {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double, std::milli>(ms_per_call_);
    while (std::chrono::steady_clock::now() < until) {
    }
    return cue_.gradient_hessian(c, u);
  }
  double log_likelihood(int c) const override { return cue_.log_likelihood(c); }
  void finish(const Frame& f, const Renders& r) override { cue_.finish(f, r); }
  ModalityQuality quality() const override { return cue_.quality(); }
  void append_residuals(std::vector<double>& residuals, std::vector<double>& weights) const override {
    cue_.append_residuals(residuals, weights);
  }

 private:
  example::PositionCue cue_;
  double ms_per_call_;
};

}  // namespace

TEST_CASE("cost timing: each cue's time is found where it is spent, and nothing is timed by default") {
  Tracker tracker;
  Body& body = tracker.add_body({"object", Mesh{}, some_pose()});
  tracker.add_modality(std::make_unique<example::PositionCue>(body, Eigen::Vector3d(0.05, 0.03, 0.55), 0.001));
  tracker.add_modality(std::make_unique<SlowPositionCue>(body, 0.5));
  tracker.start(Frame{});
  tracker.track(Frame{});
  CHECK(tracker.last_costs().cues.empty());

  tracker.set_cost_timing(true);
  tracker.track(Frame{});
  const FrameCosts& costs = tracker.last_costs();
  REQUIRE(costs.cues.size() == 2);
  CHECK(costs.cues[0].cue == "position");
  CHECK(costs.cues[1].cue == "slow");
  CHECK(costs.cues[1].body == "object");
  // 5 correspondence iterations × 2 updates × 0.5 ms in the slow cue's gradient_hessian.
  CHECK(costs.cues[1].ms >= 5.0);
  CHECK(costs.cues[0].ms < 0.5);
  CHECK(costs.render_ms >= 0.0);

  tracker.set_cost_timing(false);
  tracker.track(Frame{});
  CHECK(tracker.last_costs().cues.empty());
}
