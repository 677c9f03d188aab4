// SPDX-License-Identifier: GPL-2.0-or-later
// Kinematic trees against analytic truth: the joint's link Jacobian against finite
// differences, the tree's Newton step recovering a known root pose and joint values from
// point measurements on every link, joint limits, and a joint's stiffness.
#include <catch2/catch.hpp>
#include <cmath>

#include "icgp/geometry/joint.h"
#include "icgp/tracker/tracker.h"
#include "test_meshes.h"

using namespace icgp;

namespace {

/// A measured position of one point of a body (body frame) in the reference camera:
/// ℓ = −‖T X − p‖² / (2σ²), whose body-frame gradient and Hessian are exact.
class PointCue final : public Modality {
 public:
  PointCue(Body& body, const Eigen::Vector3d& body_point, const Eigen::Vector3d& measured)
      : Modality(body), X_(body_point), measured_(measured) {}
  std::string name() const override { return "point"; }
  const std::string& camera() const override { return no_camera_; }
  void start(const Frame&, const Renders&) override {}
  void correspondences(const Frame&, const Renders&, int) override {}
  CueTerms gradient_hessian(int, int) override {
    const Pose& T = body().reference_T_body;
    Eigen::Matrix<double, 3, 6> J;
    J << -T.rotation() * skew(X_), T.rotation();
    const double w = 1.0 / (kSigma * kSigma);
    CueTerms terms;
    terms.gradient = -w * J.transpose() * (T * X_ - measured_);
    terms.hessian = -w * J.transpose() * J;
    terms.n_correspondences = 1;
    return terms;
  }
  double log_likelihood(int) const override {
    return -(body().reference_T_body * X_ - measured_).squaredNorm() / (2.0 * kSigma * kSigma);
  }
  void finish(const Frame&, const Renders&) override {}
  ModalityQuality quality() const override { return {1.0, 1.0, 1, false, kSigma}; }
  void append_residuals(std::vector<double>&, std::vector<double>&) const override {}

 private:
  static constexpr double kSigma = 0.001;
  Eigen::Vector3d X_, measured_;
  std::string no_camera_;
};

Pose pose(double rx, double ry, double rz, double tx, double ty, double tz) {
  return Pose::from_rotation_vector(Eigen::Vector3d(rx, ry, rz), Eigen::Vector3d(tx, ty, tz));
}

/// Points that fix a body's pose: its origin and three points off it.
const std::vector<Eigen::Vector3d> kMarkers = {
    {0.0, 0.0, 0.0}, {0.05, 0.0, 0.0}, {0.0, 0.05, 0.0}, {0.0, 0.0, 0.05}};

void measure(Tracker& tracker, Body& body, const Pose& truth) {
  for (const Eigen::Vector3d& X : kMarkers) tracker.add_modality(std::make_unique<PointCue>(body, X, truth * X));
}

/// A 3-DoF joint with an offset both sides: the general case of the Jacobian.
Joint general_joint() {
  Joint joint;
  joint.parent = "base";
  joint.parent_T_joint = pose(0.1, -0.2, 0.3, 0.05, 0.02, -0.01);
  joint.joint_T_link = pose(-0.2, 0.1, 0.05, 0.0, 0.03, 0.04);
  joint.directions = {{JointDirection::Kind::kRotation, Eigen::Vector3d(0.0, 0.6, 0.8)},
                      {JointDirection::Kind::kTranslation, Eigen::Vector3d(1.0, 0.0, 0.0)},
                      {JointDirection::Kind::kRotation, Eigen::Vector3d(1.0, 0.0, 0.0)}};
  return joint;
}

}  // namespace

TEST_CASE("a joint's link Jacobian is the derivative of the link's pose in its own frame") {
  const Joint joint = general_joint();
  const std::vector<double> q = {0.4, -0.02, 1.1};
  const JointJacobian J = joint.link_jacobian(q);
  const Pose link = joint.parent_T_link(q);
  for (int k = 0; k < joint.size(); ++k) {
    // Central difference of link⁻¹ · link(q + h e_k), read as a body-frame variation.
    const double h = 1e-6;
    std::vector<double> plus = q, minus = q;
    plus[k] += h;
    minus[k] -= h;
    const Eigen::Matrix4d d =
        (link.inverse() * joint.parent_T_link(plus)).matrix() - (link.inverse() * joint.parent_T_link(minus)).matrix();
    Twist numeric;
    numeric << d(2, 1), d(0, 2), d(1, 0), d(0, 3), d(1, 3), d(2, 3);
    numeric /= 2.0 * h;
    CHECK((J.col(k) - numeric).norm() < 1e-8);
  }
}

TEST_CASE("adjoint carries a variation of one frame to a frame held to it") {
  const Pose a_T_b = pose(0.3, -0.1, 0.7, 0.1, -0.2, 0.05);
  Twist theta_b;
  theta_b << 0.01, -0.02, 0.015, 0.003, 0.001, -0.002;
  // a ← a · exp(θ_a) must move b exactly as b ← b · exp(θ_b), to first order.
  const Twist theta_a = adjoint(a_T_b) * theta_b;
  const Pose via_b = a_T_b.updated_in_body_frame(theta_b * 1e-4);
  const Pose via_a = Pose().updated_in_body_frame(theta_a * 1e-4) * a_T_b;
  CHECK((via_a.matrix() - via_b.matrix()).norm() < 1e-9);
}

TEST_CASE("one Newton step per update recovers a tree's root pose and joint values from every link's cues") {
  const Pose base_truth = pose(0.2, -0.4, 0.1, 0.05, -0.02, 0.6);
  const Joint hinge = Joint::revolute("base", pose(0.0, 0.0, 0.0, 0.0, 0.05, 0.04), Eigen::Vector3d::UnitX(), -3.0, 3.0);
  Joint slide = Joint::prismatic("lid", pose(0.0, 0.0, 0.0, 0.0, 0.02, 0.0), Eigen::Vector3d::UnitZ(), -0.1, 0.1);
  const std::vector<double> hinge_truth = {1.2}, slide_truth = {0.03};
  const Pose lid_truth = base_truth * hinge.parent_T_link(hinge_truth);
  const Pose knob_truth = lid_truth * slide.parent_T_link(slide_truth);

  Tracker tracker(TrackerParams{5, 2, 1000.0, 30000.0, 0.5});
  Body& base = tracker.add_body({"base", test::make_box(0.1f, 0.1f, 0.1f), pose(0.25, -0.35, 0.05, 0.06, -0.01, 0.62)});
  Body& lid = tracker.add_link({"lid", test::make_box(0.1f, 0.01f, 0.1f), Pose()}, hinge);
  Body& knob = tracker.add_link({"knob", test::make_box(0.01f, 0.01f, 0.01f), Pose()}, slide);
  measure(tracker, base, base_truth);
  measure(tracker, lid, lid_truth);
  measure(tracker, knob, knob_truth);
  tracker.set_joint_values("lid", {0.9});

  tracker.start(Frame{});
  std::vector<BodyResult> results;
  for (int frame = 0; frame < 4; ++frame) results = tracker.track(Frame{});

  CHECK((base.reference_T_body.matrix() - base_truth.matrix()).norm() < 1e-9);
  CHECK((lid.reference_T_body.matrix() - lid_truth.matrix()).norm() < 1e-9);
  CHECK((knob.reference_T_body.matrix() - knob_truth.matrix()).norm() < 1e-9);
  REQUIRE(results.size() == 3);
  CHECK(results[1].joint_values.at(0) == Approx(1.2).margin(1e-9));
  CHECK(results[2].joint_values.at(0) == Approx(0.03).margin(1e-9));
  CHECK(results[0].joint_values.empty());
}

TEST_CASE("a tree's joint values stay within their limits") {
  const Pose base_truth = pose(0.0, 0.0, 0.0, 0.0, 0.0, 0.5);
  const Joint free_hinge = Joint::revolute("base", Pose(), Eigen::Vector3d::UnitY(), -3.0, 3.0);
  const Pose lid_truth = base_truth * free_hinge.parent_T_link({1.0});

  Tracker tracker(TrackerParams{5, 2, 1000.0, 30000.0, 0.5});
  Body& base = tracker.add_body({"base", test::make_box(0.1f, 0.1f, 0.1f), base_truth});
  Body& lid = tracker.add_link({"lid", test::make_box(0.1f, 0.01f, 0.1f), Pose()},
                               Joint::revolute("base", Pose(), Eigen::Vector3d::UnitY(), 0.0, 0.5));
  measure(tracker, lid, lid_truth);
  measure(tracker, base, base_truth);
  tracker.start(Frame{});
  for (int frame = 0; frame < 3; ++frame) tracker.track(Frame{});
  CHECK(tracker.joint_values("lid").at(0) == 0.5);
  CHECK((lid.reference_T_body.matrix() - (base.reference_T_body * free_hinge.parent_T_link({0.5})).matrix()).norm() <
        1e-12);
}

TEST_CASE("a joint's stiffness pulls its value towards zero against the regularisation") {
  // No cue on the link: each update solves (λ_r + k) δ = −k q, so q halves when k = λ_r.
  Tracker tracker(TrackerParams{1, 1, 1000.0, 30000.0, 0.5});
  Body& base = tracker.add_body({"base", test::make_box(0.1f, 0.1f, 0.1f), pose(0, 0, 0, 0, 0, 0.5)});
  measure(tracker, base, base.reference_T_body);
  Joint spring = Joint::revolute("base", Pose(), Eigen::Vector3d::UnitZ(), -1.0, 1.0);
  spring.directions[0].stiffness = 1000.0;
  tracker.add_link({"flap", test::make_box(0.1f, 0.01f, 0.1f), Pose()}, spring);
  tracker.set_joint_values("flap", {0.4});
  tracker.start(Frame{});
  tracker.track(Frame{});
  CHECK(tracker.joint_values("flap").at(0) == Approx(0.2).epsilon(1e-12));
}

TEST_CASE("links need a tracked parent and a valid joint; errors name the body and the field") {
  Tracker tracker;
  tracker.add_body({"base", test::make_box(0.1f, 0.1f, 0.1f), Pose()});
  tracker.add_occluder({"hand", test::make_box(0.1f, 0.1f, 0.1f), Pose()});
  const Mesh box = test::make_box(0.1f, 0.1f, 0.1f);
  CHECK_THROWS_WITH(tracker.add_link({"lid", box, Pose()}, Joint::revolute("bsae", Pose(), Eigen::Vector3d::UnitX(), 0, 1)),
                    Catch::Contains("body 'lid'") && Catch::Contains("parent") && Catch::Contains("'bsae'"));
  CHECK_THROWS_WITH(tracker.add_link({"lid", box, Pose()}, Joint::revolute("hand", Pose(), Eigen::Vector3d::UnitX(), 0, 1)),
                    Catch::Contains("no tracked body is named 'hand'"));
  CHECK_THROWS_WITH(tracker.add_link({"lid", box, Pose()}, Joint::revolute("base", Pose(), Eigen::Vector3d::UnitX(), 1, 0)),
                    Catch::Contains("body 'lid'") && Catch::Contains("limits") && Catch::Contains("min <= max"));
  CHECK_THROWS_WITH(tracker.add_link({"lid", box, Pose()}, Joint::revolute("base", Pose(), Eigen::Vector3d::Zero(), 0, 1)),
                    Catch::Contains("body 'lid'") && Catch::Contains("axis"));
  CHECK_THROWS_WITH(tracker.add_body({"base", box, Pose()}), Catch::Contains("already has a body named 'base'"));
  CHECK_THROWS_WITH(tracker.set_joint_values("base", {0.0}), Catch::Contains("'base' has no joint"));
}
