// SPDX-License-Identifier: GPL-2.0-or-later
// What a servo run leaves behind: the summary (printed and JSON), the per-step CSV log and
// the plots.
#pragma once

#include <array>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "icgp/eval/json_object.h"
#include "icgp/servo/servo_run.h"

namespace icgp::servo {

/// The statistics of one or more runs of a scenario with one tracker (batch trials).
struct TrialsSummary {
  std::string scenario;
  std::string tracker;
  /// The noise seed every run had, when they all had the same (a single run): the seed a
  /// replay of its log builds the scene with. Unset for trials of several seeds.
  std::optional<unsigned> seed;
  int trials = 0;
  int converged = 0;
  double success_rate = 0.0;  ///< converged / trials, and the final true error within the
                              ///< scenario's thresholds
  double final_t_median = 0.0, final_t_max = 0.0;  ///< metres
  double final_r_median = 0.0, final_r_max = 0.0;  ///< radians
  double converged_time_median = -1.0;             ///< seconds, over converged runs; -1: none
  double mean_track_t = 0.0, max_track_t = 0.0;    ///< tracker error over all runs, metres
  double mean_track_r = 0.0, max_track_r = 0.0;    ///< radians
  /// ServoResult's, the largest over all runs.
  double max_vouched_track_t = 0.0, max_vouched_track_r = 0.0;
  double median_track_ms = 0.0;
  double steps_per_s = 0.0;  ///< median over runs
  int safety_stops = 0;      ///< over all runs
  int recovered = 0;         ///< runs with safety stops that recovered
  /// A stop request ended the work early: a run of these was cut short, or (set by the
  /// batch) the batch stopped before all its trials and `trials` counts those done.
  bool interrupted = false;
};

/// `success` of a run: it converged and its true final error is within `stop`'s thresholds.
bool succeeded(const ServoResult& result, const StopSpec& stop);
TrialsSummary summarise(const std::vector<ServoResult>& results, const StopSpec& stop);

/// The human-readable summary of one run (steps, time to converge, errors, timing, stops).
void print_run(std::ostream& out, const ServoResult& result, const StopSpec& stop);
/// One table row per summary (trackers compared on identical trials).
void print_summaries(std::ostream& out, const std::vector<TrialsSummary>& summaries);

/// The machine-readable summary: {"scenario", "tracker", "trials", "converged",
/// "success_rate", "final_t_mm": {"median", "max"}, "final_r_deg": {"median", "max"},
/// "median_track_ms", "steps_per_s", "safety_stops"} plus the other TrialsSummary fields
/// ("interrupted": true when a stop request cut the work short; "seed", null for runs of
/// several seeds);
/// with several summaries (--compare) an array of them.
void write_summary_json(const std::vector<TrialsSummary>& summaries, const std::string& path);
/// One summary as write_summary_json writes it.
JsonObject summary_json(const TrialsSummary& summary);

/// A number for the text tables: `decimals` after the point, "-" when undefined.
std::string fixed(double value, int decimals);
/// A CSV / gnuplot number: %.9g, NaN (Inf, -Inf) for undefined.
std::string data_number(double value);

/// Writes `text` into the file `path`, creating its folder; throws std::runtime_error
/// naming `what` ("step CSV") and the file when it cannot.
void write_text_file(const std::string& path, const std::string& text, const char* what);

/// The last columns of write_step_csv: the camera's true pose in the world at each step
/// (ServoStep::wMc_true), translation in metres and θu rotation in radians, written with
/// every digit so that replay_camera_path renders the frames at the poses of the run.
inline constexpr std::array<const char*, 6> kCameraPoseColumns = {"camera_tx",  "camera_ty",  "camera_tz",
                                                                  "camera_tux", "camera_tuy", "camera_tuz"};

/// One line per step: time, true and estimated errors, tracker error, velocity, flags,
/// timings, then the camera pose (kCameraPoseColumns).
void write_step_csv(const ServoResult& result, const std::string& path);

/// error.png (servo and tracker errors over time) and velocity.png (the applied velocity)
/// in `dir`, drawn by gnuplot. Throws std::runtime_error naming gnuplot when it is missing
/// or fails.
void plot_run(const ServoResult& result, const std::string& dir);

}  // namespace icgp::servo
