// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <vector>

namespace icgp {

/// How a cue estimates its own noise from its residuals (docs/accuracy.md, "Weighing the
/// cues by their noise"). Standard deviations are in the cue's own units: pixels for the
/// region and texture modalities, metres at 1 m of depth for the depth modality.
struct NoiseParams {
  /// false: the fixed `standard_deviations` schedule alone, as the ICG papers do.
  bool estimate = true;
  /// Tukey weights on the residuals, in units of their robust scale (the estimate clamped
  /// like the standard deviation, whether or not `estimate` lets it weigh the cue): a few
  /// wrong correspondences then cannot pull the pose, however far off they are.
  bool robust = true;
  /// The smallest standard deviation ever used: what the cue's model itself cannot resolve
  /// (the viewpoint model's sampling, the pixel grid), however well the data fits.
  double floor = 0.0;
  /// Below this many residuals an estimate is not trusted: the schedule's value is used.
  int min_residuals = 20;
  /// Tukey's constant c of the robust weights: a residual beyond c times the scale gets
  /// weight 0. With σ estimated, trust grows as the residuals shrink, and a few wrong
  /// correspondences would otherwise grow with it. 4.685 gives 95 % of least squares'
  /// efficiency on Gaussian residuals.
  double tukey_constant = 4.685;
};

/// A cue's noise level in one correspondence iteration, estimated from its residuals at the
/// current pose as a robust scale about zero, 1.4826·median|u| (the normal distribution's
/// standard deviation for the median absolute value; outliers up to half the residuals do
/// not move it, and a systematic offset counts as noise, as it should when cues disagree).
///
/// The standard deviation used is that estimate, clamped to [floor, scheduled]: the
/// reference schedule is the prior and upper bound, so early iterations far from the
/// optimum, whose residuals are mostly pose error, keep the schedule's robustness, and a
/// cue is trusted more than the schedule says only when its residuals show it is precise.
class ResidualNoise {
 public:
  explicit ResidualNoise(NoiseParams params = {}) : params_(params) {}

  /// Estimates the scale of the residuals `collect` hands to the function it is given, each
  /// already divided by its own nominal relative standard deviation. With neither
  /// estimation nor robust weights `collect` is not called, so a cue that keeps its
  /// schedule computes no residuals. Too few residuals leave no estimate.
  template <typename Collect>
  void estimate(Collect&& collect) {
    residuals_.clear();
    if (params_.estimate || params_.robust) collect([this](float u) { residuals_.push_back(u); });
    estimate_from_residuals();
  }
  /// For an estimate made at a pose other than the cue's own fit: takes out
  /// `known_variance`, the spread that pose's own uncertainty adds to the residuals, and
  /// keeps the rest only where it exceeds `own_fit`, the estimate at the fit, by more than
  /// twice that estimate's standard error (1.166·σ/√n for n Gaussian residuals: the median
  /// absolute value is 37 % as efficient as the standard deviation). A disagreement within
  /// sampling error is no evidence that the fit hides a bias; `own_fit` is kept then.
  /// Without an own fit (negative) the rest is kept as it is.
  void discount(double known_variance, double own_fit);
  /// Forgets the estimate: sigma() gives the schedule's values again.
  void reset() { estimate_ = -1.0; }

  /// The standard deviation to use where the schedule gives `scheduled`: the schedule's
  /// without estimation.
  double sigma(double scheduled) const;
  /// The residuals' robust scale where the schedule gives `scheduled`: the estimate clamped
  /// to [floor, scheduled], or `scheduled` without an estimate.
  double scale(double scheduled) const;
  /// Tukey's weight (1 − (u/(c·scale))²)² of a normalised residual `u`; 1 without robust
  /// weights (the reference behaviour).
  float weight(float u, double scale) const {
    if (!params_.robust) return 1.f;
    return tukey(u / static_cast<float>(params_.tukey_constant * scale));
  }
  /// weight() of each of `u` in `out`, in a loop the compiler vectorises.
  template <int N>
  void weights(const float (&u)[N], double scale, float (&out)[N]) const {
    if (!params_.robust) {
      for (float& w : out) w = 1.f;
      return;
    }
    const float cutoff = static_cast<float>(params_.tukey_constant * scale);
    for (int i = 0; i < N; ++i) out[i] = tukey(u[i] / cutoff);
  }
  /// The loss whose derivative weight() gives, of a residual in units of the scale `x`:
  /// Tukey's ρ(x) = c²/6·(1 − (1 − (x/c)²)³), c²/6 beyond c; x²/2 without robust weights.
  double loss(double x) const {
    if (!params_.robust) return 0.5 * x * x;
    const double c2 = params_.tukey_constant * params_.tukey_constant;
    const double t = 1.0 - x * x / c2;
    return t > 0.0 ? c2 / 6.0 * (1.0 - t * t * t) : c2 / 6.0;
  }
  /// The last estimate, or a negative number when there is none.
  double estimated() const { return estimate_; }
  const NoiseParams& params() const { return params_; }

 private:
  /// Tukey's weight of x, a residual in units of the cut-off c·scale.
  static float tukey(float x) {
    const float t = 1.f - x * x;
    return t > 0.f ? t * t : 0.f;
  }
  void estimate_from_residuals();

  NoiseParams params_;
  double estimate_ = -1.0;
  std::vector<float> residuals_;  ///< scratch of estimate(), kept to reuse its memory
};

}  // namespace icgp
