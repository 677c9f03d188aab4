// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "icgp/base/frame.h"
#include "icgp/base/body.h"

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
  /// (texture on a textureless object). A body's quality is then the mean of its other
  /// cues' scores, so a cue without data can neither confirm nor condemn a pose.
  bool abstained = false;
  /// The standard deviation the last iteration weighed the cue with, in the cue's units
  /// (pixels; depth: metres at 1 m): its noise estimate or its schedule (ResidualNoise).
  double sigma = 0.0;
};

/// Where a cue measured something in one camera's image, for display (ViSP's
/// getFeaturesForDisplay): a region line's contour, a texture keypoint's match.
struct ImageFeature {
  Eigen::Vector2d pixel;  ///< (u, v)
  double weight = 1.0;    ///< the correspondence's weight in [0, 1]
};

/// One cue about one body's pose (ALGORITHMS.md §2): it supplies the gradient and Hessian of
/// its log-likelihood with respect to a body-frame pose variation θ = [θ_r; θ_t] at θ = 0.
/// The optimizer only sums them; a new cue needs nothing but a new subclass.
class Modality {
 public:
  explicit Modality(Body& body) : body_(&body) {}
  virtual ~Modality() = default;
  Modality(const Modality&) = delete;
  Modality& operator=(const Modality&) = delete;

  virtual std::string name() const = 0;
  /// The camera whose images the cue reads.
  virtual const std::string& camera() const = 0;
  /// (Re)initialises from the body's current pose: histograms, keyframes, ...
  virtual void start(const Frame& frame) = 0;
  /// Finds data associations at the current pose for correspondence iteration `corr_iter`.
  virtual void correspondences(const Frame& frame, int corr_iter) = 0;
  /// Adds this modality's gradient and Hessian at the current pose to g and H.
  virtual void add_gradient_hessian(int corr_iter, int update_iter, Vec6& g, Mat66& H) = 0;
  /// The log-likelihood (up to a constant) that add_gradient_hessian differentiates, at
  /// the current pose with the current correspondences. For tests and diagnostics.
  virtual double log_likelihood(int corr_iter) const = 0;
  /// After the frame has converged: update statistics (histograms, keyframes).
  virtual void finish(const Frame& frame) = 0;
  virtual ModalityQuality quality() const = 0;
  /// Appends the residuals of the last correspondences at the current pose, each with a
  /// weight in [0, 1] (1: full; lower: a robust or confidence down-weighting). Units are
  /// the modality's own: pixels along the contour normal (region), metres point-to-plane
  /// (depth), pixels in u and v (texture). ViSP's getError()/getRobustWeights() show them.
  virtual void append_residuals(std::vector<double>& residuals, std::vector<double>& weights) const = 0;
  /// Appends the image measurements of the last correspondences in camera(); cues that
  /// measure depth rather than image positions append nothing.
  virtual void append_image_features(std::vector<ImageFeature>&) const {}

  Body& body() const { return *body_; }

 private:
  Body* body_;
};

}  // namespace icgp
