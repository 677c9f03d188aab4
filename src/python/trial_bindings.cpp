// SPDX-License-Identifier: GPL-2.0-or-later
// Batch trials of the servo simulator (icgp._icgp.servo): one trial of a batch as a
// picklable value that a Dask worker returns, and the summaries of many, the same table and
// JSON as `icgp servo --trials`. Used by icgp.batch.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "bindings.h"
#include "icgp/servo/scenario.h"
#include "icgp/servo/servo_batch.h"
#include "icgp/servo/servo_report.h"
#include "icgp/servo/servo_sweep.h"
#include "servo_names.h"

namespace icgp::python {
namespace {

namespace py = pybind11;
using servo::ServoResult;
using servo::ServoStep;
using servo::TrialsSummary;

/// Trial `trial` of a batch: its run without the steps, except each step's tracker errors
/// and time, of which servo::summarise makes the summaries of many trials.
struct Trial {
  int trial = 0;
  bool succeeded = false;  ///< servo::succeeded against the scenario's thresholds
  ServoResult run;         ///< steps: only track_t, track_r and track_ms are kept
};

Trial slim(int trial, bool succeeded, ServoResult run) {
  for (ServoStep& step : run.steps) {
    ServoStep kept;
    kept.track_t = step.track_t;
    kept.track_r = step.track_r;
    kept.track_ms = step.track_ms;
    step = std::move(kept);
  }
  return Trial{trial, succeeded, std::move(run)};
}

/// The simulated outcome: every number of a trial but its wall-clock timings, which differ
/// from run to run of the same trial.
bool same_outcome(const Trial& a, const Trial& b) {
  const ServoResult &x = a.run, &y = b.run;
  const bool same_steps = std::equal(x.steps.begin(), x.steps.end(), y.steps.begin(), y.steps.end(),
                                     [](const ServoStep& p, const ServoStep& q) {
                                       return p.track_t == q.track_t && p.track_r == q.track_r;
                                     });
  return a.trial == b.trial && a.succeeded == b.succeeded && same_steps && x.scenario == y.scenario &&
         x.tracker == y.tracker && x.seed == y.seed && x.converged == y.converged &&
         x.converged_step == y.converged_step && x.converged_time == y.converged_time && x.final_t == y.final_t &&
         x.final_r == y.final_r && x.mean_track_t == y.mean_track_t && x.max_track_t == y.max_track_t &&
         x.mean_track_r == y.mean_track_r && x.max_track_r == y.max_track_r &&
         x.max_vouched_track_t == y.max_vouched_track_t && x.max_vouched_track_r == y.max_vouched_track_r &&
         x.safety_stops == y.safety_stops &&
         x.recovered == y.recovered && x.lost_reason == y.lost_reason && x.joint_limit_stops == y.joint_limit_stops &&
         x.interrupted == y.interrupted;
}

/// Per-step values as bytes: a pickle of 10 000 trials stays small and quick.
py::bytes step_values(const ServoResult& run, double ServoStep::*field) {
  std::string bytes(run.steps.size() * sizeof(double), '\0');
  for (std::size_t i = 0; i < run.steps.size(); ++i)
    std::memcpy(&bytes[i * sizeof(double)], &(run.steps[i].*field), sizeof(double));
  return py::bytes(bytes);
}

void set_step_values(ServoResult& run, double ServoStep::*field, const py::bytes& values) {
  const std::string bytes = values;
  if (bytes.size() % sizeof(double) != 0) throw py::value_error("TrialResult pickle: step values of a wrong size");
  run.steps.resize(bytes.size() / sizeof(double));
  for (std::size_t i = 0; i < run.steps.size(); ++i)
    std::memcpy(&(run.steps[i].*field), &bytes[i * sizeof(double)], sizeof(double));
}

py::tuple pickled(const Trial& t) {
  const ServoResult& r = t.run;
  return py::make_tuple(t.trial, t.succeeded, r.scenario, r.tracker, r.seed, r.converged, r.converged_step,
                        r.converged_time, r.final_t, r.final_r, r.mean_track_t, r.max_track_t, r.mean_track_r,
                        r.max_track_r, r.median_track_ms, r.steps_per_s, r.safety_stops, r.recovered,
                        r.joint_limit_stops, r.interrupted, r.lost_reason, step_values(r, &ServoStep::track_t),
                        step_values(r, &ServoStep::track_r), step_values(r, &ServoStep::track_ms),
                        r.max_vouched_track_t, r.max_vouched_track_r);
}

Trial unpickled(const py::tuple& s) {
  if (s.size() != 26) throw py::value_error("TrialResult pickle: expected 26 values, got " + std::to_string(s.size()));
  Trial t;
  ServoResult& r = t.run;
  t.trial = s[0].cast<int>();
  t.succeeded = s[1].cast<bool>();
  r.scenario = s[2].cast<std::string>();
  r.tracker = s[3].cast<std::string>();
  r.seed = s[4].cast<unsigned>();
  r.converged = s[5].cast<bool>();
  r.converged_step = s[6].cast<int>();
  r.converged_time = s[7].cast<double>();
  r.final_t = s[8].cast<double>();
  r.final_r = s[9].cast<double>();
  r.mean_track_t = s[10].cast<double>();
  r.max_track_t = s[11].cast<double>();
  r.mean_track_r = s[12].cast<double>();
  r.max_track_r = s[13].cast<double>();
  r.median_track_ms = s[14].cast<double>();
  r.steps_per_s = s[15].cast<double>();
  r.safety_stops = s[16].cast<int>();
  r.recovered = s[17].cast<bool>();
  r.joint_limit_stops = s[18].cast<int>();
  r.interrupted = s[19].cast<bool>();
  r.lost_reason = s[20].cast<std::string>();
  set_step_values(r, &ServoStep::track_t, s[21].cast<py::bytes>());
  set_step_values(r, &ServoStep::track_r, s[22].cast<py::bytes>());
  set_step_values(r, &ServoStep::track_ms, s[23].cast<py::bytes>());
  r.max_vouched_track_t = s[24].cast<double>();
  r.max_vouched_track_r = s[25].cast<double>();
  return t;
}

py::dict trial_dict(const Trial& t) {
  const ServoResult& r = t.run;
  py::dict d;
  d["trial"] = t.trial;
  d["scenario"] = r.scenario;
  d["tracker"] = r.tracker;
  d["seed"] = r.seed;
  d["succeeded"] = t.succeeded;
  d["converged"] = r.converged;
  d["converged_step"] = r.converged_step;
  d["converged_time"] = r.converged_time;
  d["final_t"] = r.final_t;
  d["final_r"] = r.final_r;
  d["mean_track_t"] = r.mean_track_t;
  d["max_track_t"] = r.max_track_t;
  d["mean_track_r"] = r.mean_track_r;
  d["max_track_r"] = r.max_track_r;
  d["max_vouched_track_t"] = r.max_vouched_track_t;
  d["max_vouched_track_r"] = r.max_vouched_track_r;
  d["median_track_ms"] = r.median_track_ms;
  d["steps_per_s"] = r.steps_per_s;
  d["safety_stops"] = r.safety_stops;
  d["recovered"] = r.recovered;
  d["lost_reason"] = r.lost_reason;
  d["joint_limit_stops"] = r.joint_limit_stops;
  d["interrupted"] = r.interrupted;
  d["steps"] = r.steps.size();
  return d;
}

py::dict summary_dict(const TrialsSummary& s) {
  py::dict d;
  d["scenario"] = s.scenario;
  d["tracker"] = s.tracker;
  d["trials"] = s.trials;
  d["converged"] = s.converged;
  d["success_rate"] = s.success_rate;
  d["final_t_median"] = s.final_t_median;
  d["final_t_max"] = s.final_t_max;
  d["final_r_median"] = s.final_r_median;
  d["final_r_max"] = s.final_r_max;
  d["converged_time_median"] = s.converged_time_median;
  d["mean_track_t"] = s.mean_track_t;
  d["max_track_t"] = s.max_track_t;
  d["mean_track_r"] = s.mean_track_r;
  d["max_track_r"] = s.max_track_r;
  d["max_vouched_track_t"] = s.max_vouched_track_t;
  d["max_vouched_track_r"] = s.max_vouched_track_r;
  d["median_track_ms"] = s.median_track_ms;
  d["steps_per_s"] = s.steps_per_s;
  d["safety_stops"] = s.safety_stops;
  d["recovered"] = s.recovered;
  d["interrupted"] = s.interrupted;
  return d;
}

/// The runs of `trials` by tracker, in the order the trackers first appear, each tracker's
/// in trial index order (the order run_trials sums them in, so the numbers are the CLI's).
std::vector<std::vector<ServoResult>> runs_by_tracker(const std::vector<Trial>& trials,
                                                      const servo::Scenario& scenario) {
  if (trials.empty()) throw py::value_error("results: no trials to summarise");
  std::vector<std::string> order;
  std::map<std::string, std::vector<const Trial*>> by_tracker;
  for (const Trial& t : trials) {
    if (t.run.scenario != scenario.name)
      throw py::value_error("results: trial " + std::to_string(t.trial) + " ran scenario '" + t.run.scenario +
                            "', not '" + scenario.name + "'");
    std::vector<const Trial*>& group = by_tracker[t.run.tracker];
    if (group.empty()) order.push_back(t.run.tracker);
    group.push_back(&t);
  }
  std::vector<std::vector<ServoResult>> runs(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    std::vector<const Trial*>& group = by_tracker[order[k]];
    std::stable_sort(group.begin(), group.end(), [](const Trial* a, const Trial* b) { return a->trial < b->trial; });
    for (std::size_t i = 0; i < group.size(); ++i) {
      if (i > 0 && group[i]->trial == group[i - 1]->trial)
        throw py::value_error("results: trial " + std::to_string(group[i]->trial) + " of " + order[k] + " twice");
      runs[k].push_back(group[i]->run);
    }
  }
  return runs;
}

/// The summaries of `trials`, one per tracker (runs_by_tracker).
std::vector<TrialsSummary> summarise(const std::vector<Trial>& trials, const servo::Scenario& scenario,
                                     bool interrupted) {
  std::vector<TrialsSummary> summaries;
  for (const std::vector<ServoResult>& runs : runs_by_tracker(trials, scenario)) {
    summaries.push_back(servo::summarise(runs, scenario.stop));
    summaries.back().interrupted = summaries.back().interrupted || interrupted;
  }
  return summaries;
}

/// What `icgp servo --sweep` prints and writes, from the trials at each value done so far:
/// `done` holds (value, the Scenario read with it, its TrialResults, the error that stopped
/// its trials or "", interrupted). Writes `json` and, unless `plot_dir` is empty, the plot;
/// returns the table.
std::string write_sweep(const std::string& field, const std::vector<double>& swept, const py::list& done,
                        const std::filesystem::path& json, const std::filesystem::path& plot_dir) {
  const servo::SweepSpec sweep{field, swept};
  std::vector<servo::SweepValue> values;
  for (const py::handle& item : done) {
    const py::tuple entry = item.cast<py::tuple>();
    if (entry.size() != 5)
      throw py::value_error("done: expected (value, scenario, results, error, interrupted) per value");
    const double value = entry[0].cast<double>();
    const auto& scenario = entry[1].cast<const servo::Scenario&>();
    const auto trials = entry[2].cast<std::vector<Trial>>();
    servo::SweepValue v = trials.empty() ? servo::SweepValue{value, {}, {}}
                                         : servo::sweep_value(value, runs_by_tracker(trials, scenario), scenario,
                                                              entry[4].cast<bool>());
    v.error = entry[3].cast<std::string>();
    values.push_back(std::move(v));
  }
  servo::write_sweep_json(sweep, values, json.string());
  if (!plot_dir.empty()) servo::plot_sweep(sweep, values, plot_dir.string());
  std::ostringstream table;
  servo::print_sweep(table, sweep, values);
  return table.str();
}

constexpr const char* kTrialDoc =
    "One trial of a batch (run_trial, icgp.batch.trials): the run's outcome without its steps. Distances are\n"
    "metres, angles radians, as in the C++ ServoResult. Picklable (Dask returns it from workers); == compares\n"
    "every simulated number, not the wall-clock timings (median_track_ms, steps_per_s).";

}  // namespace

void register_trials(py::module_& m) {
  py::module_ servo = m.attr("servo");

  py::class_<Trial>(servo, "TrialResult", kTrialDoc)
      .def_readonly("trial", &Trial::trial, "The trial's index in its batch.")
      .def_readonly("succeeded", &Trial::succeeded,
                    "Converged with the true final error within the scenario's thresholds.")
      .def_property_readonly("scenario", [](const Trial& t) { return t.run.scenario; })
      .def_property_readonly("tracker", [](const Trial& t) { return t.run.tracker; },
                             "The tracker's name as the table shows it, e.g. 'oracle (ground truth)'.")
      .def_property_readonly("seed", [](const Trial& t) { return t.run.seed; }, "The noise seed: scenario seed + trial.")
      .def_property_readonly("converged", [](const Trial& t) { return t.run.converged; })
      .def_property_readonly("converged_step", [](const Trial& t) { return t.run.converged_step; }, "-1 when never.")
      .def_property_readonly("converged_time", [](const Trial& t) { return t.run.converged_time; },
                             "Simulated seconds; -1 when never.")
      .def_property_readonly("final_t", [](const Trial& t) { return t.run.final_t; }, "True final pose to the desired, m.")
      .def_property_readonly("final_r", [](const Trial& t) { return t.run.final_r; }, "The same, radians.")
      .def_property_readonly("mean_track_t", [](const Trial& t) { return t.run.mean_track_t; }, "Tracker error, m.")
      .def_property_readonly("max_track_t", [](const Trial& t) { return t.run.max_track_t; })
      .def_property_readonly("mean_track_r", [](const Trial& t) { return t.run.mean_track_r; }, "Radians.")
      .def_property_readonly("max_track_r", [](const Trial& t) { return t.run.max_track_r; })
      .def_property_readonly("median_track_ms", [](const Trial& t) { return t.run.median_track_ms; },
                             "Wall-clock milliseconds per tracked frame.")
      .def_property_readonly("steps_per_s", [](const Trial& t) { return t.run.steps_per_s; },
                             "Wall-clock rate of the loop.")
      .def_property_readonly("safety_stops", [](const Trial& t) { return t.run.safety_stops; })
      .def_property_readonly("recovered", [](const Trial& t) { return t.run.recovered; })
      .def_property_readonly("lost_reason", [](const Trial& t) { return t.run.lost_reason; },
                             "Lost at the end: the tracker's last reason (never found, say); empty otherwise.")
      .def_property_readonly("joint_limit_stops", [](const Trial& t) { return t.run.joint_limit_stops; })
      .def_property_readonly("interrupted", [](const Trial& t) { return t.run.interrupted; })
      .def_property_readonly("steps", [](const Trial& t) { return t.run.steps.size(); }, "The number of steps run.")
      .def("as_dict", &trial_dict, "Every field as a dict.")
      .def("__eq__", [](const Trial& a, const Trial& b) { return same_outcome(a, b); }, py::is_operator())
      .def("__ne__", [](const Trial& a, const Trial& b) { return !same_outcome(a, b); }, py::is_operator())
      .def("__repr__",
           [](const Trial& t) {
             char text[160];
             std::snprintf(text, sizeof text, "<icgp.servo.TrialResult trial %d %s: %s, final %.3f mm %.3f deg>",
                           t.trial, t.run.tracker.c_str(), t.succeeded ? "success" : "failed", 1e3 * t.run.final_t,
                           t.run.final_r / servo::kDegree);
             return std::string(text);
           })
      .def(py::pickle(&pickled, &unpickled));

  py::class_<TrialsSummary>(servo, "TrialsSummary",
                            "The statistics of one tracker's trials (summarise, icgp.batch.trials); metres, radians.")
      .def_readonly("scenario", &TrialsSummary::scenario)
      .def_readonly("tracker", &TrialsSummary::tracker)
      .def_readonly("trials", &TrialsSummary::trials)
      .def_readonly("converged", &TrialsSummary::converged, "Trials that succeeded.")
      .def_readonly("success_rate", &TrialsSummary::success_rate)
      .def_readonly("final_t_median", &TrialsSummary::final_t_median)
      .def_readonly("final_t_max", &TrialsSummary::final_t_max)
      .def_readonly("final_r_median", &TrialsSummary::final_r_median)
      .def_readonly("final_r_max", &TrialsSummary::final_r_max)
      .def_readonly("converged_time_median", &TrialsSummary::converged_time_median, "-1 when none converged.")
      .def_readonly("mean_track_t", &TrialsSummary::mean_track_t, "Over every step of every trial.")
      .def_readonly("max_track_t", &TrialsSummary::max_track_t)
      .def_readonly("mean_track_r", &TrialsSummary::mean_track_r)
      .def_readonly("max_track_r", &TrialsSummary::max_track_r)
      .def_readonly("median_track_ms", &TrialsSummary::median_track_ms)
      .def_readonly("steps_per_s", &TrialsSummary::steps_per_s, "Median over the trials.")
      .def_readonly("safety_stops", &TrialsSummary::safety_stops)
      .def_readonly("recovered", &TrialsSummary::recovered, "Trials with safety stops that recovered.")
      .def_readonly("interrupted", &TrialsSummary::interrupted)
      .def("as_dict", &summary_dict, "Every field as a dict.")
      .def("__repr__", [](const TrialsSummary& s) {
        return "<icgp.servo.TrialsSummary " + s.tracker + ": " + std::to_string(s.converged) + " of " +
               std::to_string(s.trials) + " succeeded>";
      });

  servo.def(
      "run_trial",
      [](const servo::Scenario& scenario, const py::object& tracker, int trial) {
        const servo::TrackerKind kind = tracker_kind(tracker).value_or(scenario.tracker.kind);
        if (trial < 0) throw py::value_error("trial: expected an index >= 0, got " + std::to_string(trial));
        ServoResult run;
        {
          py::gil_scoped_release release;  // trials run in parallel in threads too
          run = servo::run_trial(scenario, kind, trial);
        }
        const bool succeeded = servo::succeeded(run, scenario.stop);
        return slim(trial, succeeded, std::move(run));
      },
      py::arg("scenario"), py::arg("tracker").none(true), py::arg("trial"),
      "Runs trial `trial` of a batch of `scenario` with `tracker` ('icgp', 'visp', 'oracle'; None: the\n"
      "scenario's), exactly as `icgp servo --trials` runs it: from the scenario's start moved by the trial's\n"
      "seeded random offset, with the noise seed scenario.seed + trial. Returns a TrialResult.");
  servo.def("summarise", &summarise, py::arg("results"), py::arg("scenario"), py::arg("interrupted") = false,
            "The TrialsSummary of each tracker among `results` (TrialResults of `scenario`), in the order the\n"
            "trackers first appear, each over its trials in index order: the numbers `icgp servo --trials` prints.\n"
            "`interrupted`: a stop ended the batch before all its trials (marked in each summary).");
  servo.def(
      "parse_sweep",
      [](const std::string& text) {
        const servo::SweepSpec sweep = servo::parse_sweep(text);
        return py::make_tuple(sweep.field, sweep.values);
      },
      py::arg("text"), "FIELD=V1,V2,... as `icgp servo --sweep` reads it: (field, [values]); ValueError otherwise.");
  servo.def("write_sweep", &write_sweep, py::arg("field"), py::arg("values"), py::arg("done"), py::arg("json"),
            py::arg("plot_dir"),
            "Writes sweep.json (and sweep.png in plot_dir, unless empty) of `icgp servo --sweep` from `done`, a list\n"
            "of (value, Scenario, [TrialResult], error text or '', interrupted) per value swept so far; returns the\n"
            "table it prints.");
  servo.def(
      "table",
      [](const std::vector<TrialsSummary>& summaries) {
        std::ostringstream out;
        servo::print_summaries(out, summaries);
        return out.str();
      },
      py::arg("summaries"), "The text table `icgp servo --trials` prints, one row per summary.");
  servo.def(
      "write_summary_json",
      [](const std::vector<TrialsSummary>& summaries, const std::filesystem::path& path) {
        if (summaries.empty()) throw py::value_error("summaries: expected at least one TrialsSummary");
        servo::write_summary_json(summaries, path.string());
      },
      py::arg("summaries"), py::arg("path"),
      "Writes the summary JSON of `icgp servo --summary`: an object for one summary, an array for several.");
}

}  // namespace icgp::python
