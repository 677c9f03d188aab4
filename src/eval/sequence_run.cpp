// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/eval/sequence_run.h"

#include <algorithm>
#include <memory>

#include "icgp/base/stop_request.h"
#include "icgp/eval/sequence.h"

namespace icgp {

FrameSource FrameSource::of(const Sequence& sequence, int count) {
  const int n = count < 0 ? sequence.size() : std::min(count, sequence.size());
  auto read = std::make_shared<Frame>();
  return {n, [&sequence, read](int index) -> const Frame& { return *read = sequence.load(index); }};
}

FrameSource FrameSource::of(const Sequence& sequence, const Frame& first) {
  auto read = std::make_shared<Frame>();
  return {sequence.size(), [&sequence, &first, read](int index) -> const Frame& {
            return index == 0 ? first : *read = sequence.load(index);
          }};
}

FrameSource FrameSource::of(const std::vector<Frame>& frames) {
  return {static_cast<int>(frames.size()),
          [&frames](int index) -> const Frame& { return frames[static_cast<std::size_t>(index)]; }};
}

void run_sequence(const FrameSource& frames, const RunTracker& tracker, const std::optional<Pose>& start_pose,
                  const std::function<void(const Frame&, const TrackedFrame&)>& on_frame) {
  for (int i = 0; i < frames.count; ++i) {
    if (stop_requested()) throw StopRequested("stopped on request before frame " + std::to_string(i));
    const Frame& frame = frames.load(i);
    if (i == 0 && start_pose) tracker.start(frame, *start_pose);
    const TrackedFrame outcome = tracker.track(frame);
    if (on_frame) on_frame(frame, outcome);
  }
}

TrackingEvaluation evaluate_sequence(const FrameSource& frames, const std::string& body, const Mesh& mesh,
                                     const RunTracker& tracker, const std::optional<Pose>& start_pose,
                                     const EvaluatedFrameObserver& on_frame) {
  TrackingEvaluation evaluation(mesh);
  run_sequence(frames, tracker, start_pose, [&](const Frame& frame, const TrackedFrame& outcome) {
    const Pose* truth = frame.truth(body);
    const FrameEvaluation& e = evaluation.add(frame.index, outcome.reference_T_body,
                                              truth ? std::optional<Pose>(*truth) : std::nullopt, outcome.tracked,
                                              outcome.ms, outcome.quality);
    if (on_frame) on_frame(frame, outcome, e);
  });
  return evaluation;
}

}  // namespace icgp
