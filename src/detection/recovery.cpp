// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/detection/recovery.h"

#include <algorithm>

namespace icgp {

namespace {

/// Of a detection's pose and its symmetric equivalents, the one nearest `reference` in rotation.
Pose nearest_rotation(const Detection& detection, const Pose& reference) {
  Pose nearest = detection.reference_T_body;
  double least = rotation_angle_between(nearest.rotation(), reference.rotation());
  for (const Pose& pose : detection.equivalents) {
    const double angle = rotation_angle_between(pose.rotation(), reference.rotation());
    if (angle < least) {
      nearest = pose;
      least = angle;
    }
  }
  return nearest;
}

}  // namespace

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

void Recovery::reset() { states_.clear(); }

bool Recovery::lost(const std::string& body) const {
  const auto it = states_.find(body);
  return it != states_.end() && it->second.lost;
}

bool Recovery::can_detect() const {
  return std::any_of(cameras_.begin(), cameras_.end(), [](const CameraCues& c) { return (c.types & visp_type::kEdge) != 0; });
}

std::vector<std::string> Recovery::after_track(const Frame& frame, std::vector<BodyResult>& results) {
  std::vector<std::string> found;
  for (const BodyResult& r : results) {
    // A link's pose follows its parent's: it is found with its tree's root.
    if (!tracker_.joint_values(r.body).empty()) continue;
    BodyState& s = states_[r.body];
    // Without recovery a body is lost on the frames its cues say so, no longer.
    if ((!s.lost || !config_.detection.recovery) && r.tracked) {
      s = BodyState{r.reference_T_body, false, 0};
      continue;
    }
    // Templates are matched in the region cue's image: without one (a KLT or depth camera
    // alone) a lost body stays lost until the program initialises it again.
    if (!config_.detection.recovery || !can_detect()) continue;
    s.lost = true;
    ++s.frames_lost;
    BodyDetector& d = detector(r.body);
    Detection detection;
    const BodyDetector::OtherPoses others = other_poses(r.body);
    if (s.trusted) detection = d.search_near(frame, *s.trusted, others);
    if (!detection.found && (s.frames_lost - 1) % config_.detection.global_search_interval == 0)
      detection = d.detect(frame, others);
    if (!detection.found) continue;
    // A symmetric object found again: the equivalent pose that continues the one it was
    // tracked at (lost since its start: the start pose as the cues left it), so that its
    // frame does not flip over a loss.
    detection.reference_T_body = nearest_rotation(detection, s.trusted ? *s.trusted : r.reference_T_body);
    tracker_.body(r.body).reference_T_body = detection.reference_T_body;
    s = BodyState{detection.reference_T_body, false, 0};
    found.push_back(r.body);
  }
  if (!found.empty()) {
    tracker_.start(frame);
    results = tracker_.track(frame);
    for (const BodyResult& r : results)
      if (r.tracked && !states_[r.body].lost) states_[r.body].trusted = r.reference_T_body;
  }
  // Lost bodies are reported where they were last trusted, not where their cues wandered.
  for (BodyResult& r : results) {
    const BodyState& s = states_[r.body];
    if (!s.lost) continue;
    r.tracked = false;
    if (s.trusted) r.reference_T_body = *s.trusted;
  }
  return found;
}

}  // namespace icgp
