// SPDX-License-Identifier: GPL-2.0-or-later
#include "timing_rounds.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <limits>
#include <optional>
#include <stdexcept>

namespace icgp::app {

std::vector<TimedRow> run_rounds(const std::vector<TimedJob>& jobs, int rounds, int n_frames,
                                 std::vector<std::string>& failures) {
  std::vector<std::optional<TimedRow>> results(jobs.size());
  std::vector<bool> failed(jobs.size(), false);
  for (int round = 0; round < rounds; ++round) {
    for (std::size_t k = 0; k < jobs.size(); ++k) {
      const std::size_t j = round % 2 == 0 ? k : jobs.size() - 1 - k;
      if (failed[j]) continue;
      std::fprintf(stderr, "[round %d/%d, %zu/%zu] %s ...", round + 1, rounds, k + 1, jobs.size(), jobs[j].name.c_str());
      std::fflush(stderr);
      const auto begin = std::chrono::steady_clock::now();
      // A tracker that cannot run (no EGL for model generation, say) must not cost the
      // others' results: it is reported and the command fails at the end.
      TrackingSummary summary;
      try {
        summary = jobs[j].run();
      } catch (const std::exception& e) {
        std::fprintf(stderr, " failed: %s\n", e.what());
        failures.push_back(jobs[j].name);
        failed[j] = true;
        continue;
      }
      if (!results[j]) results[j] = TimedRow{jobs[j].name, summary, {}};
      results[j]->round_ms.push_back(summary.median_ms);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
      std::fprintf(stderr, " %d frames in %.1f s (including set-up), median %.2f ms\n", n_frames, seconds,
                   summary.median_ms);
    }
  }
  std::vector<TimedRow> rows;
  for (std::optional<TimedRow>& row : results) {
    if (!row) continue;
    row->summary.median_ms = median(row->round_ms);
    row->summary.hz = 1000.0 / row->summary.median_ms;
    rows.push_back(std::move(*row));
  }
  return rows;
}

double median_over_rounds(const TimedRow* a, const TimedRow* b, const std::function<double(double, double)>& per_round) {
  std::vector<double> values;
  if (a && b)
    for (std::size_t r = 0; r < std::min(a->round_ms.size(), b->round_ms.size()); ++r)
      values.push_back(per_round(a->round_ms[r], b->round_ms[r]));
  return values.empty() ? std::numeric_limits<double>::quiet_NaN() : median(values);
}

double speed_ratio(const TimedRow* reference, const TimedRow& row) {
  return median_over_rounds(reference, &row, [](double reference_ms, double row_ms) { return reference_ms / row_ms; });
}

const TimedRow* find_row(const std::vector<TimedRow>& rows, const std::string& name) {
  for (const TimedRow& row : rows)
    if (row.name == name) return &row;
  return nullptr;
}

void throw_if_failed(const std::vector<std::string>& failures) {
  if (failures.empty()) return;
  std::string names;
  for (const std::string& name : failures) names += (names.empty() ? "" : ", ") + name;
  throw std::runtime_error(std::to_string(failures.size()) + " configuration(s) failed: " + names);
}

std::vector<TableColumn> timing_columns() { return {{"median ms", 10}, {"Hz", 8}, {"speed vs ViSP", 14}}; }

void timing_cells(TextTable& table, const TimedRow& row, const TimedRow* reference) {
  table.number(row.summary.median_ms, 2).number(row.summary.hz, 0).ratio(speed_ratio(reference, row)).end_row();
}

}  // namespace icgp::app
