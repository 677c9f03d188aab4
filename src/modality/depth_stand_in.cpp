// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/modality/depth_stand_in.h"

#include <stdexcept>

namespace icgp {

DepthStandIn::DepthStandIn(std::unique_ptr<Modality> cue, std::vector<std::string> depth_cameras)
    : Modality(cue ? cue->body() : throw std::invalid_argument("DepthStandIn: no cue given")),
      cue_(std::move(cue)),
      depth_cameras_(std::move(depth_cameras)) {
  if (depth_cameras_.empty())
    throw std::invalid_argument("DepthStandIn: the " + cue_->name() + " cue of '" + body().name +
                                "' stands in for depth, but no depth camera is given");
}

bool DepthStandIn::needed(const Frame& frame) const {
  for (const std::string& camera : depth_cameras_)
    if (const DepthImage* depth = frame.find_depth(camera); depth && depth->delivered()) return false;
  return true;
}

std::vector<RenderRequest> DepthStandIn::render_requests(const Frame& frame, Stage stage) const {
  switch (stage.kind) {
    case Stage::kStart:
      return needed(frame) ? cue_->render_requests(frame, stage) : std::vector<RenderRequest>{};
    case Stage::kCorrespondences: {
      // Before the first correspondences the frame's state is not set yet.
      const bool works = stage.corr_iter == 0 ? current_ && needed(frame) : working_;
      return works ? cue_->render_requests(frame, stage) : std::vector<RenderRequest>{};
    }
    case Stage::kFinish:
      if (working_) return cue_->render_requests(frame, stage);
      if (starting_) return cue_->render_requests(frame, {Stage::kStart, 0, stage.scene});
      return {};
  }
  return {};
}

void DepthStandIn::start(const Frame& frame, const Renders& renders) {
  working_ = starting_ = false;
  current_ = needed(frame);
  if (current_) cue_->start(frame, renders);
}

void DepthStandIn::correspondences(const Frame& frame, const Renders& renders, int corr_iter) {
  if (corr_iter == 0) {
    const bool needed_now = needed(frame);
    working_ = needed_now && current_;
    starting_ = needed_now && !current_;
    current_ = false;  // until finish() keeps it up to date or starts it
  }
  if (working_) cue_->correspondences(frame, renders, corr_iter);
}

CueTerms DepthStandIn::gradient_hessian(int corr_iter, int update_iter) {
  return working_ ? cue_->gradient_hessian(corr_iter, update_iter) : CueTerms{};
}

double DepthStandIn::log_likelihood(int corr_iter) const { return working_ ? cue_->log_likelihood(corr_iter) : 0.0; }

void DepthStandIn::finish(const Frame& frame, const Renders& renders) {
  if (working_)
    cue_->finish(frame, renders);
  else if (starting_)
    cue_->start(frame, renders);
  current_ = working_ || starting_;
}

ModalityQuality DepthStandIn::quality() const {
  if (working_) return cue_->quality();
  ModalityQuality sitting_out;
  sitting_out.abstained = true;
  return sitting_out;
}

void DepthStandIn::append_residuals(std::vector<double>& residuals, std::vector<double>& weights) const {
  if (working_) cue_->append_residuals(residuals, weights);
}

void DepthStandIn::append_image_features(std::vector<ImageFeature>& features) const {
  if (working_) cue_->append_image_features(features);
}

}  // namespace icgp
