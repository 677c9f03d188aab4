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

  /// λ_r and λ_t on the diagonal, in the order of θ = [θ_r; θ_t].
  Vec6 diagonal() const;
};

/// Throws std::invalid_argument for a negative or NaN λ.
void validate(const OptimizerParams& params);

/// A body's data terms at its current pose, asked of each of its cues: each cue's part and
/// their sum, kept for diagnostics until the next collect().
class CueTermSum {
 public:
  /// Asks each cue for its gradient and Hessian in update iteration `update_iter` of
  /// correspondence iteration `corr_iter`.
  void collect(const std::vector<Modality*>& cues, int corr_iter, int update_iter);

  /// Each cue's part, in the order of the cues given to collect().
  const std::vector<CueTerms>& per_cue() const { return per_cue_; }
  /// Their sum (without the regularisation): −H⁻¹ of its Hessian is the pose covariance in
  /// θ = [θ_r; θ_t].
  const CueTerms& total() const { return total_; }

  /// With `on`, collect() adds each cue's time to cue_ms() (a profile: off by default, so
  /// that tracking reads no clock).
  void time_cues(bool on) { timed_ = on; }
  /// Milliseconds each cue spent in gradient_hessian since reset_cue_ms(), in cue order.
  const std::vector<double>& cue_ms() const { return cue_ms_; }
  void reset_cue_ms() { cue_ms_.assign(cue_ms_.size(), 0.0); }

 private:
  std::vector<CueTerms> per_cue_;
  CueTerms total_;
  bool timed_ = false;
  std::vector<double> cue_ms_;
};

/// The Newton–Tikhonov step of one body (ALGORITHMS.md §2, eq. θ = (−H + diag(λ))⁻¹ g):
/// sums the terms of the body's cues at the current pose and moves the body by the
/// solution θ (T ← T exp(θ)).
class Optimizer {
 public:
  /// Throws std::invalid_argument for a negative or NaN λ.
  explicit Optimizer(const OptimizerParams& params = {});

  /// One update, the cues' terms collected into `terms`. A singular system (no data and no
  /// regularisation) leaves the pose as it is.
  void step(Body& body, const std::vector<Modality*>& cues, CueTermSum& terms, int corr_iter, int update_iter) const;

 private:
  Vec6 regularisation_;
};

}  // namespace icgp
