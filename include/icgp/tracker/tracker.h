// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <memory>
#include <vector>

#include "icgp/base/body.h"
#include "icgp/geometry/joint.h"
#include "icgp/modality/modality.h"
#include "icgp/optimizer/optimizer.h"
#include "icgp/optimizer/tree_optimizer.h"
#include "icgp/render/scene_renderer.h"

namespace icgp {

/// Newton–Tikhonov fusion and the iteration schedule (ALGORITHMS.md §2).
struct TrackerParams {
  int n_corr_iterations = 5;
  int n_update_iterations = 2;
  OptimizerParams regularisation;  ///< λ_r, λ_t
  /// A body whose combined quality (the median of the scores of its modalities that had
  /// something to measure, ModalityQuality::abstained) is below this is reported lost. A
  /// body whose cues all just started (ModalityQuality::just_started) has quality 1.
  double quality_threshold = 0.5;
};

/// Outcome of one frame for one body.
struct BodyResult {
  std::string body;
  Pose reference_T_body;
  double quality = 0.0;
  bool tracked = false;
  std::vector<ModalityQuality> modalities;  ///< in the order they were added
  /// A link's joint values (radians, metres) in the order of its joint's directions;
  /// empty for a free body.
  std::vector<double> joint_values;
};

/// Where one frame's tracking time went (Tracker::set_cost_timing): each cue's own work
/// (correspondences, gradient and Hessian, finish), and the render step all cues share. The
/// rest of the frame is the optimizer's solve and the tracker's bookkeeping.
struct FrameCosts {
  struct Cue {
    std::string body, cue, camera;
    double ms = 0.0;
  };
  std::vector<Cue> cues;  ///< every body's modalities, in the order they were added
  double render_ms = 0.0;
};

/// Tracks any number of bodies with any number of modalities on frames from any number of
/// cameras. Bodies are free (6 DoF) or links of kinematic trees: a link hangs from its
/// parent by a Joint, and a tree's pose and joint values are solved in one Newton step per
/// update (TreeOptimizer), every link's cues contributing; a free body alone is one 6-DoF
/// step of its own modalities (Optimizer). Occluders are bodies the tracker renders but
/// does not track: the caller sets their poses. Before each stage of a frame (start, every
/// correspondence iteration, finish) the tracker renders what the modalities ask for, once,
/// with one SceneRenderer that shows every body and occluder (modeled occlusions, region
/// checking, keyframes).
class Tracker {
 public:
  /// `renderer`: shared with whoever else draws these bodies (vpMbIcgTracker's display);
  /// null: the tracker's own.
  explicit Tracker(TrackerParams params = {}, std::shared_ptr<SceneRenderer> renderer = nullptr);
  ~Tracker();
  Tracker(Tracker&&) noexcept;
  Tracker& operator=(Tracker&&) noexcept;

  /// Adds a free body; the returned reference stays valid for the tracker's lifetime.
  /// Names are unique among bodies, links and occluders.
  Body& add_body(Body body);
  /// Adds a link of a kinematic tree, hanging from `joint.parent` (a body or link added
  /// before, not an occluder) with joint values 0 clamped into the joint's limits. Its pose
  /// follows from its parent's and its joint values: set the root's pose and the joint values
  /// (set_joint_values), not the link's pose. Throws std::invalid_argument naming the body
  /// for an unknown parent or an invalid joint (validate(Joint&, name)).
  Body& add_link(Body body, Joint joint);
  /// Adds a body that is rendered (it hides the tracked bodies behind it) but not tracked:
  /// the caller sets its reference_T_body before each frame. It takes no modality.
  Body& add_occluder(Body body);
  /// Adds a modality bound to one of this tracker's bodies.
  void add_modality(std::unique_ptr<Modality> modality);

  const TrackerParams& params() const { return params_; }
  /// The tracked bodies and links, in the order they were added (occluders are not).
  std::vector<Body*> bodies();
  /// The occluders, in the order they were added.
  std::vector<Body*> occluders();
  Body& body(const std::string& name);

  /// The joint values of link `body` (empty for a free body).
  const std::vector<double>& joint_values(const std::string& body) const;
  /// Sets the joint values of link `body` (clamped into its limits) and places it and the
  /// links below it. Throws std::invalid_argument for a body that is not a link or a wrong
  /// number of values.
  void set_joint_values(const std::string& body, std::vector<double> values);

  /// Initialises every modality at its body's current pose (call after setting the
  /// initial poses, and again to restart after a loss).
  void start(const Frame& frame);
  /// Refines every tree's pose and joint values on this frame and reports each tracked
  /// body's quality, in the order the bodies were added.
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

  /// With `on`, every track() times each cue and the render step (last_costs()); off by
  /// default, so that tracking reads no clock.
  void set_cost_timing(bool on);
  /// The last track()'s costs; empty without set_cost_timing(true).
  const FrameCosts& last_costs() const { return costs_; }

 private:
  struct BodyState;
  const BodyState& state(const std::string& body) const;
  BodyState& state(const std::string& body);
  BodyState& add_state(Body body);
  /// The kinematic trees of the tracked bodies, each in tree order (rebuilt after adds).
  const std::vector<std::vector<TreeLink>>& trees();
  /// Renders what the modalities ask for in `stage` into renders_.
  void render(const Frame& frame, Stage stage);

  TrackerParams params_;
  std::vector<std::unique_ptr<BodyState>> states_;
  std::shared_ptr<SceneRenderer> renderer_;
  Renders renders_;
  std::vector<BodyExtent> scene_;  ///< where every body is, for the render step's Stage
  std::vector<std::vector<TreeLink>> trees_;
  Optimizer optimizer_;  ///< of a free body
  TreeOptimizer tree_optimizer_;
  bool timed_ = false;
  FrameCosts costs_;
};

}  // namespace icgp
