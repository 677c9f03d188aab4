// SPDX-License-Identifier: GPL-2.0-or-later
// icgp's tracker on one body as the commands, benchmarks and bindings run it over a
// sequence: built from a configuration, timed by the same rule as the ViSP baselines, and
// searching again for a lost body (Recovery) when the configuration's detection.recovery is
// on.
#pragma once

#include <memory>
#include <string>

#include "icgp/detection/recovery.h"
#include "icgp/eval/sequence_run.h"
#include "icgp/tracker/tracker.h"
#include "icgp/tracker/tracker_config.h"

namespace icgp {

class SingleBodyTracker {
 public:
  SingleBodyTracker(const TrackerConfig& config, const Mesh& mesh, const std::string& body_name);

  /// Puts the body at `reference_T_body` and starts every modality on `frame`.
  void start(const Frame& frame, const Pose& reference_T_body);
  /// Detects the body in `frame` and, when found, starts there.
  Detection start_by_detection(const Frame& frame) { return recovery_.initialise(frame); }

  /// Tracks one frame, searching again for a lost body; `track_ms` receives the duration
  /// of Tracker::track and of the search alone. `found_again`: whether a search found it
  /// in this frame.
  BodyResult track(const Frame& frame, double* track_ms = nullptr, bool* found_again = nullptr);

  /// This tracker as run_sequence drives it.
  RunTracker as_run_tracker();
  /// The tracker itself (its costs, its cues' diagnostics).
  Tracker& tracker() { return *tracker_; }

 private:
  std::unique_ptr<Tracker> tracker_;
  Recovery recovery_;
  std::string body_name_;
};

/// evaluate_sequence of icgp's tracker built from `config`, started at `start_pose`.
TrackingEvaluation evaluate_tracker(const FrameSource& frames, const std::string& body, const Mesh& mesh,
                                    const TrackerConfig& config, const Pose& start_pose);

}  // namespace icgp
