// SPDX-License-Identifier: GPL-2.0-or-later
// Batch trials: runs of a scenario from seeded random starts, with one tracker or several
// compared on identical trials, stoppable between and within runs.
#pragma once

#include <exception>
#include <functional>
#include <vector>

#include "icgp/servo/scenario.h"
#include "icgp/servo/servo_run.h"

namespace icgp::servo {

/// The runs of a batch, only of trials every tracker finished.
struct TrialBatch {
  std::vector<std::vector<ServoResult>> runs;  ///< runs[k][i]: tracker k of the batch, trial i
  int trials_done = 0;
  bool interrupted = false;  ///< a stop request ended the batch before all its trials
};

/// Called after each finished run with the index of its trial.
using RunDone = std::function<void(int trial, const ServoResult& run)>;
/// Called for a run that threw, with its trial, its tracker and what it threw.
using RunFailed = std::function<void(int trial, TrackerKind tracker, const std::exception& error)>;

/// Runs trial `trial` of a batch of `scenario` with `tracker`: from
/// perturbed_start(scenario.trials, scenario.seed, trial) with the noise seed
/// scenario.seed + trial, no progress line. `run` holds the other options (on_step, ...).
/// run_trials runs its trials with it; so can a process that runs some trials of a batch
/// (a Dask worker), with the same results.
ServoResult run_trial(const Scenario& scenario, TrackerKind tracker, int trial, ServoRunOptions run = {});

/// Runs `trials` trials of `scenario` with each of `trackers`. Trial i starts at
/// perturbed_start(scenario.trials, scenario.seed, i) with the noise seed scenario.seed + i,
/// the same for every tracker. Every tracker runs trial i before any runs trial i + 1, so a
/// batch stopped early still compares the trackers on identical trials, and a time estimate
/// made after any run averages over all trackers. A stop request (icgp::stop_requested())
/// ends the batch before the next run, or within a run at its next step; the trial it cut
/// short is left out. `each_run` holds the options of every run (on_step: a live view,
/// tests); its start_offset, seed and progress are the trial's. With `on_failure`, a run
/// that throws is reported to it and its trial left out for every tracker, and the batch goes
/// on; without, the exception ends the batch.
TrialBatch run_trials(const Scenario& scenario, const std::vector<TrackerKind>& trackers, int trials,
                      const RunDone& on_run = {}, const ServoRunOptions& each_run = {},
                      const RunFailed& on_failure = {});

}  // namespace icgp::servo
