// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "icgp/base/pose.h"

namespace icgp {

using Twist = Eigen::Matrix<double, 6, 1>;  ///< [ω; v], the order of the pose variation θ
using JointJacobian = Eigen::Matrix<double, 6, Eigen::Dynamic>;

/// The adjoint of a_T_b for variations θ = [θ_r; θ_t] (ALGORITHMS.md §1): a variation of
/// frame b, b ← b · exp(θ), is the variation adjoint(a_T_b) · θ of frame a, where a is held
/// to b (a · a_T_b ← (a · exp(θ_a)) · a_T_b).
Eigen::Matrix<double, 6, 6> adjoint(const Pose& a_T_b);

/// One free direction of a joint, in the joint frame: a rotation about `axis` (value in
/// radians) or a translation along it (metres).
struct JointDirection {
  enum class Kind { kRotation, kTranslation };
  Kind kind = Kind::kRotation;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< unit vector
  double min = -std::numeric_limits<double>::infinity();  ///< lowest value
  double max = std::numeric_limits<double>::infinity();   ///< highest value
  /// A soft constraint (a spring towards value 0): −½·stiffness·value² is added to the
  /// log-likelihood, in its units per rad² (m²). 0: free within the limits.
  double stiffness = 0.0;

  /// The direction's unit twist [ω; v] in the joint frame.
  Twist twist() const;
};

/// How a link of a kinematic tree hangs from its parent body:
///   parent_T_link(q) = parent_T_joint · exp(q₁ ξ₁) ⋯ exp(qₙ ξₙ) · joint_T_link
/// where ξₖ is the twist of free direction k and qₖ its value. At q = 0 the link sits at
/// parent_T_joint · joint_T_link. No direction: the link is fixed to its parent.
struct Joint {
  std::string parent;
  Pose parent_T_joint;
  Pose joint_T_link;
  std::vector<JointDirection> directions;

  /// One rotation about `axis` (joint frame) within [min, max] radians.
  static Joint revolute(std::string parent, const Pose& parent_T_joint, const Eigen::Vector3d& axis, double min,
                        double max);
  /// One translation along `axis` (joint frame) within [min, max] metres.
  static Joint prismatic(std::string parent, const Pose& parent_T_joint, const Eigen::Vector3d& axis, double min,
                         double max);

  int size() const { return static_cast<int>(directions.size()); }
  /// The link's pose in its parent at joint values `q` (size() values).
  Pose parent_T_link(const std::vector<double>& q) const;
  /// The variation of the link's frame per unit of each joint value at `q`: column k is the
  /// body-frame θ of the link when qₖ grows by one (6 × size()).
  JointJacobian link_jacobian(const std::vector<double>& q) const;
  /// `q` with every value moved into its direction's [min, max].
  std::vector<double> clamped(std::vector<double> q) const;
};

/// Throws std::invalid_argument, naming `link` and the field, for a joint without a parent
/// name, a direction whose axis is not a finite non-zero vector, limits that are not
/// ordered (min > max, or NaN), or a negative or non-finite stiffness. Axes are normalised.
void validate(Joint& joint, const std::string& link);

}  // namespace icgp
