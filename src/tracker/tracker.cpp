// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/tracker/tracker.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <optional>
#include <stdexcept>

namespace icgp {

struct Tracker::BodyState {
  explicit BodyState(Body body)
      : body(std::make_unique<Body>(std::move(body))),
        // A body without a mesh (cues that read no image) is never rendered.
        sphere(this->body->mesh.empty() ? Sphere{} : bounding_sphere(this->body->mesh)) {}

  std::unique_ptr<Body> body;
  Sphere sphere;  ///< bounding_sphere of the body's mesh
  bool occluder = false;
  std::optional<Joint> joint;  ///< to the parent; none for a free body and an occluder
  std::vector<double> joint_values;
  std::vector<std::unique_ptr<Modality>> modalities;
  std::vector<Modality*> cues;  ///< the same modalities, as the optimizer takes them
  CueTermSum terms;             ///< of the last update
  std::vector<double> cue_ms;   ///< with cost timing: each cue's correspondences and finish this frame
};

Tracker::Tracker(TrackerParams params, std::shared_ptr<SceneRenderer> renderer)
    : params_(params),
      renderer_(renderer ? std::move(renderer) : std::make_shared<SceneRenderer>()),
      optimizer_(params.regularisation),
      tree_optimizer_(params.regularisation) {
  if (params_.n_corr_iterations < 1 || params_.n_update_iterations < 1)
    throw std::invalid_argument("tracker needs at least one correspondence and one update iteration");
}

Tracker::~Tracker() = default;
Tracker::Tracker(Tracker&&) noexcept = default;
Tracker& Tracker::operator=(Tracker&&) noexcept = default;

Tracker::BodyState& Tracker::add_state(Body body) {
  for (const auto& s : states_)
    if (s->body->name == body.name) throw std::invalid_argument("tracker already has a body named '" + body.name + "'");
  states_.push_back(std::make_unique<BodyState>(std::move(body)));
  states_.back()->terms.time_cues(timed_);
  trees_.clear();
  return *states_.back();
}

namespace {

/// A body's quality from the scores of its cues that did not abstain: their median (the
/// mean of the middle two for an even count), 0 without any. A majority of cues must agree
/// that the pose is wrong: one cue that matches little by nature, as texture on an object
/// with little of it, does not make a well-tracked body lost, and one fooled cue does not
/// keep a lost one. Sorts `scores` in place.
double median_score(std::vector<double>& scores) {
  if (scores.empty()) return 0.0;
  std::sort(scores.begin(), scores.end());
  const std::size_t n = scores.size();
  return n % 2 == 1 ? scores[n / 2] : 0.5 * (scores[n / 2 - 1] + scores[n / 2]);
}

/// Runs `work`, adding its milliseconds to `*ms`; a null `ms` reads no clock.
template <typename Work>
void add_time(double* ms, Work&& work) {
  if (!ms) return work();
  const auto begin = std::chrono::steady_clock::now();
  work();
  *ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
}

}  // namespace

void Tracker::set_cost_timing(bool on) {
  timed_ = on;
  for (auto& s : states_) s->terms.time_cues(on);
  costs_ = FrameCosts();
}

Body& Tracker::add_body(Body body) { return *add_state(std::move(body)).body; }

Body& Tracker::add_link(Body body, Joint joint) {
  validate(joint, body.name);
  const auto parent = std::find_if(states_.begin(), states_.end(),
                                   [&](const auto& s) { return s->body->name == joint.parent && !s->occluder; });
  if (parent == states_.end())
    throw std::invalid_argument("body '" + body.name + "': joint: parent: no tracked body is named '" + joint.parent +
                                "' (a parent is added before its links)");
  const Pose parent_pose = (*parent)->body->reference_T_body;
  BodyState& link = add_state(std::move(body));
  link.joint_values = joint.clamped(std::vector<double>(joint.size(), 0.0));
  link.body->reference_T_body = parent_pose * joint.parent_T_link(link.joint_values);
  link.joint = std::move(joint);
  return *link.body;
}

Body& Tracker::add_occluder(Body body) {
  BodyState& occluder = add_state(std::move(body));
  occluder.occluder = true;
  return *occluder.body;
}

void Tracker::add_modality(std::unique_ptr<Modality> modality) {
  for (auto& s : states_)
    if (s->body.get() == &modality->body()) {
      if (s->occluder)
        throw std::invalid_argument("modality '" + modality->name() + "' belongs to occluder '" + s->body->name +
                                    "', which is not tracked");
      s->cues.push_back(modality.get());
      s->modalities.push_back(std::move(modality));
      return;
    }
  throw std::invalid_argument("modality '" + modality->name() + "' belongs to a body this tracker does not have");
}

std::vector<Body*> Tracker::bodies() {
  std::vector<Body*> out;
  for (auto& s : states_)
    if (!s->occluder) out.push_back(s->body.get());
  return out;
}

std::vector<Body*> Tracker::occluders() {
  std::vector<Body*> out;
  for (auto& s : states_)
    if (s->occluder) out.push_back(s->body.get());
  return out;
}

const std::vector<double>& Tracker::joint_values(const std::string& name) const { return state(name).joint_values; }

void Tracker::set_joint_values(const std::string& name, std::vector<double> values) {
  BodyState& link = state(name);
  if (!link.joint) throw std::invalid_argument("body '" + name + "' has no joint");
  if (static_cast<int>(values.size()) != link.joint->size())
    throw std::invalid_argument("body '" + name + "': its joint has " + std::to_string(link.joint->size()) +
                                " values, got " + std::to_string(values.size()));
  link.joint_values = link.joint->clamped(std::move(values));
  for (const std::vector<TreeLink>& tree : trees()) place_links(tree);
}

const std::vector<std::vector<TreeLink>>& Tracker::trees() {
  if (!trees_.empty()) return trees_;
  // Parents are added before their links, so one pass in the order of adding puts every
  // link after its parent, in its parent's tree.
  std::map<std::string, std::pair<std::size_t, int>> placed;  // body -> its tree, its index there
  for (auto& s : states_) {
    if (s->occluder) continue;
    TreeLink link{s->body.get(), &s->cues, &s->terms};
    std::size_t tree = trees_.size();
    if (s->joint) {
      const auto [parent_tree, parent_index] = placed.at(s->joint->parent);
      tree = parent_tree;
      link.parent = parent_index;
      link.joint = &*s->joint;
      link.joint_values = &s->joint_values;
    } else {
      trees_.emplace_back();
    }
    placed[s->body->name] = {tree, static_cast<int>(trees_[tree].size())};
    trees_[tree].push_back(link);
  }
  return trees_;
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

Tracker::BodyState& Tracker::state(const std::string& name) {
  return const_cast<BodyState&>(static_cast<const Tracker&>(*this).state(name));
}

const Mat66& Tracker::last_hessian(const std::string& name) const { return state(name).terms.total().hessian; }

const std::vector<CueTerms>& Tracker::last_cue_terms(const std::string& name) const {
  return state(name).terms.per_cue();
}

void Tracker::residuals(const std::string& name, std::vector<double>& residuals, std::vector<double>& weights) const {
  for (const auto& m : state(name).modalities) m->append_residuals(residuals, weights);
}

std::vector<const Modality*> Tracker::modalities(const std::string& name) const {
  const BodyState& s = state(name);
  return {s.cues.begin(), s.cues.end()};
}

void Tracker::render(const Frame& frame, Stage stage) {
  scene_.clear();
  for (const auto& s : states_)
    if (!s->body->mesh.empty())
      scene_.push_back({s->body->name, s->body->reference_T_body * s->sphere.centre, s->sphere.radius});
  stage.scene = &scene_;
  std::vector<RenderRequest> requests;
  for (auto& s : states_)
    for (const Modality* m : s->cues)
      for (RenderRequest& r : m->render_requests(frame, stage))
        // Cues of one body in one camera ask for the same crop: render it once.
        if (std::find(requests.begin(), requests.end(), r) == requests.end()) requests.push_back(std::move(r));
  if (requests.empty()) {
    renders_.clear();
    return;
  }
  std::vector<const Body*> bodies;
  for (const auto& s : states_) bodies.push_back(s->body.get());
  renderer_->render(bodies, requests, renders_);
}

void Tracker::start(const Frame& frame) {
  for (const std::vector<TreeLink>& tree : trees()) place_links(tree);
  render(frame, {Stage::kStart});
  for (auto& s : states_)
    for (Modality* m : s->cues) m->start(frame, renders_);
}

std::vector<BodyResult> Tracker::track(const Frame& frame) {
  double* const render_ms = timed_ ? &costs_.render_ms : nullptr;
  if (timed_) {
    costs_.render_ms = 0.0;
    for (auto& s : states_) {
      s->cue_ms.assign(s->cues.size(), 0.0);
      s->terms.reset_cue_ms();
    }
  }
  const auto cue_ms = [&](BodyState& s, std::size_t i) { return timed_ ? &s.cue_ms[i] : nullptr; };
  for (int c = 0; c < params_.n_corr_iterations; ++c) {
    add_time(render_ms, [&] { render(frame, {Stage::kCorrespondences, c}); });
    for (auto& s : states_)
      for (std::size_t i = 0; i < s->cues.size(); ++i)
        add_time(cue_ms(*s, i), [&] { s->cues[i]->correspondences(frame, renders_, c); });
    for (int u = 0; u < params_.n_update_iterations; ++u)
      for (const std::vector<TreeLink>& tree : trees()) {
        if (tree.size() == 1)
          optimizer_.step(*tree.front().body, *tree.front().cues, *tree.front().terms, c, u);
        else
          tree_optimizer_.step(tree, c, u);
      }
  }

  add_time(render_ms, [&] { render(frame, {Stage::kFinish}); });
  std::vector<BodyResult> results;
  for (auto& s : states_) {
    if (s->occluder) continue;
    BodyResult r;
    r.body = s->body->name;
    r.joint_values = s->joint_values;
    std::vector<double> scores;
    for (std::size_t i = 0; i < s->cues.size(); ++i) {
      Modality* m = s->cues[i];
      add_time(cue_ms(*s, i), [&] { m->finish(frame, renders_); });
      r.modalities.push_back(m->quality());
      if (!r.modalities.back().abstained) scores.push_back(r.modalities.back().score);
    }
    r.reference_T_body = s->body->reference_T_body;
    r.quality = median_score(scores);
    // Cues that only lifted their points at the given pose this frame (texture, flow) have
    // nothing to judge yet: that is no evidence against the pose the caller gave.
    const bool all_just_started = std::all_of(r.modalities.begin(), r.modalities.end(),
                                              [](const ModalityQuality& q) { return q.just_started; });
    if (scores.empty() && all_just_started && !r.modalities.empty()) r.quality = 1.0;
    r.tracked = r.quality >= params_.quality_threshold;
    results.push_back(std::move(r));
  }
  if (timed_) {
    costs_.cues.clear();
    for (auto& s : states_)
      for (std::size_t i = 0; i < s->cues.size(); ++i) {
        const std::vector<double>& solve_ms = s->terms.cue_ms();
        costs_.cues.push_back({s->body->name, s->cues[i]->name(), s->cues[i]->camera(),
                               s->cue_ms[i] + (i < solve_ms.size() ? solve_ms[i] : 0.0)});
      }
  }
  return results;
}

}  // namespace icgp
