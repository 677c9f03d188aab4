// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/detection/recovery.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace icgp {

namespace {

/// More consecutive frames than this are never asked of a found pose.
constexpr int kMaxFramesToConfirm = 6;

}  // namespace

int Recovery::frames_to_confirm(double windows_apart) {
  if (!(windows_apart > 1.0)) return 1;
  return std::min(kMaxFramesToConfirm, 2 + static_cast<int>(std::floor(std::log2(windows_apart))));
}

Pose Recovery::continuation(const Detection& detection, const Pose& reference) {
  std::vector<Pose> poses{detection.reference_T_body};
  poses.insert(poses.end(), detection.equivalents.begin(), detection.equivalents.end());
  Pose nearest = poses.front();
  double least = std::numeric_limits<double>::infinity();
  for (Pose pose : poses) {
    for (const BodyAxis& axis : detection.free_turn_axes) pose = turned_towards(pose, axis, reference);
    const double angle = rotation_angle_between(pose.rotation(), reference.rotation());
    if (angle < least) {
      nearest = pose;
      least = angle;
    }
  }
  return nearest;
}

Recovery::Recovery(Tracker& tracker, TrackerConfig config, std::string main_body, std::vector<CameraCues> cameras,
                   std::shared_ptr<SceneRenderer> renderer)
    : tracker_(tracker),
      config_(std::move(config)),
      main_body_(std::move(main_body)),
      cameras_(std::move(cameras)),
      renderer_(std::move(renderer)) {}

Recovery::~Recovery() = default;

BodyDetector& Recovery::detector(const std::string& body) {
  auto it = detectors_.find(body);
  if (it != detectors_.end()) return *it->second;
  TrackerConfig config = config_;
  // The configuration's region meshes are the main body's.
  if (body != main_body_) config.regions.clear();
  // Every other body may stand in front of this one: the refinement renders them.
  std::vector<Body> others;
  for (Body* other : tracker_.bodies())
    if (other->name != body) others.push_back({other->name, other->mesh, other->reference_T_body});
  for (Body* occluder : tracker_.occluders()) others.push_back({occluder->name, occluder->mesh, occluder->reference_T_body});
  auto made = std::make_unique<BodyDetector>(config, tracker_.body(body).mesh, body, cameras_, renderer_, std::move(others));
  return *detectors_.emplace(body, std::move(made)).first->second;
}

BodyDetector::OtherPoses Recovery::other_poses(const std::string& body) {
  BodyDetector::OtherPoses poses;
  for (Body* other : tracker_.bodies())
    if (other->name != body) poses[other->name] = other->reference_T_body;
  for (Body* occluder : tracker_.occluders()) poses[occluder->name] = occluder->reference_T_body;
  return poses;
}

Detection Recovery::detect(const Frame& frame, const std::string& body) {
  const std::string name = body.empty() ? main_body_ : body;
  return detector(name).detect(frame, other_poses(name));
}

Detection Recovery::initialise(const Frame& frame, const std::string& body) {
  const std::string name = body.empty() ? main_body_ : body;
  Detection detection = detect(frame, name);
  if (!detection.found) return detection;
  tracker_.body(name).reference_T_body = detection.reference_T_body;
  tracker_.start(frame);
  states_[name] = BodyState{detection.reference_T_body, false, 0};
  return detection;
}

void Recovery::reset() {
  states_.clear();
  for (Body* body : tracker_.bodies())
    if (tracker_.joint_values(body->name).empty()) states_[body->name].trusted = body->reference_T_body;
}

std::string Recovery::occupied_by(const std::string& body, const Pose& reference_T_body) {
  const auto sphere_of = [this](const Body& b) -> const Sphere& {
    auto it = spheres_.find(b.name);
    if (it == spheres_.end()) it = spheres_.emplace(b.name, bounding_sphere(b.mesh)).first;
    return it->second;
  };
  const Sphere& mine = sphere_of(tracker_.body(body));
  const Eigen::Vector3d centre = reference_T_body * mine.centre;
  for (const auto& [name, state] : states_) {
    if (name == body || state.lost || !state.trusted) continue;
    const Sphere& theirs = sphere_of(tracker_.body(name));
    if ((*state.trusted * theirs.centre - centre).norm() < 0.5 * std::min(mine.radius, theirs.radius)) return name;
  }
  return "";
}

bool Recovery::lost(const std::string& body) const {
  const auto it = states_.find(body);
  return it != states_.end() && it->second.lost;
}

std::string Recovery::why_lost(const std::string& body) const {
  const auto it = states_.find(body);
  return it != states_.end() && it->second.lost ? it->second.why_lost : std::string();
}

bool Recovery::can_detect() const {
  return std::any_of(cameras_.begin(), cameras_.end(), [](const CameraCues& c) { return (c.types & visp_type::kEdge) != 0; });
}

bool Recovery::confirms(const Frame& frame, const BodyState& s, const BodyResult& result, std::string& why_not) {
  if (!result.tracked || result.quality < config_.detection.accept_quality) {
    why_not = "its cues' quality is " + std::to_string(result.quality) + ", below " +
              std::to_string(config_.detection.accept_quality);
    return false;
  }
  const std::string occupant = occupied_by(result.body, result.reference_T_body);
  if (!occupant.empty()) {
    why_not = "it would be where '" + occupant + "' is";
    return false;
  }
  std::vector<std::string> cue_names;
  for (const Modality* m : tracker_.modalities(result.body)) cue_names.push_back(m->name());
  return s.usual.all_agree(result, cue_names, tracker_.params().quality_threshold, why_not) &&
         detector(result.body).confirms(frame, result.reference_T_body, other_poses(result.body), why_not);
}

std::vector<std::string> Recovery::after_track(const Frame& frame, std::vector<BodyResult>& results) {
  std::vector<std::string> found, trusted_again;
  for (const BodyResult& r : results) {
    // A link's pose follows its parent's: it is found with its tree's root.
    if (!tracker_.joint_values(r.body).empty()) continue;
    BodyState& s = states_[r.body];
    // Without recovery a body is lost on the frames its cues say so, no longer.
    if ((!s.lost || !config_.detection.recovery) && r.tracked) {
      s.trusted = r.reference_T_body;
      s.lost = false;
      s.frames_lost = 0;
      s.usual.learn(r);
      continue;
    }
    // Templates are matched in the region cue's image: without one (a KLT or depth camera
    // alone) a lost body stays lost until the program initialises it again.
    if (!config_.detection.recovery || !can_detect()) continue;
    if (!s.lost) s.why_lost = "its cues' quality fell to " + std::to_string(r.quality);
    s.lost = true;
    ++s.frames_lost;
    if (s.candidate) {
      // The tracker has followed the pose found far away since: confirmed once more, or refuted.
      std::string why_not;
      if (confirms(frame, s, r, why_not)) {
        if (++s.candidate->confirmed < s.candidate->needed) {
          s.why_lost = "found far from where it was last trusted: confirmed on " +
                       std::to_string(s.candidate->confirmed) + " of " + std::to_string(s.candidate->needed) +
                       " frames";
          continue;
        }
        s.trusted = r.reference_T_body;
        s.lost = false;
        s.frames_lost = 0;
        s.candidate.reset();
        s.usual.learn(r);
        trusted_again.push_back(r.body);
        continue;
      }
      s.why_lost = "a pose found far from where it was last trusted was refuted: " + why_not;
      s.candidate.reset();
    }
    BodyDetector& d = detector(r.body);
    Detection detection;
    const BodyDetector::OtherPoses others = other_poses(r.body);
    if (s.trusted) detection = d.search_near(frame, *s.trusted, others);
    if (!detection.found && (s.frames_lost - 1) % config_.detection.global_search_interval == 0)
      detection = d.detect(frame, others);
    if (!detection.found) {
      if (!s.candidate && !detection.why_not.empty()) s.why_lost = "not found: " + detection.why_not;
      continue;
    }
    const std::string occupant = occupied_by(r.body, detection.reference_T_body);
    if (!occupant.empty()) {
      s.why_lost = "found only where '" + occupant + "' is";
      continue;
    }
    // The pose that continues the one it was tracked at, so that its frame does not flip or
    // turn over a loss: the cues' pose of this frame while it stays within a local window of
    // the last trusted one (texture may have followed a turn that the shape cannot see), else
    // the last trusted pose (lost since its start: the start pose as the cues left it).
    const bool cues_nearby = s.trusted && d.windows_apart(*s.trusted, r.reference_T_body) <= 1.0;
    const Pose pose = continuation(detection, cues_nearby || !s.trusted ? r.reference_T_body : *s.trusted);
    tracker_.body(r.body).reference_T_body = pose;
    // The detection verified it on this frame: that is its first confirmation.
    s.candidate = Candidate{1, s.trusted ? frames_to_confirm(d.windows_apart(*s.trusted, pose)) : 1};
    found.push_back(r.body);
  }
  if (!found.empty()) {
    tracker_.start(frame);
    results = tracker_.track(frame);
    for (const std::string& body : found) {
      BodyState& s = states_[body];
      if (s.candidate->confirmed < s.candidate->needed) {
        s.why_lost = "found far from where it was last trusted: confirmed on 1 of " +
                     std::to_string(s.candidate->needed) + " frames";
        continue;
      }
      const auto r = std::find_if(results.begin(), results.end(), [&](const BodyResult& x) { return x.body == body; });
      s.lost = false;
      s.frames_lost = 0;
      s.candidate.reset();
      s.trusted = r->tracked ? r->reference_T_body : tracker_.body(body).reference_T_body;
      trusted_again.push_back(body);
    }
  }
  // Lost bodies are reported where they were last trusted, not where their cues wandered.
  for (BodyResult& r : results) {
    const BodyState& s = states_[r.body];
    if (!s.lost) continue;
    r.tracked = false;
    if (s.trusted) r.reference_T_body = *s.trusted;
  }
  return trusted_again;
}

}  // namespace icgp
