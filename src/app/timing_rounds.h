// SPDX-License-Identifier: GPL-2.0-or-later
// Timing several trackers on a machine whose speed drifts: rounds in alternating order, and
// speed ratios taken within a round.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "icgp/eval/metrics.h"
#include "text_table.h"

namespace icgp::app {

/// One tracker configuration run over a command's frames.
struct TimedJob {
  std::string name;
  std::function<TrackingSummary()> run;
};

/// A job's result: the errors of its first round (the trackers are deterministic, so every
/// round gives the same poses) with median_ms and hz over all rounds, and each round's
/// median time.
struct TimedRow {
  std::string name;
  TrackingSummary summary;
  std::vector<double> round_ms;
};

/// Runs every job `rounds` times, in reverse order every other round, with a progress line
/// per run on stderr. Load from elsewhere on the machine comes and goes over seconds, so
/// rounds share it out between the jobs. Rows come in the jobs' order; a job that throws is
/// named in `failures` and not run again.
std::vector<TimedRow> run_rounds(const std::vector<TimedJob>& jobs, int rounds, int n_frames,
                                 std::vector<std::string>& failures);

/// The median over the rounds both rows ran of `per_round(a's median, b's median)` in that
/// round. NaN without a common round or without one of the rows (nullptr).
double median_over_rounds(const TimedRow* a, const TimedRow* b, const std::function<double(double, double)>& per_round);

/// How many times faster `row` is than `reference` (nullptr: NaN): the median over rounds
/// of the ratio of their medians in the same round.
double speed_ratio(const TimedRow* reference, const TimedRow& row);

/// The row named `name`, or nullptr.
const TimedRow* find_row(const std::vector<TimedRow>& rows, const std::string& name);

/// After the table: throws naming the configurations that failed, if any.
void throw_if_failed(const std::vector<std::string>& failures);

/// "median ms", "Hz" and "speed vs ViSP": the columns of timing_cells.
std::vector<TableColumn> timing_columns();
/// Appends `row`'s median ms, Hz and speed against `reference` to the table's row and ends it.
void timing_cells(TextTable& table, const TimedRow& row, const TimedRow* reference);

}  // namespace icgp::app
