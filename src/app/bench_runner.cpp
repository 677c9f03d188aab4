// SPDX-License-Identifier: GPL-2.0-or-later
#include "bench_runner.h"

#include <stdexcept>
#include <optional>

namespace icgp::app {

TrackingSummary run_configuration(const std::vector<Frame>& frames, const std::string& body, const Mesh& mesh,
                                  const StartFunction& start, const TrackFunction& track) {
  return evaluate_configuration(frames, body, mesh, start, track).summary();
}

TrackingEvaluation evaluate_configuration(const std::vector<Frame>& frames, const std::string& body, const Mesh& mesh,
                                          const StartFunction& start, const TrackFunction& track) {
  TrackingEvaluation evaluation(mesh);
  start(frames.front(), *frames.front().truth(body));
  for (const Frame& frame : frames) {
    double ms = 0.0;
    const TrackedPose result = track(frame, &ms);
    const Pose* truth = frame.truth(body);
    evaluation.add(frame.index, result.reference_T_body, truth ? std::optional<Pose>(*truth) : std::nullopt,
                   result.tracked, ms);
  }
  return evaluation;
}

TrackingSummary run_icgp(const std::vector<Frame>& frames, const std::string& body, const Mesh& mesh,
                         const TrackerConfig& config) {
  return evaluate_icgp(frames, body, mesh, config).summary();
}

TrackingEvaluation evaluate_icgp(const std::vector<Frame>& frames, const std::string& body, const Mesh& mesh,
                                 const TrackerConfig& config) {
  TimedIcgTracker tracker(config, mesh, body);
  return evaluate_configuration(
      frames, body, mesh, [&](const Frame& f, const Pose& pose) { tracker.start(f, pose); },
      [&](const Frame& f, double* ms) {
        const BodyResult r = tracker.track(f, ms);
        return TrackedPose{r.reference_T_body, r.tracked};
      });
}

TrackingSummary summarise_visp_run(const std::vector<Frame>& frames, const std::string& body, const Mesh& mesh,
                                   const RgbdRun& run) {
  TrackingEvaluation evaluation(mesh);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const Pose* truth = frames[i].truth(body);
    evaluation.add(frames[i].index, run.poses[i], truth ? std::optional<Pose>(*truth) : std::nullopt, true,
                   run.track_ms[i]);
  }
  return evaluation.summary();
}

void throw_if_failed(const std::vector<std::string>& failures) {
  if (failures.empty()) return;
  std::string names;
  for (const std::string& name : failures) names += (names.empty() ? "" : ", ") + name;
  throw std::runtime_error(std::to_string(failures.size()) + " configuration(s) failed: " + names);
}

}  // namespace icgp::app
