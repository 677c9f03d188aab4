// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/servo/servo_sweep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "icgp/eval/gnuplot.h"
#include "icgp/eval/json_object.h"
#include "icgp/eval/metrics.h"
#include "icgp/io/yaml_reader.h"

namespace icgp::servo {
namespace {

/// The most values one sweep takes: each is a whole batch of trials.
constexpr std::size_t kMaxSweepValues = 1000;

/// The rows of `values`, in order.
std::vector<const SweepRow*> all_rows(const std::vector<SweepValue>& values) {
  std::vector<const SweepRow*> rows;
  for (const SweepValue& v : values)
    for (const SweepRow& row : v.rows) rows.push_back(&row);
  return rows;
}

/// The trackers of the rows, in the order they first appear.
std::vector<std::string> trackers_of(const std::vector<SweepValue>& values) {
  std::vector<std::string> names;
  for (const SweepRow* row : all_rows(values))
    if (std::find(names.begin(), names.end(), row->summary.tracker) == names.end())
      names.push_back(row->summary.tracker);
  return names;
}

}  // namespace

SweepSpec parse_sweep(const std::string& text) {
  const std::string::size_type equals = text.find('=');
  if (equals == std::string::npos || equals == 0)
    throw std::invalid_argument("--sweep: expected FIELD=V1,V2,... (a scenario field and its values), got '" + text +
                                "'");
  SweepSpec sweep;
  sweep.field = text.substr(0, equals);
  std::stringstream list(text.substr(equals + 1));
  std::string item;
  while (std::getline(list, item, ',')) {
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !std::isfinite(value))
      throw std::invalid_argument("--sweep " + sweep.field + ": expected a list of numbers, got '" + item + "'");
    sweep.values.push_back(value);
  }
  if (sweep.values.empty()) throw std::invalid_argument("--sweep " + sweep.field + ": no values given");
  if (sweep.values.size() > kMaxSweepValues)
    throw std::invalid_argument("--sweep " + sweep.field + ": " + std::to_string(sweep.values.size()) +
                                " values, more than the " + std::to_string(kMaxSweepValues) + " a sweep takes");
  return sweep;
}

SweepValue sweep_value(double value, const std::vector<std::vector<ServoResult>>& runs_by_tracker,
                       const Scenario& scenario, bool interrupted) {
  SweepValue out;
  out.value = value;
  for (const std::vector<ServoResult>& runs : runs_by_tracker) {
    if (runs.empty()) continue;
    SweepRow row;
    row.value = value;
    row.summary = summarise(runs, scenario.stop);
    // Only icgp detects; the others' names start with theirs (PoseEstimator::name).
    const bool icgp = row.summary.tracker.rfind(name_of(TrackerKind::kIcgp, tracker_names()), 0) == 0;
    row.starts_from_truth = !icgp || !scenario.tracker.init_by_detection;
    row.summary.interrupted = row.summary.interrupted || interrupted;
    std::vector<double> final_t, final_r;
    for (const ServoResult& r : runs) {
      final_t.push_back(r.final_t);
      final_r.push_back(r.final_r);
    }
    row.final_t_p95 = percentile(final_t, 0.95);
    row.final_r_p95 = percentile(final_r, 0.95);
    out.rows.push_back(row);
  }
  return out;
}

SweepValue run_sweep_value(const std::string& scenario_file, const std::string& models_dir, const SweepSpec& sweep,
                           std::size_t index, const std::vector<TrackerKind>& trackers, int trials, unsigned seed,
                           std::optional<RendererKind> renderer, const RunDone& on_run) {
  SweepValue out;
  out.value = sweep.values.at(index);
  try {
    Scenario scenario = load_scenario(scenario_file, models_dir, {{sweep.field, out.value}});
    if (seed != 0) scenario.seed = seed;
    if (renderer) scenario.camera.renderer = *renderer;
    std::string failures;
    const TrialBatch batch =
        run_trials(scenario, trackers, trials, on_run, {}, [&](int trial, TrackerKind tracker, const std::exception& e) {
          failures += (failures.empty() ? "" : "; ") + std::string("trial ") + std::to_string(trial + 1) + " (" +
                      name_of(tracker, tracker_names()) + "): " + e.what();
        });
    out = sweep_value(out.value, batch.runs, scenario, batch.interrupted);
    out.error = failures;
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  return out;
}

void print_sweep(std::ostream& out, const SweepSpec& sweep, const std::vector<SweepValue>& values) {
  char line[256];
  std::snprintf(line, sizeof line, "%14s  %-34s %-6s %6s %8s %19s %19s\n", sweep.field.c_str(), "tracker", "start",
                "trials", "success", "final mm med/p95", "final deg med/p95");
  out << line;
  for (const SweepValue& v : values) {
    for (const SweepRow& row : v.rows) {
      const TrialsSummary& s = row.summary;
      std::snprintf(line, sizeof line, "%14s  %-34s %-6s %6d %7.1f%% %9.3f / %-7.3f %9.3f / %-7.3f\n",
                    yaml::plain_number(v.value).c_str(), s.tracker.c_str(), row.starts_from_truth ? "truth" : "detect",
                    s.trials, 100.0 * s.success_rate,
                    1e3 * s.final_t_median, 1e3 * row.final_t_p95, s.final_r_median / kDegree, row.final_r_p95 / kDegree);
      out << line;
    }
    if (!v.error.empty()) out << yaml::plain_number(v.value) << ": " << v.error << "\n";
  }
}

void write_sweep_json(const SweepSpec& sweep, const std::vector<SweepValue>& values, const std::string& path) {
  std::vector<JsonObject> rows, errors;
  for (const SweepValue& v : values) {
    for (const SweepRow& row : v.rows)
      rows.push_back(JsonObject()
                         .add("value", row.value)
                         .add("final_t_mm_p95", 1e3 * row.final_t_p95)
                         .add("final_r_deg_p95", row.final_r_p95 / kDegree)
                         .add("starts_from_truth", row.starts_from_truth)
                         .add_fields(summary_json(row.summary)));
    if (!v.error.empty()) errors.push_back(JsonObject().add("value", v.value).add("error", v.error));
  }
  std::vector<JsonObject> swept;
  for (double value : sweep.values) swept.push_back(JsonObject().add("value", value));
  JsonObject().add("field", sweep.field).add("values", swept).add("rows", rows).add("errors", errors).write(path);
}

void plot_sweep(const SweepSpec& sweep, const std::vector<SweepValue>& values, const std::string& dir) {
  namespace fs = std::filesystem;
  const fs::path folder(dir);
  std::string s = gnuplot_png_preamble("icgp servo --sweep", "gnuplot sweep_plot.gp (in this folder)", 900, 700);
  const std::vector<std::string> trackers = trackers_of(values);
  // One datablock per tracker: value, success %, final mm median, final mm p95.
  for (std::size_t k = 0; k < trackers.size(); ++k) {
    s += "$t" + std::to_string(k) + " << EOD\n";
    for (const SweepRow* row : all_rows(values))
      if (row->summary.tracker == trackers[k]) {
        char line[160];
        std::snprintf(line, sizeof line, "%.9g %.9g %.9g %.9g\n", row->value, 100.0 * row->summary.success_rate,
                      1e3 * row->summary.final_t_median, 1e3 * row->final_t_p95);
        s += line;
      }
    s += "EOD\n";
  }
  // Plain text (field names have underscores); the legends under the plots, whose width
  // long tracker names would otherwise take.
  s += "set output 'sweep.png'\nset termoption noenhanced\nset multiplot layout 2,1\nset key below\n";
  s += "set xlabel '" + sweep.field + "'\nset ylabel 'success (%)'\nset yrange [0:105]\nplot ";
  for (std::size_t k = 0; k < trackers.size(); ++k)
    s += std::string(k ? ", " : "") + "$t" + std::to_string(k) + " using 1:2 with linespoints lw 2 title '" +
         trackers[k] + "'";
  s += "\nset ylabel 'final error (mm)'\nset autoscale y\nset logscale y\nplot ";
  for (std::size_t k = 0; k < trackers.size(); ++k)
    s += std::string(k ? ", " : "") + "$t" + std::to_string(k) + " using 1:3 with linespoints lw 2 lc " +
         std::to_string(k + 1) + " title '" + trackers[k] + " median', $t" + std::to_string(k) +
         " using 1:4 with linespoints dt 2 lc " + std::to_string(k + 1) + " title '" + trackers[k] + " p95'";
  s += "\nunset multiplot\n";
  std::error_code error;
  fs::create_directories(folder, error);
  if (error) throw std::runtime_error("cannot create plot folder '" + dir + "': " + error.message());
  draw_with_gnuplot(s, folder / "sweep_plot.gp", {folder / "sweep.png"});
}

}  // namespace icgp::servo
