// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <vector>

#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"
#include "icgp/modality/modality.h"
#include "icgp/modality/residual_noise.h"

namespace icgp {

/// The weighted reprojection error of 2D–3D matches (ALGORITHMS.md §8), shared by the cues
/// that match body points to image points (texture keyframes, flow-tracked corners). A match
/// is any type with `body_point` (Eigen::Vector3f, body frame), `image_point`
/// (Eigen::Vector2f, pixels) and `weight` (float, its robust weight, held fixed here).
///
/// The gradient and Hessian of −Σ w_i ‖π(T X_i) − x_i‖² / (2σ²) at θ = 0; points behind the
/// camera and zero weights do not count.
template <typename Match>
CueTerms reprojection_terms(const std::vector<Match>& matches, const Posef& camera_T_body, const Intrinsics& k,
                            float sigma) {
  const float inverse_variance = 1.f / (sigma * sigma);
  Eigen::Matrix<float, 6, 1> g_sum = Eigen::Matrix<float, 6, 1>::Zero();
  Eigen::Matrix<float, 6, 6> H_sum = Eigen::Matrix<float, 6, 6>::Zero();
  for (const Match& m : matches) {
    const Eigen::Vector3f X = camera_T_body * m.body_point;
    if (X.z() <= 0.f || m.weight <= 0.f) continue;
    const Eigen::Vector2f residual = k.project<float>(X) - m.image_point;
    const Eigen::Matrix<float, 2, 6> J =
        k.projection_jacobian<float>(X) * point_jacobian_body_variation<float>(camera_T_body.rotation(), m.body_point);
    const float w = m.weight * inverse_variance;
    g_sum.noalias() -= w * J.transpose() * residual;
    H_sum.noalias() -= w * J.transpose() * J;
  }
  return {g_sum.cast<double>(), H_sum.cast<double>(), static_cast<int>(matches.size())};
}

/// −Σ w_i ‖π(T X_i) − x_i‖² / (2σ²), what reprojection_terms differentiates.
template <typename Match>
double reprojection_log_likelihood(const std::vector<Match>& matches, const Pose& camera_T_body, const Intrinsics& k,
                                   double sigma) {
  double sum = 0.0;
  for (const Match& m : matches) {
    const Eigen::Vector3d X = camera_T_body * m.body_point.template cast<double>();
    if (X.z() <= 0.0) continue;
    sum -= 0.5 * m.weight * (k.project<double>(X) - m.image_point.template cast<double>()).squaredNorm() /
           (sigma * sigma);
  }
  return sum;
}

/// Estimates `noise` from the u and v reprojection errors of the matches in front of the
/// camera (ResidualNoise::estimate).
template <typename Match>
void estimate_reprojection_noise(ResidualNoise& noise, const std::vector<Match>& matches, const Posef& camera_T_body,
                                 const Intrinsics& k) {
  noise.estimate([&](auto add) {
    for (const Match& m : matches) {
      const Eigen::Vector3f X = camera_T_body * m.body_point;
      if (X.z() <= 0.f) continue;
      const Eigen::Vector2f e = k.project<float>(X) - m.image_point;
      add(e.x());
      add(e.y());
    }
  });
}

/// The variance, pixels² per coordinate and averaged with the matches' weights, that a pose
/// error of covariance `covariance` (body frame, [θ_r; θ_t]) adds to the reprojection
/// errors at `camera_T_body`: the weighted mean of tr(J Σ Jᵀ) / 2. 0 without weighted matches.
template <typename Match>
double reprojection_spread(const std::vector<Match>& matches, const Posef& camera_T_body, const Intrinsics& k,
                           const Eigen::Matrix<float, 6, 6>& covariance) {
  double sum = 0.0, weights = 0.0;
  for (const Match& m : matches) {
    const Eigen::Vector3f X = camera_T_body * m.body_point;
    if (X.z() <= 0.f || m.weight <= 0.f) continue;
    const Eigen::Matrix<float, 2, 6> J =
        k.projection_jacobian<float>(X) * point_jacobian_body_variation<float>(camera_T_body.rotation(), m.body_point);
    sum += m.weight * (J * covariance * J.transpose()).trace();
    weights += m.weight;
  }
  return weights > 0.0 ? sum / (2.0 * weights) : 0.0;
}

/// Appends the u and v reprojection errors of the matches in front of the camera, each with
/// its match's weight (Modality::append_residuals).
template <typename Match>
void append_reprojection_residuals(const std::vector<Match>& matches, const Pose& camera_T_body,
                                   const Intrinsics& k, std::vector<double>& residuals, std::vector<double>& weights) {
  for (const Match& m : matches) {
    const Eigen::Vector3d X = camera_T_body * m.body_point.template cast<double>();
    if (X.z() <= 0.0) continue;
    const Eigen::Vector2d e = k.project<double>(X) - m.image_point.template cast<double>();
    residuals.insert(residuals.end(), {e.x(), e.y()});
    weights.insert(weights.end(), {m.weight, m.weight});
  }
}

}  // namespace icgp
