// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/tracker/tracker.h"

#include <Eigen/Cholesky>
#include <stdexcept>

namespace icgp {

struct Tracker::BodyState {
  std::unique_ptr<Body> body;
  std::vector<std::unique_ptr<Modality>> modalities;
  Mat66 hessian = Mat66::Zero();
};

Tracker::Tracker(TrackerParams params) : params_(params) {
  if (params_.n_corr_iterations < 1 || params_.n_update_iterations < 1)
    throw std::invalid_argument("tracker needs at least one correspondence and one update iteration");
  if (!(params_.tikhonov_rotation >= 0.0) || !(params_.tikhonov_translation >= 0.0))
    throw std::invalid_argument("tracker Tikhonov parameters must be non-negative");
}

Tracker::~Tracker() = default;
Tracker::Tracker(Tracker&&) noexcept = default;
Tracker& Tracker::operator=(Tracker&&) noexcept = default;

Body& Tracker::add_body(Body body) {
  for (const auto& s : states_)
    if (s->body->name == body.name) throw std::invalid_argument("tracker already has a body named '" + body.name + "'");
  auto state = std::make_unique<BodyState>();
  state->body = std::make_unique<Body>(std::move(body));
  states_.push_back(std::move(state));
  return *states_.back()->body;
}

void Tracker::add_modality(std::unique_ptr<Modality> modality) {
  for (auto& s : states_)
    if (s->body.get() == &modality->body()) {
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

const Mat66& Tracker::last_hessian(const std::string& name) const {
  for (const auto& s : states_)
    if (s->body->name == name) return s->hessian;
  throw std::invalid_argument("tracker has no body named '" + name + "'");
}

void Tracker::residuals(const std::string& name, std::vector<double>& residuals, std::vector<double>& weights) const {
  for (const auto& s : states_)
    if (s->body->name == name) {
      for (const auto& m : s->modalities) m->append_residuals(residuals, weights);
      return;
    }
  throw std::invalid_argument("tracker has no body named '" + name + "'");
}

std::vector<const Modality*> Tracker::modalities(const std::string& name) const {
  for (const auto& s : states_)
    if (s->body->name == name) {
      std::vector<const Modality*> out;
      for (const auto& m : s->modalities) out.push_back(m.get());
      return out;
    }
  throw std::invalid_argument("tracker has no body named '" + name + "'");
}

void Tracker::start(const Frame& frame) {
  for (auto& s : states_)
    for (auto& m : s->modalities) m->start(frame);
}

std::vector<BodyResult> Tracker::track(const Frame& frame) {
  Vec6 regularisation;
  regularisation << Eigen::Vector3d::Constant(params_.tikhonov_rotation),
      Eigen::Vector3d::Constant(params_.tikhonov_translation);
  for (int c = 0; c < params_.n_corr_iterations; ++c) {
    for (auto& s : states_)
      for (auto& m : s->modalities) m->correspondences(frame, c);
    for (int u = 0; u < params_.n_update_iterations; ++u) {
      for (auto& s : states_) {
        Vec6 g = Vec6::Zero();
        Mat66 H = Mat66::Zero();
        for (auto& m : s->modalities) m->add_gradient_hessian(c, u, g, H);
        s->hessian = H;
        Mat66 A = -H;
        A.diagonal() += regularisation;
        const Vec6 theta = A.ldlt().solve(g);
        // A singular system (no data and no regularisation) must not corrupt the pose.
        if (theta.allFinite()) s->body->reference_T_body = s->body->reference_T_body.updated_in_body_frame(theta);
      }
    }
  }

  std::vector<BodyResult> results;
  for (auto& s : states_) {
    BodyResult r;
    r.body = s->body->name;
    double score_sum = 0.0;
    int n_scored = 0;
    for (auto& m : s->modalities) {
      m->finish(frame);
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
