// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/optimizer/optimizer.h"

#include <Eigen/Cholesky>
#include <stdexcept>

namespace icgp {

void validate(const OptimizerParams& params) {
  if (!(params.tikhonov_rotation >= 0.0) || !(params.tikhonov_translation >= 0.0))
    throw std::invalid_argument("tracker Tikhonov parameters must be non-negative");
}

Optimizer::Optimizer(const OptimizerParams& params) {
  validate(params);
  regularisation_ << Eigen::Vector3d::Constant(params.tikhonov_rotation),
      Eigen::Vector3d::Constant(params.tikhonov_translation);
}

void Optimizer::step(Body& body, const std::vector<Modality*>& cues, int corr_iter, int update_iter) {
  collect(cues, corr_iter, update_iter);
  Mat66 A = -total_.hessian;
  A.diagonal() += regularisation_;
  const Vec6 theta = A.ldlt().solve(total_.gradient);
  // A singular system (no data and no regularisation) must not corrupt the pose.
  if (theta.allFinite()) body.reference_T_body = body.reference_T_body.updated_in_body_frame(theta);
}

void Optimizer::collect(const std::vector<Modality*>& cues, int corr_iter, int update_iter) {
  cue_terms_.clear();
  total_ = CueTerms{};
  for (Modality* cue : cues) {
    cue_terms_.push_back(cue->gradient_hessian(corr_iter, update_iter));
    total_.gradient += cue_terms_.back().gradient;
    total_.hessian += cue_terms_.back().hessian;
    total_.n_correspondences += cue_terms_.back().n_correspondences;
  }
}

}  // namespace icgp
