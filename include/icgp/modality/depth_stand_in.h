// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "icgp/modality/modality.h"

namespace icgp {

/// A cue that works only in frames where its body has no depth: it stands in for what the
/// depth cue pins down. vpMbIcgTracker's flow and edge cues are such stand-ins when the
/// tracker has all of ICG+'s cues: a ViSP program that asks for KLT_TRACKER or EDGE_TRACKER
/// with a colour camera alone needs them to hold the pose as ViSP's KLT and moving edges do,
/// while with depth, region, depth and texture are more accurate than ViSP without them and
/// twice as fast (docs/visp.md, "Every tracker type, measured").
///
/// In a frame where any of `depth_cameras` delivers depth the cue sits out: it asks for no
/// render, adds no term and abstains. In a frame without, it works if it was kept up to
/// date through the frame before; if it sat that one out, it starts at the end of this frame
/// instead, at the pose the other cues converged to, as a tracker starts a cue at a given
/// pose before the next frame: what it carries over between frames (corners, contrasts)
/// must come from the frame just before.
class DepthStandIn final : public Modality {
 public:
  /// `depth_cameras`: the cameras the body's depth cues read; at least one.
  DepthStandIn(std::unique_ptr<Modality> cue, std::vector<std::string> depth_cameras);

  std::string name() const override { return cue_->name(); }
  const std::string& camera() const override { return cue_->camera(); }
  std::vector<RenderRequest> render_requests(const Frame& frame, Stage stage) const override;
  void start(const Frame& frame, const Renders& renders) override;
  void correspondences(const Frame& frame, const Renders& renders, int corr_iter) override;
  CueTerms gradient_hessian(int corr_iter, int update_iter) override;
  double log_likelihood(int corr_iter) const override;
  void finish(const Frame& frame, const Renders& renders) override;
  ModalityQuality quality() const override;
  void append_residuals(std::vector<double>& residuals, std::vector<double>& weights) const override;
  void append_image_features(std::vector<ImageFeature>& features) const override;

  /// Whether the cue works in the current frame.
  bool working() const { return working_; }

 private:
  /// True when none of the depth cameras delivers depth in `frame`.
  bool needed(const Frame& frame) const;

  std::unique_ptr<Modality> cue_;
  std::vector<std::string> depth_cameras_;
  /// The cue was started or worked in the last frame: it may work in the next.
  bool current_ = false;
  /// In the current frame (from its first correspondences on): it works, or it starts at
  /// the end of the frame.
  bool working_ = false, starting_ = false;
};

}  // namespace icgp
