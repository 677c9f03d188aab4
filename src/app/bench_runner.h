// SPDX-License-Identifier: GPL-2.0-or-later
// Runs one tracker over a sequence's frames the way every bench row does: start at the
// first frame's ground truth, track every frame, time only the tracking call.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "icgp/eval/metrics.h"
#include "icgp/visp/rgbd_tracking_loop.h"
#include "timed_icg_tracker.h"

namespace icgp::app {

/// What every tracker reports per frame. vpMbGenericTracker has no tracked flag (it throws
/// when it fails), so its frames count as tracked.
struct TrackedPose {
  Pose reference_T_body;
  bool tracked = true;
};
using StartFunction = std::function<void(const Frame&, const Pose&)>;
using TrackFunction = std::function<TrackedPose(const Frame&, double* ms)>;

TrackingSummary run_configuration(const std::vector<Frame>& frames, const std::string& body, const Mesh& mesh,
                                  const StartFunction& start, const TrackFunction& track);
/// The same run with every frame's errors kept (TrackingEvaluation::frames()).
TrackingEvaluation evaluate_configuration(const std::vector<Frame>& frames, const std::string& body, const Mesh& mesh,
                                          const StartFunction& start, const TrackFunction& track);

/// run_configuration for icgp's tracker built from `config`.
TrackingSummary run_icgp(const std::vector<Frame>& frames, const std::string& body, const Mesh& mesh,
                         const TrackerConfig& config);
/// evaluate_configuration for icgp's tracker built from `config`.
TrackingEvaluation evaluate_icgp(const std::vector<Frame>& frames, const std::string& body, const Mesh& mesh,
                                 const TrackerConfig& config);

/// Errors against the ground truth and timing of the track() calls of a run through the
/// ViSP API (track_visp_sequence), every frame counted as tracked.
TrackingSummary summarise_visp_run(const std::vector<Frame>& frames, const std::string& body, const Mesh& mesh,
                                   const RgbdRun& run);

/// After the table: throws naming the configurations that failed, if any.
void throw_if_failed(const std::vector<std::string>& failures);

}  // namespace icgp::app
