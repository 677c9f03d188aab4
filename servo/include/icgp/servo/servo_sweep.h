// SPDX-License-Identifier: GPL-2.0-or-later
// Robustness envelopes: batch trials repeated over the values of one scenario field.
#pragma once

#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "icgp/servo/scenario.h"
#include "icgp/servo/servo_batch.h"
#include "icgp/servo/servo_report.h"

namespace icgp::servo {

/// `icgp servo --sweep FIELD=V1,V2,...`: a numeric scenario field and the values it takes.
struct SweepSpec {
  std::string field;
  std::vector<double> values;
};

/// Reads "FIELD=V1,V2,..." (at least one value, each a finite number, at most 1000 values).
/// Throws std::invalid_argument naming what is wrong; the field itself is checked when the
/// scenario is read with it (load_scenario with overrides).
SweepSpec parse_sweep(const std::string& text);

/// One tracker's trials at one value of the swept field.
struct SweepRow {
  double value = 0.0;
  TrialsSummary summary;
  double final_t_p95 = 0.0;  ///< metres, over the trials
  double final_r_p95 = 0.0;  ///< radians
  /// The tracker started from the true pose rather than by detection: ViSP's tracker and the
  /// oracle always, icgp with `tracker.init: truth`. Its row is then no test of the start.
  bool starts_from_truth = false;
};

/// What happened at one value: a row per tracker, or the error that stopped its trials.
struct SweepValue {
  double value = 0.0;
  std::vector<SweepRow> rows;
  std::string error;  ///< why its trials did not run (empty: they did)
};

/// The rows of the runs at one value: runs_by_tracker[k] are tracker k's runs (trials in
/// index order) of `scenario`, judged against its stop thresholds; `interrupted` marks a
/// batch a stop request cut short.
SweepValue sweep_value(double value, const std::vector<std::vector<ServoResult>>& runs_by_tracker,
                       const Scenario& scenario, bool interrupted);

/// The rows at one value of `sweep`: the scenario read with the field set to it, then its
/// trials with every tracker of `trackers` on the same seeded starts at every value (the
/// scenario's seed, or `seed` when not 0), rendered with `renderer` when given (the
/// scenario's camera.renderer otherwise). `on_run` reports each run as run_trials does.
/// A value whose scenario cannot be read (a value out of the field's range) or whose trials
/// throw gives a SweepValue with its error, and the next value runs.
SweepValue run_sweep_value(const std::string& scenario_file, const std::string& models_dir, const SweepSpec& sweep,
                           std::size_t index, const std::vector<TrackerKind>& trackers, int trials, unsigned seed,
                           std::optional<RendererKind> renderer, const RunDone& on_run);

/// The table: value, tracker, how it started (detect or truth), success rate, final error
/// median / p95 (mm, deg).
void print_sweep(std::ostream& out, const SweepSpec& sweep, const std::vector<SweepValue>& values);
/// sweep.json: {"field", "values": [...], "rows": [{"value", "p95": {...}, summary...}],
/// "errors": [{"value", "error"}]}; written after every value, so a stopped sweep keeps
/// what it computed.
void write_sweep_json(const SweepSpec& sweep, const std::vector<SweepValue>& values, const std::string& path);
/// sweep.png in `dir`: the success rate, and the final error's median and p95, against the
/// value, per tracker (gnuplot; its script sweep_plot.gp beside it).
void plot_sweep(const SweepSpec& sweep, const std::vector<SweepValue>& values, const std::string& dir);

}  // namespace icgp::servo
