// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "icgp/base/frame.h"
#include "icgp/base/body.h"
#include "icgp/render/scene_renderer.h"

namespace icgp {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat66 = Eigen::Matrix<double, 6, 6>;

/// How well a modality's data fits the current pose, computed after the last correspondence
/// iteration of a frame. `score` is in [0, 1] (1: perfect fit); `valid_fraction` is the
/// share of the modality's model points that found usable data.
struct ModalityQuality {
  double score = 0.0;
  double valid_fraction = 0.0;
  int n_valid = 0;
  /// The cue had nothing to measure, through no fault of the pose: no depth measurement
  /// anywhere it searched (all invalid, NaN or missing), or no keypoints on the object
  /// (texture on a textureless object). A body's quality is then the median of its
  /// other cues' scores, so a cue without data can neither confirm nor condemn a pose.
  bool abstained = false;
  /// The standard deviation the last iteration weighed the cue with, in the cue's units
  /// (pixels; depth: metres at 1 m): its noise estimate or its schedule (ResidualNoise).
  double sigma = 0.0;
  /// It abstained because it started on this frame and made its points at the pose it would
  /// judge (texture keyframes, flow corners): no evidence either way. A body whose cues all
  /// just started keeps the pose it was given (quality 1).
  bool just_started = false;
};

/// Where a cue measured something in one camera's image, for display (ViSP's
/// getFeaturesForDisplay): a region line's contour, a texture keypoint's match.
struct ImageFeature {
  Eigen::Vector2d pixel;  ///< (u, v)
  double weight = 1.0;    ///< the correspondence's weight in [0, 1]
};

/// One cue's part of a Newton step (ALGORITHMS.md §2): the gradient and Hessian of its
/// log-likelihood with respect to θ at θ = 0, and the number of correspondences (lines,
/// points, matches) they sum over.
struct CueTerms {
  Vec6 gradient = Vec6::Zero();
  Mat66 hessian = Mat66::Zero();
  int n_correspondences = 0;
};

/// Where a body of a tracker's scene is: its bounding sphere (bounding_sphere of its mesh)
/// in the reference camera's frame.
struct BodyExtent {
  std::string name;
  Eigen::Vector3d centre;
  double radius = 0.0;
};

/// Where in a frame a cue may read renders (Modality::render_requests): when it starts,
/// in correspondence iteration `corr_iter`, or when it finishes the frame.
struct Stage {
  enum Kind { kStart, kCorrespondences, kFinish };
  Kind kind = kStart;
  int corr_iter = 0;
  /// Every body the renders show (tracked bodies, links, occluders) at its current pose:
  /// whether another body may cover the cue's decides whether a render can reveal modeled
  /// occlusions. Null: the cue's body alone.
  const std::vector<BodyExtent>* scene = nullptr;
};

/// One cue about one body's pose (ALGORITHMS.md §2): it supplies the gradient and Hessian of
/// its log-likelihood with respect to a body-frame pose variation θ = [θ_r; θ_t] at θ = 0.
/// The optimizer only sums them; a new cue needs nothing but a new subclass, added to the
/// tracker with Tracker::add_modality (docs/architecture.md shows the smallest one).
///
/// In each frame the tracker calls start() (after a (re)start only), then for each
/// correspondence iteration correspondences() and, per update, gradient_hessian(), then
/// finish(). Before each of these stages it renders what the cue asked for with
/// render_requests() and hands the renders over.
class Modality {
 public:
  explicit Modality(Body& body) : body_(&body) {}
  virtual ~Modality() = default;
  Modality(const Modality&) = delete;
  Modality& operator=(const Modality&) = delete;

  virtual std::string name() const = 0;
  /// The camera whose images the cue reads.
  virtual const std::string& camera() const = 0;
  /// The renders the cue reads in `stage` of `frame`, at the bodies' current poses (none by
  /// default). The tracker renders them once per stage and passes them to the stage.
  virtual std::vector<RenderRequest> render_requests(const Frame&, Stage) const { return {}; }
  /// (Re)initialises from the body's current pose: histograms, keyframes, ...
  virtual void start(const Frame& frame, const Renders& renders) = 0;
  /// Finds data associations at the current pose for correspondence iteration `corr_iter`.
  virtual void correspondences(const Frame& frame, const Renders& renders, int corr_iter) = 0;
  /// This cue's gradient and Hessian at the current pose.
  virtual CueTerms gradient_hessian(int corr_iter, int update_iter) = 0;
  /// The log-likelihood (up to a constant) that gradient_hessian differentiates, at the
  /// current pose with the current correspondences. For tests and diagnostics.
  virtual double log_likelihood(int corr_iter) const = 0;
  /// After the frame has converged: update statistics (histograms, keyframes).
  virtual void finish(const Frame& frame, const Renders& renders) = 0;
  virtual ModalityQuality quality() const = 0;
  /// Appends the residuals of the last correspondences at the current pose, each with a
  /// weight in [0, 1] (1: full; lower: a robust or confidence down-weighting). Units are
  /// the modality's own: pixels along the contour normal (region), metres point-to-plane
  /// (depth), pixels in u and v (texture). ViSP's getError()/getRobustWeights() show them.
  virtual void append_residuals(std::vector<double>& residuals, std::vector<double>& weights) const = 0;
  /// Appends the image measurements of the last correspondences in camera(); cues that
  /// measure depth rather than image positions append nothing.
  virtual void append_image_features(std::vector<ImageFeature>&) const {}
  /// True for a cue whose residuals cannot show its own bias, so that it measures its noise
  /// at the pose the body's other cues give (texture: a keyframe lifted at an estimated pose
  /// matches itself however wrong that pose was).
  virtual bool weighs_against_others() const { return false; }
  /// After each update, to such a cue: the step θ = [θ_r; θ_t], in the body frame, from the
  /// updated pose to where the body's other cues alone would have taken it, and that
  /// estimate's covariance, the inverse of their regularised Hessian. Where the others are
  /// unsure, their pose is no check on this cue.
  virtual void others_estimate(const Vec6& /*step*/, const Mat66& /*covariance*/) {}

  Body& body() const { return *body_; }

 private:
  Body* body_;
};

}  // namespace icgp
