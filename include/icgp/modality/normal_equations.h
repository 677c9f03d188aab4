// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include "icgp/modality/modality.h"

namespace icgp {

/// A cue's gradient and Hessian (CueTerms) summed over its correspondences, in blocks of
/// kLanes: each correspondence gives its Jacobian row J (6 values), its weight w and its
/// weighted residual w·r, and
///   gradient = −Σ w·r J,   Hessian = −Σ w J Jᵀ
/// (the log-likelihood −Σ w r² / 2 with r changing by J·θ).
///
/// Why blocks: dense depth sums over thousands of sampled pixels ten times a frame, and one
/// running float sum per entry is a chain the compiler may not reorder, so it stays scalar.
/// A cue that computes its rows a block at a time, lane by lane, gets every step vectorised;
/// here each lane keeps its own sums of the Hessian's upper triangle (21 of its 36 values),
/// and terms() adds the lanes up.
class NormalEquations {
 public:
  static constexpr int kLanes = 8;

  /// Adds one block: rows[a][l] is value a of lane l's row. A lane of weight 0 adds nothing
  /// (the padding of a last, partial block).
  void add(const float (&rows)[6][kLanes], const float (&weights)[kLanes], const float (&weighted_residuals)[kLanes]) {
    for (int a = 0; a < 6; ++a)
      for (int l = 0; l < kLanes; ++l) gradient_[a][l] += weighted_residuals[l] * rows[a][l];
    int k = 0;
    for (int a = 0; a < 6; ++a)
      for (int b = a; b < 6; ++b, ++k)
        for (int l = 0; l < kLanes; ++l) hessian_[k][l] += weights[l] * rows[a][l] * rows[b][l];
  }

  /// The sums, with `n_correspondences` as CueTerms::n_correspondences.
  CueTerms terms(int n_correspondences) const {
    CueTerms out;
    int k = 0;
    for (int a = 0; a < 6; ++a) {
      out.gradient[a] = -lane_sum(gradient_[a]);
      for (int b = a; b < 6; ++b, ++k) out.hessian(a, b) = out.hessian(b, a) = -lane_sum(hessian_[k]);
    }
    out.n_correspondences = n_correspondences;
    return out;
  }

 private:
  static double lane_sum(const float (&lanes)[kLanes]) {
    double sum = 0.0;
    for (const float value : lanes) sum += value;
    return sum;
  }

  float gradient_[6][kLanes] = {};
  float hessian_[21][kLanes] = {};
};

}  // namespace icgp
