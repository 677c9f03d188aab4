// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <vector>

#include "icgp/base/body.h"
#include "icgp/modality/modality.h"

namespace icgp {

/// The Tikhonov regularisation of the Newton step (ALGORITHMS.md §2): how strongly a step
/// is held back in rotation and translation.
struct OptimizerParams {
  double tikhonov_rotation = 1000.0;      ///< λ_r
  double tikhonov_translation = 30000.0;  ///< λ_t
};

/// Throws std::invalid_argument for a negative or NaN λ.
void validate(const OptimizerParams& params);

/// The Newton–Tikhonov step of one body (ALGORITHMS.md §2, eq. θ = (−H + diag(λ))⁻¹ g):
/// asks each of the body's cues for its gradient and Hessian at the current pose, keeps
/// them per cue, sums them, and moves the body by the solution θ (T ← T exp(θ)).
class Optimizer {
 public:
  /// Throws std::invalid_argument for a negative or NaN λ.
  explicit Optimizer(const OptimizerParams& params = {});

  /// One update of update iteration `update_iter` within correspondence iteration
  /// `corr_iter`. A singular system (no data and no regularisation) leaves the pose as it is.
  void step(Body& body, const std::vector<Modality*>& cues, int corr_iter, int update_iter);
  /// Asks each cue for its terms at the current pose and keeps them (cue_terms(), total())
  /// without moving the body: a link of a kinematic tree, which TreeOptimizer moves.
  void collect(const std::vector<Modality*>& cues, int corr_iter, int update_iter);

  /// Each cue's part of the last step, in the order of the cues given to step().
  const std::vector<CueTerms>& cue_terms() const { return cue_terms_; }
  /// The sum of the last step's cue terms (without the regularisation): −H⁻¹ of its Hessian
  /// is the pose covariance in θ = [θ_r; θ_t].
  const CueTerms& total() const { return total_; }

  /// λ_r and λ_t on the diagonal, in the order of θ.
  const Vec6& regularisation() const { return regularisation_; }

 private:
  Vec6 regularisation_;
  std::vector<CueTerms> cue_terms_;
  CueTerms total_;
};

}  // namespace icgp
