// SPDX-License-Identifier: GPL-2.0-or-later
// icgp's tracker on one body, with the same start/track shape and the same timing rule as
// the ViSP baseline (icgp::VispRgbdTracker), so the commands treat both alike. A lost body
// is searched for again (Recovery) when the configuration's detection.recovery is on.
#pragma once

#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>

#include "icgp/detection/recovery.h"
#include "icgp/tracker/tracker.h"
#include "icgp/tracker/tracker_builder.h"

namespace icgp::app {

class TimedIcgTracker {
 public:
  TimedIcgTracker(const TrackerConfig& config, const Mesh& mesh, const std::string& body_name)
      : tracker_(build_tracker(config, mesh, body_name)),
        recovery_(*tracker_, config, body_name, configured_cameras(config)),
        body_name_(body_name) {}

  /// Puts the body at `reference_T_body` and starts every modality on `frame`.
  void start(const Frame& frame, const Pose& reference_T_body) {
    tracker_->body(body_name_).reference_T_body = reference_T_body;
    tracker_->start(frame);
    recovery_.reset();
  }
  /// Detects the body in `frame` and, when found, starts there.
  Detection start_by_detection(const Frame& frame) { return recovery_.initialise(frame); }

  /// Tracks one frame, searching again for a lost body; `track_ms` receives the duration
  /// of Tracker::track and of the search alone. `found_again`: whether a search found it
  /// in this frame.
  BodyResult track(const Frame& frame, double* track_ms = nullptr, bool* found_again = nullptr) {
    const auto begin = std::chrono::steady_clock::now();
    std::vector<BodyResult> results = tracker_->track(frame);
    const bool found = !recovery_.after_track(frame, results).empty();
    const auto end = std::chrono::steady_clock::now();
    if (track_ms) *track_ms = std::chrono::duration<double, std::milli>(end - begin).count();
    if (found_again) *found_again = found;
    for (BodyResult& result : results)
      if (result.body == body_name_) return std::move(result);
    throw std::logic_error("the tracker reported no result for body '" + body_name_ + "'");
  }

 private:
  std::unique_ptr<Tracker> tracker_;
  Recovery recovery_;
  std::string body_name_;
};

}  // namespace icgp::app
