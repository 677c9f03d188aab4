// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/optimizer/optimizer.h"

#include <Eigen/Cholesky>
#include <chrono>
#include <stdexcept>

namespace icgp {

void validate(const OptimizerParams& params) {
  if (!(params.tikhonov_rotation >= 0.0) || !(params.tikhonov_translation >= 0.0))
    throw std::invalid_argument("tracker Tikhonov parameters must be non-negative");
}

Vec6 OptimizerParams::diagonal() const {
  Vec6 lambda;
  lambda << Eigen::Vector3d::Constant(tikhonov_rotation), Eigen::Vector3d::Constant(tikhonov_translation);
  return lambda;
}

void CueTermSum::collect(const std::vector<Modality*>& cues, int corr_iter, int update_iter) {
  per_cue_.clear();
  total_ = CueTerms{};
  if (timed_) cue_ms_.resize(cues.size(), 0.0);
  for (std::size_t i = 0; i < cues.size(); ++i) {
    const auto begin = timed_ ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point();
    per_cue_.push_back(cues[i]->gradient_hessian(corr_iter, update_iter));
    if (timed_) cue_ms_[i] += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
    total_.gradient += per_cue_.back().gradient;
    total_.hessian += per_cue_.back().hessian;
    total_.n_correspondences += per_cue_.back().n_correspondences;
  }
}

Optimizer::Optimizer(const OptimizerParams& params) : regularisation_((validate(params), params.diagonal())) {}

void Optimizer::step(Body& body, const std::vector<Modality*>& cues, CueTermSum& terms, int corr_iter,
                     int update_iter) const {
  terms.collect(cues, corr_iter, update_iter);
  Mat66 A = -terms.total().hessian;
  A.diagonal() += regularisation_;
  const Vec6 theta = A.ldlt().solve(terms.total().gradient);
  // A singular system (no data and no regularisation) must not corrupt the pose.
  if (!theta.allFinite()) return;
  body.reference_T_body = body.reference_T_body.updated_in_body_frame(theta);
  // A cue that cannot see its own bias in its residuals measures its noise where the other
  // cues alone would go, and how sure they are there: the same system without its terms.
  for (std::size_t i = 0; i < cues.size(); ++i) {
    if (!cues[i]->weighs_against_others()) continue;
    const CueTerms& own = terms.per_cue()[i];
    const Eigen::LDLT<Mat66> others(A + own.hessian);
    const Vec6 others_theta = others.solve(terms.total().gradient - own.gradient);
    const Mat66 covariance = others.solve(Mat66::Identity());
    if (others_theta.allFinite() && covariance.allFinite()) cues[i]->others_estimate(others_theta - theta, covariance);
  }
}

}  // namespace icgp
