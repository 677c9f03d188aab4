// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp servo SCENARIO`: the closed loop tracker -> ViSP control law -> simulated robot, one
// run with its log and plots, batch trials, or trackers compared on identical trials.
#include <cstdio>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <vector>
#include <opencv2/imgproc.hpp>
#include <unistd.h>
#include <visp3/core/vpImageConvert.h>
#include <visp3/gui/vpDisplayX.h>

#include "commands.h"
#include "eta_progress.h"
#include "icgp/base/camera_names.h"
#include "icgp/base/stop_request.h"
#include "icgp/servo/blender_process.h"
#include "icgp/servo/servo_batch.h"
#include "icgp/servo/servo_report.h"
#include "icgp/servo/servo_run.h"
#include "icgp/servo/servo_sweep.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/conversions.h"
#include "option_ranges.h"
#include "overlay_video.h"
#include "servo_replay_command.h"

namespace icgp::app {
namespace {

namespace fs = std::filesystem;
using servo::Scenario;
using servo::ServoResult;
using servo::TrackerKind;

/// The most trials of one batch: 10 000, some 17 hours for one tracker at 6 s a trial
/// (a 640x480 run here), three times that with --compare.
constexpr long long kMaxTrials = 10000;

struct ServoOptions {
  std::string scenario;
  std::string tracker;  ///< overrides the scenario's: icgp, visp, oracle
  int trials = 1;
  unsigned seed = 0;  ///< 0: the scenario's
  bool compare = false;
  std::string summary;
  std::string out;
  std::string video;
  bool display = false;
  bool quiet = false;
  std::string scheduler;  ///< a Dask scheduler's address: the trials run on its workers
  int jobs = 0;           ///< > 0: the trials run on this many local worker processes
  std::string sweep;      ///< FIELD=V1,V2,...: the trials at each value of a scenario field
  std::string renderer;   ///< overrides the scenario's camera.renderer: opengl, cycles
  std::string replay;     ///< a run's log.csv: its camera path rendered again and tracked open-loop
};

/// The names scenario files give trackers, which --tracker takes.
std::vector<std::string> tracker_choices() { return servo::names_in(servo::tracker_names()); }

TrackerKind tracker_kind(const std::string& name) {
  if (const std::optional<TrackerKind> kind = servo::kind_named(name, servo::tracker_names())) return *kind;
  throw std::invalid_argument("--tracker: expected one of " + yaml::join(tracker_choices()) + ", got '" + name + "'");
}

/// The names scenario files give renderers (camera.renderer), which --renderer takes.
std::vector<std::string> renderer_choices() { return servo::names_in(servo::renderer_names()); }

/// --renderer's renderer; none when it is not given.
std::optional<servo::RendererKind> renderer_kind(const std::string& name) {
  if (name.empty()) return std::nullopt;
  if (const std::optional<servo::RendererKind> kind = servo::kind_named(name, servo::renderer_names())) return kind;
  throw std::invalid_argument("--renderer: expected one of " + yaml::join(renderer_choices()) + ", got '" + name +
                              "'");
}

/// Writes the overlay video and shows the live window of a single run.
class RunViewer {
 public:
  RunViewer(const ServoOptions& o, const Scenario& scenario) {
    if (!o.video.empty()) video_ = std::make_unique<OverlayVideo>(o.video, load_any_mesh(scenario.object.model), scenario.camera.rate_hz);
    if (o.display) {
      if (!std::getenv("DISPLAY"))
        throw std::runtime_error("--display needs an X display (DISPLAY is not set); run without it headless");
      image_.resize(static_cast<unsigned>(scenario.camera.color.height), static_cast<unsigned>(scenario.camera.color.width));
      display_ = std::make_unique<vpDisplayX>(image_, 0, 0, "icgp servo: " + scenario.name);
    }
    intrinsics_ = scenario.camera.color;
  }

  bool active() const { return video_ || display_; }

  void show(const servo::RgbdCapture& capture, const servo::ServoStep& step) {
    char caption[96];
    std::snprintf(caption, sizeof caption, "t %.2f s  error %.2f mm %.2f deg%s", step.time, 1e3 * step.servo_t,
                  step.servo_r / servo::kDegree, step.safety_stop ? "  SAFETY STOP" : "");
    if (video_) {
      ColorImage color{kColorCamera, intrinsics_, Pose(), cv::Mat()};
      vpImageConvert::convert(capture.color, color.image);  // BGR
      const Pose truth = to_pose(step.cMo_true);
      video_->write(color, to_pose(step.cMo_estimated), &truth, caption);
    }
    if (display_) {
      image_ = capture.color;
      vpDisplay::display(image_);
      vpDisplay::displayFrame(image_, step.cMo_estimated, to_camera_parameters(intrinsics_), 0.05, vpColor::none, 2);
      vpDisplay::displayText(image_, 20, 10, caption, vpColor::red);
      vpDisplay::flush(image_);
    }
  }

 private:
  std::unique_ptr<OverlayVideo> video_;
  std::unique_ptr<vpDisplayX> display_;
  vpImage<vpRGBa> image_;
  Intrinsics intrinsics_;
};

/// "visp 93 of 100, icgp 1 of 100": the trackers some of whose runs did not succeed.
std::string failures(const std::vector<servo::TrialsSummary>& summaries) {
  std::string text;
  for (const servo::TrialsSummary& s : summaries) {
    const int failed = s.trials - s.converged;
    if (failed == 0) continue;
    text += (text.empty() ? "" : ", ") + s.tracker + " " + std::to_string(failed) + " of " + std::to_string(s.trials);
  }
  return text;
}

/// Why a single run failed, in one line.
std::string failure_reason(const ServoResult& r, const servo::StopSpec& stop) {
  char text[256];
  std::snprintf(text, sizeof text, "%s: final error %.3f mm, %.3f deg; thresholds %.3g mm, %.3g deg",
                r.converged ? "settled off target" : "did not converge", 1e3 * r.final_t, r.final_r / servo::kDegree,
                1e3 * stop.converged_translation, stop.converged_rotation / servo::kDegree);
  std::string reason = text;
  if (!r.converged) reason += " (limit " + yaml::plain_number(stop.max_time) + " s simulated)";
  if (!r.lost_reason.empty()) reason += "; lost at the end: " + r.lost_reason;
  return reason;
}

/// Trials (--trials, --compare): a line per run with the time left, the table and the JSON
/// summary of the trials done, also when Ctrl-C stopped the batch. A run that throws (a
/// renderer that crashed, say) is reported and its trial left out; the batch goes on.
void run_batch(const ServoOptions& o, const Scenario& scenario, const std::string& summary) {
  if (!o.video.empty() || o.display) throw std::invalid_argument("--video and --display show a single run, not trials");
  const std::vector<TrackerKind> kinds =
      o.compare ? std::vector<TrackerKind>{TrackerKind::kOracle, TrackerKind::kVisp, TrackerKind::kIcgp}
                : std::vector<TrackerKind>{scenario.tracker.kind};
  EtaProgress progress(o.trials * static_cast<int>(kinds.size()));
  const auto run_done = [&](int trial, const ServoResult& r) {
    std::fprintf(stderr, "trial %d/%d %s: %s, final %.3f mm %.3f deg, tracker max %.2f mm%s%s %s\n", trial + 1,
                 o.trials, r.tracker.c_str(),
                 servo::succeeded(r, scenario.stop) ? "success" : r.converged ? "settled off target" : "not converged",
                 1e3 * r.final_t, r.final_r / servo::kDegree, 1e3 * r.max_track_t,
                 r.safety_stops > 0 ? (", " + std::to_string(r.safety_stops) + " safety stop(s)").c_str() : "",
                 r.lost_reason.empty() ? "" : (", lost at the end: " + r.lost_reason).c_str(),
                 progress.done().c_str());
  };
  std::vector<std::string> errors;
  const auto run_failed = [&](int trial, TrackerKind tracker, const std::exception& e) {
    const std::string what = "trial " + std::to_string(trial + 1) + " (" +
                             servo::name_of(tracker, servo::tracker_names()) + "): " + e.what();
    std::fprintf(stderr, "trial %d/%d failed, left out: %s %s\n", trial + 1, o.trials, what.c_str(),
                 progress.done().c_str());
    errors.push_back(what);
  };
  const servo::TrialBatch batch = servo::run_trials(scenario, kinds, o.trials, run_done, {}, run_failed);
  const std::string failed_trials = std::to_string(errors.size()) + " trial(s) failed with an error, the first: " +
                                    (errors.empty() ? "" : errors.front());
  if (batch.trials_done == 0 && !errors.empty())
    throw CommandOutcome(kExitError, "servo: no trial ended; " + failed_trials);
  if (batch.trials_done == 0)
    throw CommandOutcome(kExitInterrupted, "interrupted before the first trial ended: nothing written");
  std::vector<servo::TrialsSummary> summaries;
  for (const std::vector<ServoResult>& runs : batch.runs) {
    summaries.push_back(servo::summarise(runs, scenario.stop));
    summaries.back().interrupted = batch.interrupted;
  }
  servo::print_summaries(std::cout, summaries);
  servo::write_summary_json(summaries, summary);
  std::cout << "wrote " << summary << "\n";
  if (batch.interrupted)
    throw CommandOutcome(kExitInterrupted, "interrupted: " + std::to_string(batch.trials_done) + " of " +
                                               std::to_string(o.trials) + " trials done, in the table and " + summary);
  if (!errors.empty()) throw CommandOutcome(kExitError, "servo: " + failed_trials + " (the table holds the others)");
  if (const std::string failed = failures(summaries); !failed.empty())
    throw CommandOutcome(kExitNotAchieved, "servo: runs that did not succeed: " + failed);
}

/// One run: the printed summary, its log, plots and JSON summary, also when Ctrl-C stopped it.
void run_single(const ServoOptions& o, const Scenario& scenario, const fs::path& out, const std::string& summary) {
  servo::ServoRunOptions run;
  run.seed = scenario.seed;
  run.progress = !o.quiet;
  RunViewer viewer(o, scenario);
  if (viewer.active()) run.on_step = [&viewer](const servo::RgbdCapture& c, const servo::ServoStep& s) { viewer.show(c, s); };
  const ServoResult result = servo::run_servo(scenario, run);
  servo::print_run(std::cout, result, scenario.stop);
  servo::write_step_csv(result, (out / "log.csv").string());
  servo::plot_run(result, out.string());
  std::cout << "wrote " << (out / "log.csv").string() << ", " << (out / "error.png").string() << ", "
            << (out / "velocity.png").string() << (o.video.empty() ? "" : ", " + o.video) << "\n";
  servo::write_summary_json({servo::summarise({result}, scenario.stop)}, summary);
  std::cout << "wrote " << summary << "\n";
  if (result.interrupted) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "interrupted at %.2f s simulated: the log, plots and summary hold the %zu steps done",
                  result.steps.back().time, result.steps.size());
    throw CommandOutcome(kExitInterrupted, text);
  }
  if (!servo::succeeded(result, scenario.stop))
    throw CommandOutcome(kExitNotAchieved, "servo run failed: " + failure_reason(result, scenario.stop));
}

/// --scheduler, --jobs: the trials run on Dask workers through icgp's Python package, whose
/// `python -m icgp servo` prints and writes what run_batch does. This process becomes that
/// interpreter (exec), so Ctrl-C and the exit status are its.
[[noreturn]] void run_on_workers(const ServoOptions& o) {
  const std::string option = o.jobs > 0 ? "--jobs" : "--scheduler";
  if (!o.video.empty() || o.display)
    throw std::invalid_argument(option + " runs trials on workers; --video and --display show a single run");
  if (o.trials < 2 && !o.compare && o.sweep.empty())
    throw std::invalid_argument(option + " runs batch trials: give --trials N with N > 1, --compare or --sweep");
#ifdef ICGP_PYTHON_EXECUTABLE
  std::vector<std::string> args{ICGP_PYTHON_EXECUTABLE, "-m", "icgp", "servo", o.scenario, "--trials",
                                std::to_string(o.trials)};
  const auto add = [&args](const std::string& name, const std::string& value) {
    if (!value.empty()) args.insert(args.end(), {name, value});
  };
  add("--seed", o.seed != 0 ? std::to_string(o.seed) : "");
  add("--tracker", o.tracker);
  if (o.compare) args.push_back("--compare");
  add("--sweep", o.sweep);
  add("--summary", o.summary);
  add("--out", o.out);
  add("--scheduler", o.scheduler);
  add("--jobs", o.jobs > 0 ? std::to_string(o.jobs) : "");

  // The package installed beside the program (<prefix>/bin/icgp, <prefix>/lib/python3/...),
  // else the build tree's.
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  fs::path package = exe.parent_path().parent_path() / ICGP_PYTHON_INSTALL_DIR;
  if (ec || !fs::is_regular_file(package / "icgp" / "__main__.py")) package = ICGP_PYTHON_BUILD_DIR;
  if (!fs::is_regular_file(package / "icgp" / "__main__.py"))
    throw std::runtime_error(option + ": icgp's Python package is not in " + package.string() +
                             " (build it: cmake --build, or install it)");
  const char* path = std::getenv("PYTHONPATH");
  const std::string python_path = package.string() + (path && *path ? ":" + std::string(path) : "");
  ::setenv("PYTHONPATH", python_path.c_str(), 1);

  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::cout.flush();
  // Python turns Ctrl-C into KeyboardInterrupt (the trials done are written) only when
  // SIGINT is not ignored, as it is in a shell's background jobs: the C++ batch stops on it
  // there too (install_stop_on_sigint).
  std::signal(SIGINT, SIG_DFL);
  ::execv(argv[0], argv.data());
  throw std::runtime_error(option + ": cannot run the Python interpreter " + args[0] + ": " + std::strerror(errno));
#else
  throw std::invalid_argument(option + " runs the trials through icgp's Python package, and this icgp was built "
                              "without it (configure with -DICGP_BUILD_PYTHON=ON)");
#endif
}

/// --sweep: the trials at each value of a scenario field, on the same seeded starts; the
/// table, sweep.json (after every value) and sweep.png. Every value is read first, so that a
/// field or value the scenario refuses stops the sweep before anything runs.
void run_sweep(const ServoOptions& o, const fs::path& out) {
  if (!o.video.empty() || o.display) throw std::invalid_argument("--video and --display show a single run, not a sweep");
  const servo::SweepSpec sweep = servo::parse_sweep(o.sweep);
  for (double value : sweep.values) servo::load_scenario(o.scenario, models_dir(), {{sweep.field, value}});
  const Scenario scenario = servo::load_scenario(o.scenario, models_dir());
  const std::vector<TrackerKind> kinds =
      o.compare ? std::vector<TrackerKind>{TrackerKind::kOracle, TrackerKind::kVisp, TrackerKind::kIcgp}
                : std::vector<TrackerKind>{o.tracker.empty() ? scenario.tracker.kind : tracker_kind(o.tracker)};
  const std::string json = o.summary.empty() ? (out / "sweep.json").string() : o.summary;
  EtaProgress progress(o.trials * static_cast<int>(kinds.size() * sweep.values.size()));
  std::vector<servo::SweepValue> values;
  for (std::size_t i = 0; i < sweep.values.size() && !stop_requested(); ++i) {
    values.push_back(servo::run_sweep_value(
        o.scenario, models_dir(), sweep, i, kinds, o.trials, o.seed, renderer_kind(o.renderer),
        [&](int trial, const ServoResult& r) {
          std::fprintf(stderr, "%s %s trial %d/%d %s: %s, final %.3f mm %.3f deg %s\n", sweep.field.c_str(),
                       yaml::plain_number(sweep.values[i]).c_str(), trial + 1, o.trials, r.tracker.c_str(),
                       servo::succeeded(r, scenario.stop) ? "success" : "failure", 1e3 * r.final_t,
                       r.final_r / servo::kDegree, progress.done().c_str());
        }));
    if (!values.back().error.empty())
      std::fprintf(stderr, "%s %s: %s\n", sweep.field.c_str(), yaml::plain_number(sweep.values[i]).c_str(),
                   values.back().error.c_str());
    servo::write_sweep_json(sweep, values, json);
  }
  servo::print_sweep(std::cout, sweep, values);
  servo::plot_sweep(sweep, values, out.string());
  std::cout << "wrote " << json << ", " << (out / "sweep.png").string() << "\n";
  if (stop_requested())
    throw CommandOutcome(kExitInterrupted, "interrupted: " + std::to_string(values.size()) + " of " +
                                               std::to_string(sweep.values.size()) + " values swept, in " + json);
}

/// --replay: the folder of its files, --out or else the log's own.
fs::path replay_folder(const ServoOptions& o) {
  if (!o.out.empty()) return o.out;
  const fs::path log_folder = fs::path(o.replay).parent_path();
  return log_folder.empty() ? fs::path(".") : log_folder;
}

void run_command(const ServoOptions& o) {
  const bool on_workers = !o.scheduler.empty() || o.jobs > 0;
  // The workers read the scenario file again (its numeric fields set over it travel with
  // it, a renderer does not): refused rather than ignored.
  if (on_workers && !o.renderer.empty()) {
    const std::string option = o.jobs > 0 ? "--jobs" : "--scheduler";
    throw std::invalid_argument(option + " runs the trials on Dask workers, which --renderer does not reach: set "
                                "camera.renderer in the scenario file, or leave " + option +
                                " out to run the trials here");
  }
  Scenario scenario = servo::load_scenario(o.scenario, models_dir());
  if (const std::optional<servo::RendererKind> renderer = renderer_kind(o.renderer)) scenario.camera.renderer = *renderer;
  // Without Blender every trial would fail alike: say so once, before anything runs.
  if (scenario.camera.renderer == servo::RendererKind::kCycles) servo::blender_executable();
  if (on_workers) run_on_workers(o);
  // Runs and batches can take hours: Ctrl-C stops them at the next step, writing what is done.
  install_stop_on_sigint();
  if (!o.tracker.empty()) scenario.tracker.kind = tracker_kind(o.tracker);
  if (o.seed != 0) scenario.seed = o.seed;
  const fs::path out = o.out.empty() ? fs::path("out") / "servo" / scenario.name : fs::path(o.out);
  const std::string summary = o.summary.empty() ? (out / "summary.json").string() : o.summary;
  std::cerr << "scenario " << scenario.name << (scenario.description.empty() ? "" : ": " + scenario.description) << "\n";
  if (!o.replay.empty())
    run_servo_replay(scenario, o.replay, o.seed != 0 ? std::optional<unsigned>(o.seed) : std::nullopt,
                     replay_folder(o).string(), o.quiet);
  else if (!o.sweep.empty())
    run_sweep(o, out);
  else if (o.compare || o.trials > 1)
    run_batch(o, scenario, summary);
  else
    run_single(o, scenario, out, summary);
}

}  // namespace

std::string default_scenario_path() {
  namespace fs = std::filesystem;
  const fs::path installed = fs::path(models_dir()).parent_path() / "scenarios" / "default.yaml";
  return fs::is_regular_file(installed) ? installed.string() : ICGP_SOURCE_SCENARIOS_DIR "/default.yaml";
}

void register_servo_command(CLI::App& app) {
  auto o = std::make_shared<ServoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "servo", "Close the loop: simulated RGB-D camera -> tracker -> ViSP control law -> simulated robot, for a scenario");
  o->scenario = default_scenario_path();
  cmd->add_option("scenario", o->scenario, "Scenario file (YAML, see scenarios/)")->check(CLI::ExistingFile)->capture_default_str();
  cmd->add_option("--tracker", o->tracker, "Tracker in the loop instead of the scenario's: " + yaml::join(tracker_choices()))
      ->check(CLI::IsMember(tracker_choices()));
  CLI::Option* trials = cmd->add_option("--trials", o->trials,
                  "Batch: runs from random starts within the scenario's trial ranges (Ctrl-C stops it and writes "
                  "the trials done)")
      ->check(integer_in(1, kMaxTrials));
  cmd->add_option("--seed", o->seed, "Seed of the noise and of the random starts (default: the scenario's)")
      ->check(integer_in(0, std::numeric_limits<unsigned>::max()));
  CLI::Option* compare =
      cmd->add_flag("--compare", o->compare, "Run the oracle, visp and icgp trackers on identical trials, one table");
  CLI::Option* summary = cmd->add_option("--summary", o->summary, "Summary JSON (default: OUT/summary.json)");
  cmd->add_option("--out", o->out, "Folder for the log and plots (default: out/servo/<scenario name>)");
  CLI::Option* video =
      cmd->add_option("--video", o->video, "Overlay video (.avi) of a single run: estimated (red) and true (green) outline");
  CLI::Option* display = cmd->add_flag("--display", o->display, "Show the run in a ViSP window (needs an X display)");
  cmd->add_flag("--quiet", o->quiet, "No progress lines");
  CLI::Option* scheduler =
      cmd->add_option("--scheduler", o->scheduler,
                      "Batch: run the trials on the workers of this Dask scheduler (tcp://HOST:PORT), through "
                      "icgp's Python package; each worker needs the package and the scenario's files");
  CLI::Option* sweep = cmd->add_option("--sweep", o->sweep,
                  "FIELD=V1,V2,...: the trials (--trials, --compare) at each value of a numeric scenario field, "
                  "e.g. camera.latency_ms=0,50,100; writes OUT/sweep.json and OUT/sweep.png");
  CLI::Option* jobs = cmd->add_option("--jobs", o->jobs, "Batch: run the trials on this many local worker processes (Dask)")
      ->check(integer_in(1, 1024))
      ->excludes(scheduler);
  cmd->add_option("--renderer", o->renderer,
                  "Renderer of the camera's images instead of the scenario's camera.renderer: " +
                      yaml::join(renderer_choices()) + " (not with --jobs or --scheduler)")
      ->check(CLI::IsMember(renderer_choices()));
  cmd->add_option("--replay", o->replay,
                  "A run's log.csv: render its camera path again (with --renderer, or the scenario's renderer) and "
                  "track it open-loop with the scenario's tracker, seeded as the run (its summary.json); writes "
                  "OUT/replay.csv and OUT/replay.json (default OUT: the log's folder)")
      ->check(CLI::ExistingFile)
      ->excludes(trials)
      ->excludes(compare)
      ->excludes(sweep)
      ->excludes(scheduler)
      ->excludes(jobs)
      ->excludes(video)
      ->excludes(display)
      ->excludes(summary);
  cmd->callback([o] { run_command(*o); });
}

}  // namespace icgp::app
