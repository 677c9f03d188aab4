// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/optimizer/covariance.h"

#include <Eigen/Dense>

namespace icgp {

Mat66 camera_twist_covariance(const Mat66& hessian, const Pose& reference_T_body) {
  // Σ_θ = (−H)⁻¹ over θ = [θ_r; θ_t] (T ← T exp(θ)). A body-frame twist ξ_b is the
  // reference-frame twist ξ_c = Ad(T) ξ_b.
  const Mat66 information = -hessian;
  const Mat66 body_covariance = information.completeOrthogonalDecomposition().pseudoInverse();
  Mat66 to_v_omega = Mat66::Zero();  // (v, ω) = P θ
  to_v_omega.block<3, 3>(0, 3).setIdentity();
  to_v_omega.block<3, 3>(3, 0).setIdentity();
  const Eigen::Matrix3d R = reference_T_body.rotation();
  Mat66 adjoint = Mat66::Zero();
  adjoint.block<3, 3>(0, 0) = R;
  adjoint.block<3, 3>(0, 3) = skew(Eigen::Vector3d(reference_T_body.translation())) * R;
  adjoint.block<3, 3>(3, 3) = R;
  const Mat66 A = adjoint * to_v_omega;
  const Mat66 product = A * body_covariance * A.transpose();
  return 0.5 * (product + product.transpose());
}

}  // namespace icgp
