// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/geometry/joint.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace icgp {

Eigen::Matrix<double, 6, 6> adjoint(const Pose& a_T_b) {
  // a · exp(θ_a) · a_T_b = a · a_T_b · exp(θ_b) with exp(θ_a) = a_T_b exp(θ_b) b_T_a:
  // ω_a = R ω_b, v_a = R v_b + t × (R ω_b).
  const Eigen::Matrix3d& R = a_T_b.rotation();
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
  A.topLeftCorner<3, 3>() = R;
  A.bottomRightCorner<3, 3>() = R;
  A.bottomLeftCorner<3, 3>() = skew(a_T_b.translation()) * R;
  return A;
}

Twist JointDirection::twist() const {
  Twist xi = Twist::Zero();
  if (kind == Kind::kRotation)
    xi.head<3>() = axis;
  else
    xi.tail<3>() = axis;
  return xi;
}

namespace {

Pose exp_twist(const Twist& xi) {
  // Pure rotations about an axis through the origin or pure translations: the motion of a
  // single joint direction, so the full SE(3) exponential (with its V matrix) is not needed.
  return Pose(exp_so3<double>(xi.head<3>()), xi.tail<3>());
}

Joint one_direction(std::string parent, const Pose& parent_T_joint, const Eigen::Vector3d& axis, double min,
                    double max, JointDirection::Kind kind) {
  Joint joint;
  joint.parent = std::move(parent);
  joint.parent_T_joint = parent_T_joint;
  joint.directions.push_back({kind, axis, min, max, 0.0});
  return joint;
}

}  // namespace

Joint Joint::revolute(std::string parent, const Pose& parent_T_joint, const Eigen::Vector3d& axis, double min,
                      double max) {
  return one_direction(std::move(parent), parent_T_joint, axis, min, max, JointDirection::Kind::kRotation);
}

Joint Joint::prismatic(std::string parent, const Pose& parent_T_joint, const Eigen::Vector3d& axis, double min,
                       double max) {
  return one_direction(std::move(parent), parent_T_joint, axis, min, max, JointDirection::Kind::kTranslation);
}

Pose Joint::parent_T_link(const std::vector<double>& q) const {
  if (static_cast<int>(q.size()) != size())
    throw std::invalid_argument("joint of " + std::to_string(size()) + " directions given " +
                                std::to_string(q.size()) + " values");
  Pose pose = parent_T_joint;
  for (int k = 0; k < size(); ++k) pose = pose * exp_twist(q[k] * directions[k].twist());
  return pose * joint_T_link;
}

JointJacobian Joint::link_jacobian(const std::vector<double>& q) const {
  // Growing q_k by δ multiplies exp(q_k ξ_k) by exp(δ ξ_k) in place; carried through the
  // motions after it (B = exp(q_{k+1} ξ_{k+1}) ⋯ joint_T_link) it is the link variation
  // adjoint(B⁻¹) ξ_k δ.
  JointJacobian J(6, size());
  Pose after = joint_T_link;
  for (int k = size() - 1; k >= 0; --k) {
    J.col(k) = adjoint(after.inverse()) * directions[k].twist();
    after = exp_twist(q[k] * directions[k].twist()) * after;
  }
  return J;
}

std::vector<double> Joint::clamped(std::vector<double> q) const {
  for (int k = 0; k < size() && k < static_cast<int>(q.size()); ++k)
    q[k] = std::clamp(q[k], directions[k].min, directions[k].max);
  return q;
}

void validate(Joint& joint, const std::string& link) {
  const std::string where = "body '" + link + "': joint";
  if (joint.parent.empty()) throw std::invalid_argument(where + ": parent: expected the name of another body");
  if (!joint.parent_T_joint.matrix().allFinite() || !joint.joint_T_link.matrix().allFinite())
    throw std::invalid_argument(where + ": origin: expected a finite pose");
  for (std::size_t k = 0; k < joint.directions.size(); ++k) {
    JointDirection& d = joint.directions[k];
    const std::string at = where + " direction " + std::to_string(k);
    const double norm = d.axis.norm();
    if (!std::isfinite(norm) || norm < 1e-12) throw std::invalid_argument(at + ": axis: expected a non-zero finite vector");
    d.axis /= norm;
    if (std::isnan(d.min) || std::isnan(d.max) || d.min > d.max)
      throw std::invalid_argument(at + ": limits: expected min <= max, got [" + std::to_string(d.min) + ", " +
                                  std::to_string(d.max) + "]");
    if (!(d.stiffness >= 0.0) || !std::isfinite(d.stiffness))
      throw std::invalid_argument(at + ": stiffness: expected a non-negative number");
  }
}

}  // namespace icgp
