// SPDX-License-Identifier: GPL-2.0-or-later
// icgp's tracker on one body, with the same start/track shape and the same timing rule as
// the ViSP baseline (icgp::VispRgbdTracker), so the commands treat both alike.
#pragma once

#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>

#include "icgp/tracker/tracker.h"
#include "icgp/tracker/tracker_builder.h"

namespace icgp::app {

class TimedIcgTracker {
 public:
  TimedIcgTracker(const TrackerConfig& config, const Mesh& mesh, const std::string& body_name)
      : tracker_(build_tracker(config, mesh, body_name)), body_name_(body_name) {}

  /// Puts the body at `reference_T_body` and starts every modality on `frame`.
  void start(const Frame& frame, const Pose& reference_T_body) {
    tracker_->body(body_name_).reference_T_body = reference_T_body;
    tracker_->start(frame);
  }

  /// Tracks one frame; `track_ms` receives the duration of Tracker::track alone.
  BodyResult track(const Frame& frame, double* track_ms = nullptr) {
    const auto begin = std::chrono::steady_clock::now();
    std::vector<BodyResult> results = tracker_->track(frame);
    const auto end = std::chrono::steady_clock::now();
    if (track_ms) *track_ms = std::chrono::duration<double, std::milli>(end - begin).count();
    for (BodyResult& result : results)
      if (result.body == body_name_) return std::move(result);
    throw std::logic_error("the tracker reported no result for body '" + body_name_ + "'");
  }

 private:
  std::unique_ptr<Tracker> tracker_;
  std::string body_name_;
};

}  // namespace icgp::app
