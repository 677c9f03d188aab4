// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/eval/single_body_tracker.h"

#include <chrono>
#include <stdexcept>
#include <utility>

#include "icgp/tracker/tracker_builder.h"

namespace icgp {

SingleBodyTracker::SingleBodyTracker(const TrackerConfig& config, const Mesh& mesh, const std::string& body_name)
    : tracker_(build_tracker(config, mesh, body_name)),
      recovery_(*tracker_, config, body_name, configured_cameras(config)),
      body_name_(body_name) {}

void SingleBodyTracker::start(const Frame& frame, const Pose& reference_T_body) {
  tracker_->body(body_name_).reference_T_body = reference_T_body;
  tracker_->start(frame);
  recovery_.reset();
}

BodyResult SingleBodyTracker::track(const Frame& frame, double* track_ms, bool* found_again) {
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

RunTracker SingleBodyTracker::as_run_tracker() {
  return {[this](const Frame& frame, const Pose& pose) { start(frame, pose); },
          [this](const Frame& frame) {
            double ms = 0.0;
            const BodyResult result = track(frame, &ms);
            return TrackedFrame::of(result, ms);
          }};
}

TrackingEvaluation evaluate_tracker(const FrameSource& frames, const std::string& body, const Mesh& mesh,
                                    const TrackerConfig& config, const Pose& start_pose) {
  SingleBodyTracker tracker(config, mesh, body);
  return evaluate_sequence(frames, body, mesh, tracker.as_run_tracker(), start_pose);
}

}  // namespace icgp
