// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/tracker/tracker.h"

#include <stdexcept>

namespace icgp {

struct Tracker::BodyState {
  BodyState(Body body, const TrackerParams& params)
      : body(std::make_unique<Body>(std::move(body))),
        optimizer(OptimizerParams{params.tikhonov_rotation, params.tikhonov_translation}) {}

  std::unique_ptr<Body> body;
  std::vector<std::unique_ptr<Modality>> modalities;
  std::vector<Modality*> cues;  ///< the same modalities, as the optimizer takes them
  Optimizer optimizer;
};

Tracker::Tracker(TrackerParams params, std::shared_ptr<SceneRenderer> renderer)
    : params_(params), renderer_(renderer ? std::move(renderer) : std::make_shared<SceneRenderer>()) {
  if (params_.n_corr_iterations < 1 || params_.n_update_iterations < 1)
    throw std::invalid_argument("tracker needs at least one correspondence and one update iteration");
  validate(OptimizerParams{params_.tikhonov_rotation, params_.tikhonov_translation});
}

Tracker::~Tracker() = default;
Tracker::Tracker(Tracker&&) noexcept = default;
Tracker& Tracker::operator=(Tracker&&) noexcept = default;

Body& Tracker::add_body(Body body) {
  for (const auto& s : states_)
    if (s->body->name == body.name) throw std::invalid_argument("tracker already has a body named '" + body.name + "'");
  states_.push_back(std::make_unique<BodyState>(std::move(body), params_));
  return *states_.back()->body;
}

void Tracker::add_modality(std::unique_ptr<Modality> modality) {
  for (auto& s : states_)
    if (s->body.get() == &modality->body()) {
      s->cues.push_back(modality.get());
      s->modalities.push_back(std::move(modality));
      return;
    }
  throw std::invalid_argument("modality '" + modality->name() + "' belongs to a body this tracker does not have");
}

std::vector<Body*> Tracker::bodies() {
  std::vector<Body*> out;
  for (auto& s : states_) out.push_back(s->body.get());
  return out;
}

Body& Tracker::body(const std::string& name) {
  for (auto& s : states_)
    if (s->body->name == name) return *s->body;
  throw std::invalid_argument("tracker has no body named '" + name + "'");
}

const Tracker::BodyState& Tracker::state(const std::string& name) const {
  for (const auto& s : states_)
    if (s->body->name == name) return *s;
  throw std::invalid_argument("tracker has no body named '" + name + "'");
}

const Mat66& Tracker::last_hessian(const std::string& name) const { return state(name).optimizer.total().hessian; }

const std::vector<CueTerms>& Tracker::last_cue_terms(const std::string& name) const {
  return state(name).optimizer.cue_terms();
}

void Tracker::residuals(const std::string& name, std::vector<double>& residuals, std::vector<double>& weights) const {
  for (const auto& m : state(name).modalities) m->append_residuals(residuals, weights);
}

std::vector<const Modality*> Tracker::modalities(const std::string& name) const {
  const BodyState& s = state(name);
  return {s.cues.begin(), s.cues.end()};
}

void Tracker::render(const Frame& frame, Stage stage) {
  std::vector<RenderRequest> requests;
  for (auto& s : states_)
    for (const Modality* m : s->cues)
      for (RenderRequest& r : m->render_requests(frame, stage)) requests.push_back(std::move(r));
  if (requests.empty()) {
    renders_.clear();
    return;
  }
  std::vector<const Body*> bodies;
  for (const auto& s : states_) bodies.push_back(s->body.get());
  renderer_->render(bodies, requests, renders_);
}

void Tracker::start(const Frame& frame) {
  render(frame, {Stage::kStart});
  for (auto& s : states_)
    for (Modality* m : s->cues) m->start(frame, renders_);
}

std::vector<BodyResult> Tracker::track(const Frame& frame) {
  for (int c = 0; c < params_.n_corr_iterations; ++c) {
    render(frame, {Stage::kCorrespondences, c});
    for (auto& s : states_)
      for (Modality* m : s->cues) m->correspondences(frame, renders_, c);
    for (int u = 0; u < params_.n_update_iterations; ++u)
      for (auto& s : states_) s->optimizer.step(*s->body, s->cues, c, u);
  }

  render(frame, {Stage::kFinish});
  std::vector<BodyResult> results;
  for (auto& s : states_) {
    BodyResult r;
    r.body = s->body->name;
    double score_sum = 0.0;
    int n_scored = 0;
    for (Modality* m : s->cues) {
      m->finish(frame, renders_);
      r.modalities.push_back(m->quality());
      if (r.modalities.back().abstained) continue;
      score_sum += r.modalities.back().score;
      ++n_scored;
    }
    r.reference_T_body = s->body->reference_T_body;
    r.quality = n_scored > 0 ? score_sum / n_scored : 0.0;
    r.tracked = r.quality >= params_.quality_threshold;
    results.push_back(std::move(r));
  }
  return results;
}

}  // namespace icgp
