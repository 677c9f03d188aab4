// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <memory>
#include <vector>

#include "icgp/base/body.h"
#include "icgp/modality/modality.h"
#include "icgp/optimizer/optimizer.h"
#include "icgp/render/scene_renderer.h"

namespace icgp {

/// Newton–Tikhonov fusion and the iteration schedule (ALGORITHMS.md §2).
struct TrackerParams {
  int n_corr_iterations = 5;
  int n_update_iterations = 2;
  double tikhonov_rotation = 1000.0;      ///< λ_r
  double tikhonov_translation = 30000.0;  ///< λ_t
  /// A body whose combined quality (the mean of the scores of its modalities that had
  /// something to measure, ModalityQuality::abstained) is below this is reported lost.
  double quality_threshold = 0.5;
};

/// Outcome of one frame for one body.
struct BodyResult {
  std::string body;
  Pose reference_T_body;
  double quality = 0.0;
  bool tracked = false;
  std::vector<ModalityQuality> modalities;  ///< in the order they were added
};

/// Tracks any number of bodies with any number of modalities on frames from any number of
/// cameras. Each body's modalities are fused into one 6-DoF Newton step per update (its
/// Optimizer). Before each stage of a frame (start, every correspondence iteration,
/// finish) the tracker renders what the modalities ask for, once, with one SceneRenderer
/// that shows all of its bodies.
class Tracker {
 public:
  /// `renderer`: shared with whoever else draws these bodies (vpMbIcgTracker's display);
  /// null: the tracker's own.
  explicit Tracker(TrackerParams params = {}, std::shared_ptr<SceneRenderer> renderer = nullptr);
  ~Tracker();
  Tracker(Tracker&&) noexcept;
  Tracker& operator=(Tracker&&) noexcept;

  /// Adds a body; the returned reference stays valid for the tracker's lifetime.
  Body& add_body(Body body);
  /// Adds a modality bound to one of this tracker's bodies.
  void add_modality(std::unique_ptr<Modality> modality);

  const TrackerParams& params() const { return params_; }
  std::vector<Body*> bodies();
  Body& body(const std::string& name);

  /// Initialises every modality at its body's current pose (call after setting the
  /// initial poses, and again to restart after a loss).
  void start(const Frame& frame);
  /// Refines every body's pose on this frame and reports each body's quality.
  std::vector<BodyResult> track(const Frame& frame);

  /// H of the last update's data terms (without the Tikhonov regularisation), per body:
  /// the inverse of −H is the pose covariance in the body-frame variation θ = [θ_r; θ_t].
  const Mat66& last_hessian(const std::string& body) const;
  /// Each modality's gradient, Hessian and correspondence count in the last update of
  /// `body`, in the order the modalities were added (empty before the first frame).
  const std::vector<CueTerms>& last_cue_terms(const std::string& body) const;
  /// The residuals and weights of every modality of `body` at its current pose, in the
  /// order the modalities were added (Modality::append_residuals).
  void residuals(const std::string& body, std::vector<double>& residuals, std::vector<double>& weights) const;
  /// The renderer of the render step, which shows every body of this tracker.
  SceneRenderer& renderer() { return *renderer_; }
  /// The modalities of `body`, in the order they were added (for per-cue diagnostics).
  std::vector<const Modality*> modalities(const std::string& body) const;

 private:
  struct BodyState;
  const BodyState& state(const std::string& body) const;
  /// Renders what the modalities ask for in `stage` into renders_.
  void render(const Frame& frame, Stage stage);

  TrackerParams params_;
  std::vector<std::unique_ptr<BodyState>> states_;
  std::shared_ptr<SceneRenderer> renderer_;
  Renders renders_;
};

}  // namespace icgp
