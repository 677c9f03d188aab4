// SPDX-License-Identifier: GPL-2.0-or-later
// The one loop that runs a tracker over a sequence: every command, benchmark, ViSP program
// and binding that tracks a sequence goes through run_sequence, so that they start, time and
// evaluate a tracker alike.
#pragma once

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "icgp/base/frame.h"
#include "icgp/base/mesh.h"
#include "icgp/base/pose.h"
#include "icgp/eval/metrics.h"
#include "icgp/tracker/tracker.h"

namespace icgp {

class Sequence;

/// What a tracker reports for its body after one frame.
struct TrackedFrame {
  Pose reference_T_body;
  /// Whether the tracker holds the body as tracked. vpMbGenericTracker has no such flag: a
  /// frame it tracks without throwing counts as tracked.
  bool tracked = true;
  double quality = std::numeric_limits<double>::quiet_NaN();
  double ms = 0.0;  ///< the tracking call alone, not loading or converting the frame

  /// An icgp tracker's result for the body, which took `ms`.
  static TrackedFrame of(const BodyResult& result, double ms) {
    return {result.reference_T_body, result.tracked, result.quality, ms};
  }
};

/// A tracker as a run drives it: `start` puts the body at a pose on the first frame and
/// starts the tracker there; `track` tracks one frame.
struct RunTracker {
  std::function<void(const Frame& first, const Pose& reference_T_body)> start;
  std::function<TrackedFrame(const Frame&)> track;
};

/// The frames of a run, read one at a time in order. The sources below keep the sequence or
/// the frames by reference: they must outlive the run. A frame `load` returns stays valid
/// until the next call (frames in memory are not copied; a sequence's are read into one
/// frame the source holds).
struct FrameSource {
  int count = 0;
  std::function<const Frame&(int index)> load;

  /// The first `count` frames of `sequence` (all of them when count < 0 or beyond its end).
  static FrameSource of(const Sequence& sequence, int count = -1);
  /// Every frame of `sequence`, its first one read already as `first`.
  static FrameSource of(const Sequence& sequence, const Frame& first);
  /// Frames already in memory.
  static FrameSource of(const std::vector<Frame>& frames);
};

/// Loads each frame, starts the tracker on the first at `start_pose` (none: the tracker finds
/// the body itself, e.g. by detection, and `tracker.start` is not called), tracks every frame
/// with the first included, as ViSP's programs do after initFromPose, and hands each frame
/// and its outcome to `on_frame`. A stop request (SIGINT under install_stop_on_sigint) ends
/// it before the next frame with StopRequested.
void run_sequence(const FrameSource& frames, const RunTracker& tracker, const std::optional<Pose>& start_pose,
                  const std::function<void(const Frame&, const TrackedFrame&)>& on_frame);

/// Sees each frame of evaluate_sequence with its outcome and its evaluation.
using EvaluatedFrameObserver = std::function<void(const Frame&, const TrackedFrame&, const FrameEvaluation&)>;

/// run_sequence, with the pose of `body` evaluated against each frame's ground truth (ADD and
/// ADD-S on `mesh`).
TrackingEvaluation evaluate_sequence(const FrameSource& frames, const std::string& body, const Mesh& mesh,
                                     const RunTracker& tracker, const std::optional<Pose>& start_pose,
                                     const EvaluatedFrameObserver& on_frame = nullptr);

}  // namespace icgp
