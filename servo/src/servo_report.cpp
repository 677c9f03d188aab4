// SPDX-License-Identifier: GPL-2.0-or-later
// Servo run reports: summaries of batch trials (text and JSON), the per-step CSV log and the
// gnuplot figures. Only needs the ServoResult / ServoStep structs: no rendering, no tracker.
#include "icgp/servo/servo_report.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <system_error>
#include <utility>
#include <visp3/core/vpThetaUVector.h>

#include "icgp/base/pose.h"
#include "icgp/eval/gnuplot.h"
#include "icgp/eval/json_object.h"
#include "icgp/eval/metrics.h"

namespace icgp::servo {

namespace {

constexpr double kMm = 1000.0;            // metres -> millimetres
constexpr double kMs = 1000.0;            // seconds -> milliseconds
constexpr double kDeg = 180.0 / kPi;      // radians -> degrees
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string format(const char* pattern, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* pattern, ...) {
  char buffer[512];
  va_list args;
  va_start(args, pattern);
  const int size = std::vsnprintf(buffer, sizeof buffer, pattern, args);
  va_end(args);
  if (size < 0) return {};
  if (static_cast<std::size_t>(size) < sizeof buffer) return std::string(buffer, static_cast<std::size_t>(size));
  std::string text(static_cast<std::size_t>(size) + 1, '\0');
  va_start(args, pattern);
  std::vsnprintf(text.data(), text.size(), pattern, args);
  va_end(args);
  text.resize(static_cast<std::size_t>(size));
  return text;
}

/// Creates the parent folder of `path` (when it has one); throws std::runtime_error naming
/// the folder and the file when that is impossible.
void create_parent_folder(const std::string& path) {
  const std::filesystem::path file(path);
  if (!file.has_parent_path()) return;
  std::error_code error;
  std::filesystem::create_directories(file.parent_path(), error);
  if (error)
    throw std::runtime_error("cannot create folder '" + file.parent_path().string() + "' for '" + path +
                             "': " + error.message());
}


// --- step data -------------------------------------------------------------------------

/// The number of velocity columns: the size of the first step's velocity (the first
/// non-empty one when the first steps have none, 6 — a camera twist — when none has any).
unsigned velocity_columns(const ServoResult& result) {
  for (const ServoStep& step : result.steps)
    if (step.velocity.size() > 0) return step.velocity.size();
  return 6;
}

double velocity_component(const ServoStep& step, unsigned i) {
  return i < step.velocity.size() ? step.velocity[i] : 0.0;
}

/// A number as it is, digit for digit (%.17g, which reads back to the same double): the
/// camera path a replay renders again.
std::string exact_number(double value) {
  if (!std::isfinite(value)) return data_number(value);
  return format("%.17g", value);
}

/// The camera pose columns of a step: wMc's translation (m) and θu rotation (rad).
void append_camera_pose(std::string& line, char separator, const vpHomogeneousMatrix& wMc) {
  const vpTranslationVector t = wMc.getTranslationVector();
  const vpThetaUVector tu(wMc.getRotationMatrix());
  for (double value : {t[0], t[1], t[2], tu[0], tu[1], tu[2]}) line += separator + exact_number(value);
}

/// The step table shared by the CSV and the plot data: one line per step, `separator`
/// between columns. Columns are only ever appended, so that readers of older logs keep
/// finding theirs.
std::string step_table(const ServoResult& result, char separator, bool header) {
  const unsigned n = velocity_columns(result);
  std::string out;
  if (header) {
    out += "time,servo_t_mm,servo_r_deg,track_t_mm,track_r_deg,error_norm";
    for (unsigned i = 0; i < n; ++i) out += ",v" + std::to_string(i);
    out += ",lost,safety_stop,dropped,render_ms,track_ms,control_ms,skipped,command_delay_ms";
    for (const char* name : kCameraPoseColumns) out += std::string(",") + name;
    out += "\n";
    if (separator != ',') std::replace(out.begin(), out.end(), ',', separator);
  }
  for (const ServoStep& step : result.steps) {
    std::string line = data_number(step.time);
    const auto column = [&line, separator](const std::string& text) { line += separator + text; };
    column(data_number(step.servo_t * kMm));
    column(data_number(step.servo_r * kDeg));
    column(data_number(step.track_t * kMm));
    column(data_number(step.track_r * kDeg));
    column(data_number(step.servo_error_norm));
    for (unsigned i = 0; i < n; ++i) column(data_number(velocity_component(step, i)));
    column(step.lost ? "1" : "0");
    column(step.safety_stop ? "1" : "0");
    column(step.dropped ? "1" : "0");
    column(data_number(step.render_ms));
    column(data_number(step.track_ms));
    column(data_number(step.control_ms));
    column(step.skipped ? "1" : "0");
    column(data_number(step.command_delay * kMs));
    append_camera_pose(line, separator, step.wMc_true);
    out += line + "\n";
  }
  return out;
}

/// The gnuplot script of plot_run, data included as a datablock so that the script alone
/// redraws the figures (`cd dir && gnuplot servo_plot.gp`).
std::string plot_script(const ServoResult& result) {
  const unsigned n = velocity_columns(result);
  // Columns of step_table: 1 time, 2 servo_t_mm, 3 servo_r_deg, 4 track_t_mm, 5 track_r_deg,
  // 6 error_norm, 7..6+n velocity, then lost, safety_stop, dropped, render, track, control ms,
  // skipped, command delay ms, and the camera pose (not plotted).
  const unsigned first_velocity = 7;
  const unsigned safety_column = first_velocity + n + 1;
  bool any_safety_stop = false, any_lost = false;
  for (const ServoStep& step : result.steps) {
    any_safety_stop = any_safety_stop || step.safety_stop;
    any_lost = any_lost || step.lost;
  }
  const unsigned lost_column = first_velocity + n;

  std::string title = result.scenario + " / " + result.tracker + " / seed " + std::to_string(result.seed);
  std::replace(title.begin(), title.end(), '"', '\'');

  std::string s;
  s += gnuplot_png_preamble("icgp servo (plot_run)", "gnuplot servo_plot.gp (in this folder)", 900, 600);
  s += "# Columns: time s, servo error mm / deg, tracker error mm / deg, |s - s*|, velocity (" +
       std::to_string(n) + "), lost, safety stop, dropped, render / track / control ms, skipped, command delay ms.\n";
  s += "$steps << EOD\n" + step_table(result, ' ', false) + "EOD\n\n";
  s += "set key inside right top opaque\nset xlabel 'simulated time (s)'\n";
  // Errors span decades: log scale, with values at or below the floor drawn on it.
  s += "floor = 1e-4\nclamp(x) = (x > floor) ? x : floor\n";
  s += "set logscale y\nset format y '%g'\n\n";

  const auto safety_marks = [&](unsigned column) {
    if (!any_safety_stop) return std::string();
    return format(", $steps using 1:(column(%u) > 0 ? clamp(column(%u)) : 1/0) with points pt 7 ps 0.8 lc rgb "
                  "'red' title 'safety stop'",
                  safety_column, column);
  };
  const auto lost_marks = [&](unsigned column) {
    if (!any_lost) return std::string();
    return format(", $steps using 1:(column(%u) > 0 ? clamp(column(%u)) : 1/0) with points pt 6 ps 0.6 lc rgb "
                  "'orange' title 'tracker lost'",
                  lost_column, column);
  };

  s += "set output 'error.png'\n";
  s += "set multiplot layout 2,1 title '" + title + "'\n";
  if (result.steps.empty()) s += "set xrange [0:1]\nset yrange [floor:1]\n";
  s += "set ylabel 'translation error (mm)'\n";
  s += "plot $steps using 1:(clamp($2)) with lines lw 2 lc rgb '#1f77b4' title 'servo (true to desired)', "
       "$steps using 1:(clamp($4)) with lines lc rgb '#2ca02c' title 'tracker (estimate to true)'" +
       lost_marks(2) + safety_marks(2) + "\n";
  s += "set ylabel 'rotation error (deg)'\n";
  s += "plot $steps using 1:(clamp($3)) with lines lw 2 lc rgb '#1f77b4' title 'servo (true to desired)', "
       "$steps using 1:(clamp($5)) with lines lc rgb '#2ca02c' title 'tracker (estimate to true)'" +
       lost_marks(3) + safety_marks(3) + "\n";
  s += "unset multiplot\nset output\n\n";

  // The velocity: a 6-vector may be a camera twist (v m/s, ω rad/s) or the joint velocities
  // of a 6-axis arm, which ServoResult does not say, so the labels stay generic.
  s += "unset logscale y\nset format y '%g'\n";
  s += "set output 'velocity.png'\n";
  s += "set title '" + title + "'\n";
  s += "set ylabel 'velocity components (twist: m/s, rad/s; arm: joint rad/s)'\n";
  if (result.steps.empty()) s += "set xrange [0:1]\nset yrange [-1:1]\n";
  s += "plot ";
  for (unsigned i = 0; i < n; ++i) {
    if (i > 0) s += ", ";
    s += format("$steps using 1:%u with lines lw 1.5 title 'v%u'", first_velocity + i, i);
  }
  if (any_safety_stop)
    s += format(", $steps using 1:(column(%u) > 0 ? 0 : 1/0) with points pt 7 ps 0.8 lc rgb 'red' "
                "title 'safety stop'",
                safety_column);
  if (n == 0) s += "0 notitle";
  s += "\nset output\n";
  return s;
}

}  // namespace

std::string fixed(double value, int decimals) {
  if (!std::isfinite(value)) return "-";
  return format("%.*f", decimals, value);
}

std::string data_number(double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "Inf" : "-Inf";
  return format("%.9g", value);
}

JsonObject summary_json(const TrialsSummary& s) {
  const auto pair = [](const char* a, double va, const char* b, double vb) { return JsonObject().add(a, va).add(b, vb); };
  return JsonObject()
      .add("scenario", s.scenario)
      .add("tracker", s.tracker)
      .add("trials", s.trials)
      .add("converged", s.converged)
      .add("success_rate", s.success_rate)
      .add("final_t_mm", pair("median", s.final_t_median * kMm, "max", s.final_t_max * kMm))
      .add("final_r_deg", pair("median", s.final_r_median * kDeg, "max", s.final_r_max * kDeg))
      .add("median_track_ms", s.median_track_ms)
      .add("steps_per_s", s.steps_per_s)
      .add("safety_stops", s.safety_stops)
      .add("recovered", s.recovered)
      // null when no run converged (-1 in TrialsSummary).
      .add("converged_time_s_median", s.converged_time_median >= 0.0 ? s.converged_time_median : kNaN)
      .add("track_t_mm", pair("mean", s.mean_track_t * kMm, "max", s.max_track_t * kMm)
                             .add("max_vouched", s.max_vouched_track_t * kMm))
      .add("track_r_deg", pair("mean", s.mean_track_r * kDeg, "max", s.max_track_r * kDeg)
                              .add("max_vouched", s.max_vouched_track_r * kDeg))
      .add("interrupted", s.interrupted)
      .add("seed", s.seed ? static_cast<double>(*s.seed) : kNaN);  // null: runs of several seeds
}

bool succeeded(const ServoResult& result, const StopSpec& stop) {
  return result.converged && result.final_t <= stop.converged_translation &&
         result.final_r <= stop.converged_rotation;
}

TrialsSummary summarise(const std::vector<ServoResult>& results, const StopSpec& stop) {
  if (results.empty()) throw std::invalid_argument("summarise: no servo runs to summarise");
  TrialsSummary s;
  s.scenario = results.front().scenario;
  s.tracker = results.front().tracker;
  s.trials = static_cast<int>(results.size());
  s.interrupted = std::any_of(results.begin(), results.end(), [](const ServoResult& r) { return r.interrupted; });
  const unsigned first_seed = results.front().seed;
  if (std::all_of(results.begin(), results.end(), [&](const ServoResult& r) { return r.seed == first_seed; }))
    s.seed = first_seed;

  std::vector<double> final_t, final_r, converged_times, track_ms, steps_per_s;
  double sum_track_t = 0.0, sum_track_r = 0.0;
  std::size_t steps = 0;
  for (const ServoResult& r : results) {
    if (succeeded(r, stop)) {
      ++s.converged;
      if (r.converged_time >= 0.0) converged_times.push_back(r.converged_time);
    }
    final_t.push_back(r.final_t);
    final_r.push_back(r.final_r);
    steps_per_s.push_back(r.steps_per_s);
    s.safety_stops += r.safety_stops;
    if (r.safety_stops > 0 && r.recovered) ++s.recovered;
    // From the runs: a step log sent back from a batch worker carries no lost flags.
    s.max_vouched_track_t = std::max(s.max_vouched_track_t, r.max_vouched_track_t);
    s.max_vouched_track_r = std::max(s.max_vouched_track_r, r.max_vouched_track_r);
    // The tracker error over every step of every run (so longer runs weigh more).
    for (const ServoStep& step : r.steps) {
      track_ms.push_back(step.track_ms);
      if (std::isnan(step.track_t)) continue;  // the object out of the scene: no truth to compare
      sum_track_t += step.track_t;
      sum_track_r += step.track_r;
      s.max_track_t = std::max(s.max_track_t, step.track_t);
      s.max_track_r = std::max(s.max_track_r, step.track_r);
      ++steps;
    }
  }
  s.success_rate = static_cast<double>(s.converged) / s.trials;
  s.final_t_median = median(final_t);
  s.final_t_max = *std::max_element(final_t.begin(), final_t.end());
  s.final_r_median = median(final_r);
  s.final_r_max = *std::max_element(final_r.begin(), final_r.end());
  s.converged_time_median = converged_times.empty() ? -1.0 : median(converged_times);
  s.steps_per_s = median(steps_per_s);
  if (steps > 0) {
    s.mean_track_t = sum_track_t / static_cast<double>(steps);
    s.mean_track_r = sum_track_r / static_cast<double>(steps);
    s.median_track_ms = median(track_ms);
  } else {
    // Runs without their step log: the per-run statistics, runs weighted equally.
    std::vector<double> run_ms;
    for (const ServoResult& r : results) {
      s.mean_track_t += r.mean_track_t / s.trials;
      s.mean_track_r += r.mean_track_r / s.trials;
      s.max_track_t = std::max(s.max_track_t, r.max_track_t);
      s.max_track_r = std::max(s.max_track_r, r.max_track_r);
      run_ms.push_back(r.median_track_ms);
    }
    s.median_track_ms = median(run_ms);
  }
  return s;
}

void print_run(std::ostream& out, const ServoResult& r, const StopSpec& stop) {
  std::string text;
  text += format("scenario           %s\n", r.scenario.c_str());
  text += format("tracker            %s (seed %u)\n", r.tracker.c_str(), r.seed);
  if (r.converged)
    text += format("converged          yes, at step %d (%.2f s simulated)\n", r.converged_step, r.converged_time);
  else if (r.interrupted)
    text += format("converged          no (interrupted at %.2f s simulated, %zu steps)\n", r.steps.back().time,
                   r.steps.size());
  else
    text += format("converged          no (limit %.1f s simulated, %zu steps)\n", stop.max_time, r.steps.size());
  text += format("final error        %.3f mm, %.3f deg to the desired pose (thresholds %.3g mm, %.3g deg): %s\n",
                 r.final_t * kMm, r.final_r * kDeg, stop.converged_translation * kMm,
                 stop.converged_rotation * kDeg, succeeded(r, stop) ? "success" : "failure");
  text += format("tracker error      mean %.3f mm, %.3f deg; max %.3f mm, %.3f deg; max on frames it vouched for "
                 "%.3f mm, %.3f deg\n",
                 r.mean_track_t * kMm, r.mean_track_r * kDeg, r.max_track_t * kMm, r.max_track_r * kDeg,
                 r.max_vouched_track_t * kMm, r.max_vouched_track_r * kDeg);
  text += format("timing             median track %.2f ms, %.1f steps/s (render + track + control)\n",
                 r.median_track_ms, r.steps_per_s);
  if (r.safety_stops > 0)
    text += format("safety stops       %d (%s)\n", r.safety_stops,
                   r.recovered ? "recovered: tracking resumed" : "not recovered: lost at the end");
  else
    text += "safety stops       0\n";
  if (!r.lost_reason.empty()) text += "lost at the end    " + r.lost_reason + "\n";
  text += format("joint-limit stops  %d\n", r.joint_limit_stops);
  out << text;
}

void print_summaries(std::ostream& out, const std::vector<TrialsSummary>& summaries) {
  std::size_t tracker_width = std::string("tracker").size();
  for (const TrialsSummary& s : summaries) tracker_width = std::max(tracker_width, s.tracker.size());
  const int w = static_cast<int>(tracker_width);
  std::string text = format("%-*s %6s %8s %17s %17s %17s %9s %8s %6s\n", w, "tracker", "trials", "success",
                            "final mm med/max", "final deg med/max", "track mm mean/max", "track ms", "steps/s",
                            "safety");
  for (const TrialsSummary& s : summaries) {
    const auto two = [](double a, double b, int decimals) { return fixed(a, decimals) + " / " + fixed(b, decimals); };
    text += format("%-*s %6d %7s%% %17s %17s %17s %9s %8s %6d\n", w, s.tracker.c_str(), s.trials,
                   fixed(s.success_rate * 100.0, 1).c_str(),
                   two(s.final_t_median * kMm, s.final_t_max * kMm, 3).c_str(),
                   two(s.final_r_median * kDeg, s.final_r_max * kDeg, 3).c_str(),
                   two(s.mean_track_t * kMm, s.max_track_t * kMm, 3).c_str(), fixed(s.median_track_ms, 2).c_str(),
                   fixed(s.steps_per_s, 1).c_str(), s.safety_stops);
  }
  out << text;
}

void write_summary_json(const std::vector<TrialsSummary>& summaries, const std::string& path) {
  create_parent_folder(path);
  if (summaries.size() == 1) {
    summary_json(summaries.front()).write(path);
    return;
  }
  std::vector<JsonObject> array;
  for (const TrialsSummary& s : summaries) array.push_back(summary_json(s));
  JsonObject::write_array(array, path);
}

void write_text_file(const std::string& path, const std::string& text, const char* what) {
  create_parent_folder(path);
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw std::runtime_error(std::string("cannot write ") + what + " '" + path + "'");
}

void write_step_csv(const ServoResult& result, const std::string& path) {
  write_text_file(path, step_table(result, ',', true), "step CSV");
}

void plot_run(const ServoResult& result, const std::string& dir) {
  namespace fs = std::filesystem;
  const fs::path folder(dir.empty() ? "." : dir);
  std::error_code error;
  fs::create_directories(folder, error);
  if (error) throw std::runtime_error("cannot create plot folder '" + dir + "': " + error.message());
  // The script (data inside) stays next to the figures: it redraws or restyles them.
  draw_with_gnuplot(plot_script(result), folder / "servo_plot.gp", {folder / "error.png", folder / "velocity.png"});
}

}  // namespace icgp::servo
