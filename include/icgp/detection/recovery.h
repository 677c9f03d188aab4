// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "icgp/detection/body_detector.h"
#include "icgp/detection/usual_scores.h"

namespace icgp {

/// Starts a tracker's bodies without a given pose and finds them again after a loss
/// (DetectionParams, docs/detection.md). A body reported lost stays lost, whatever its cues
/// say later, until a verified detection puts it back: first searched near its last trusted
/// pose every frame, then over the whole image every `global_search_interval` frames. A
/// body's detector is built the first time it is needed.
///
/// A recovery cannot jump: a pose found within the local search's window of the last
/// trusted pose is trusted on the frame it is found; one farther away is followed by the
/// tracker but reported lost, at the last trusted pose, until it has been confirmed on more
/// consecutive frames the farther it is (frames_to_confirm), each frame by every cue
/// (UsualScores), the whole silhouette and the depth beyond it, and the body's look
/// (BodyDetector::confirms). A turn that no image supports is not taken: a symmetric body
/// found again keeps the equivalent pose nearest its last trusted one, a round body without
/// texture keeps its last trusted turn about its axis. Two bodies are never in one place: a
/// pose that puts a body where another trusted body is (their bounding spheres' centres
/// closer than half the smaller radius) is refused.
class Recovery {
 public:
  /// `tracker`'s bodies as `config` configures them with `cameras`; `main_body` is the one
  /// the configuration's multi-region meshes belong to.
  Recovery(Tracker& tracker, TrackerConfig config, std::string main_body, std::vector<CameraCues> cameras,
           std::shared_ptr<SceneRenderer> renderer = nullptr);
  ~Recovery();

  /// Detects `body` (empty: the main body) in `frame` without touching the tracker.
  Detection detect(const Frame& frame, const std::string& body = "");
  /// Detects `body` and, when found, puts it there and starts the tracker on `frame`.
  Detection initialise(const Frame& frame, const std::string& body = "");
  /// The tracker was (re)started from poses given by the caller: every body is trusted
  /// there, so that a pose found far from it is confirmed as one found far from where a
  /// body was last tracked.
  void reset();

  /// After Tracker::track gave `results` for `frame`: remembers the poses of tracked
  /// bodies; marks lost ones; with DetectionParams::recovery, searches for the lost ones
  /// and, for each found, restarts the tracker there and tracks `frame` again, replacing
  /// `results`. A body still lost, or found but not yet confirmed, is reported lost at its
  /// last trusted pose. Returns the bodies trusted again in this frame.
  std::vector<std::string> after_track(const Frame& frame, std::vector<BodyResult>& results);

  /// Turns the search after a loss on or off (DetectionParams::recovery).
  void set_recovery(bool on) { config_.detection.recovery = on; }

  /// Whether `body` is lost (reported lost and not trusted again since).
  bool lost(const std::string& body) const;
  /// While `body` is lost: why it is not trusted again yet (not found, or found and being
  /// confirmed); empty otherwise.
  std::string why_lost(const std::string& body) const;

  /// Consecutive verified frames a pose found `windows_apart` local search windows from the
  /// last trusted one needs before it is trusted: 1 within a window, then one more for each
  /// doubling of the distance (a jump the images must keep supporting the farther it goes).
  static int frames_to_confirm(double windows_apart);

 private:
  /// A pose found far from the last trusted one, which the tracker follows until it is
  /// confirmed or refuted.
  struct Candidate {
    int confirmed = 0;  ///< consecutive verified frames so far (the frame it was found on is one)
    int needed = 1;
  };
  struct BodyState {
    std::optional<Pose> trusted;  ///< the last pose reported tracked
    bool lost = false;
    int frames_lost = 0;
    std::optional<Candidate> candidate;
    UsualScores usual;
    std::string why_lost;
  };
  /// Whether this frame's result for a candidate's body confirms it (see the class comment);
  /// `why_not` otherwise.
  bool confirms(const Frame& frame, const BodyState& s, const BodyResult& result, std::string& why_not);
  /// Of a detection's pose and its equivalents, turned about its free axes, the one that
  /// continues `reference`.
  static Pose continuation(const Detection& detection, const Pose& reference);
  BodyDetector& detector(const std::string& body);
  /// The trusted body other than `body` whose place `reference_T_body` would take; empty
  /// when none.
  std::string occupied_by(const std::string& body, const Pose& reference_T_body);
  /// Whether a camera has the image detection matches its templates in (the region cue's).
  bool can_detect() const;
  /// Where the tracker's other bodies and occluders are now.
  BodyDetector::OtherPoses other_poses(const std::string& body);

  Tracker& tracker_;
  TrackerConfig config_;
  std::string main_body_;
  std::vector<CameraCues> cameras_;
  std::shared_ptr<SceneRenderer> renderer_;
  std::map<std::string, std::unique_ptr<BodyDetector>> detectors_;
  std::map<std::string, BodyState> states_;
  std::map<std::string, Sphere> spheres_;  ///< each body's bounding sphere, in its own frame
};

}  // namespace icgp
