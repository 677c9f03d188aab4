// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/servo/servo_batch.h"

#include <utility>

#include "icgp/base/stop_request.h"

namespace icgp::servo {

ServoResult run_trial(const Scenario& scenario, TrackerKind tracker, int trial, ServoRunOptions run) {
  Scenario s = scenario;
  s.tracker.kind = tracker;
  run.seed = scenario.seed + static_cast<unsigned>(trial);
  run.start_offset = perturbed_start(scenario.trials, scenario.seed, trial);
  run.progress = false;  // a batch reports per run instead (RunDone)
  return run_servo(s, run);
}

TrialBatch run_trials(const Scenario& scenario, const std::vector<TrackerKind>& trackers, int trials,
                      const RunDone& on_run, const ServoRunOptions& each_run, const RunFailed& on_failure) {
  TrialBatch batch;
  batch.runs.resize(trackers.size());
  for (int i = 0; i < trials; ++i) {
    std::vector<ServoResult> trial;
    for (const TrackerKind tracker : trackers) {
      // Between runs here; within a run, run_servo polls at every step.
      if (stop_requested()) {
        batch.interrupted = true;
        return batch;
      }
      try {
        trial.push_back(run_trial(scenario, tracker, i, each_run));
      } catch (const std::exception& error) {
        if (!on_failure) throw;
        on_failure(i, tracker, error);
        break;
      }
      if (trial.back().interrupted) {
        batch.interrupted = true;
        return batch;
      }
      if (on_run) on_run(i, trial.back());
    }
    if (trial.size() < trackers.size()) continue;  // a run threw: the trial is left out
    for (std::size_t k = 0; k < trackers.size(); ++k) batch.runs[k].push_back(std::move(trial[k]));
    ++batch.trials_done;
  }
  return batch;
}

}  // namespace icgp::servo
