// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/servo/servo_replay.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>

#include "icgp/base/stop_request.h"
#include "icgp/eval/json_object.h"
#include "icgp/eval/metrics.h"
#include "icgp/io/yaml_reader.h"
#include "icgp/servo/servo_controller.h"
#include "icgp/servo/servo_report.h"
#include "icgp/servo/simulated_robot.h"
#include "icgp/visp/conversions.h"
#include "tracker_in_loop.h"

namespace icgp::servo {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMm = 1e3;                    // metres -> millimetres
constexpr double kDeg = 1.0 / kDegree;         // radians -> degrees

/// A recorded time is the run's k / rate_hz, written with 9 digits.
constexpr double kTimeTolerance = 1e-6;  ///< seconds
/// The run's camera start, read back from its 17-digit log, is where the robot starts.
constexpr double kStartTolerance = 1e-6;  ///< metres, radians

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

std::string where(const Scenario& scenario) {
  return scenario.file.empty() ? "scenario '" + scenario.name + "'" : scenario.file;
}

/// Replay moves the camera along its recorded path and the object as the scenario moves it;
/// an arm that carries the object or the gripper moves them along a path the log lacks.
void check_robot_replayable(const Scenario& scenario) {
  if (scenario.robot == RobotKind::kFreeFlyingCamera || scenario.robot == RobotKind::kViper850EyeInHand) return;
  throw std::invalid_argument(where(scenario) + ": robot " + name_of(scenario.robot, robot_names()) +
                              ": replay renders a run's recorded camera path, and this robot moves the " +
                              (scenario.grasp ? "gripper" : "object") +
                              " along a path the log does not record (replay free_flying or viper850_eye_in_hand "
                              "scenarios)");
}

/// The summary beside the log names the scenario the run was of.
void check_summary_scenario(const Scenario& scenario, const RecordedRun& run) {
  if (!run.scenario || *run.scenario == scenario.name) return;
  throw LogError(run.summary + ": scenario: the log is of a run of '" + *run.scenario + "', not of '" + scenario.name +
                 "' (" + where(scenario) + "): replay it with its own scenario");
}

/// Step k of a run is at k / rate_hz, and a run has at most simulated_steps of them.
void check_step_times(const Scenario& scenario, const RecordedRun& run) {
  const double dt = 1.0 / scenario.camera.rate_hz;
  const double most = simulated_steps(scenario.stop.max_time, scenario.camera.rate_hz);
  for (std::size_t k = 0; k < run.steps.size(); ++k) {
    const RecordedStep& step = run.steps[k];
    const std::string at = run.log + ":" + std::to_string(step.line) + ": column 'time': ";
    if (static_cast<double>(k) >= most)
      throw LogError(at + "step " + std::to_string(k) + " is beyond the " + yaml::plain_number(most) +
                     " steps of the scenario's stop.max_time " + yaml::plain_number(scenario.stop.max_time) +
                     " s: the log is not a run of " + where(scenario));
    const double expected = static_cast<double>(k) * dt;
    if (std::abs(step.time - expected) > kTimeTolerance)
      throw LogError(at + yaml::plain_number(step.time) + " s, but step " + std::to_string(k) + " of the scenario's " +
                     yaml::plain_number(scenario.camera.rate_hz) + " Hz camera is at " + yaml::plain_number(expected) +
                     " s: the log is not a run of " + where(scenario));
  }
}

/// The run's first step is where the scenario's robot starts the camera with this seed (an
/// arm's calibration errors are drawn from it).
void check_camera_start(const Scenario& scenario, const RecordedRun& run, const vpHomogeneousMatrix& start_wMc,
                        unsigned seed) {
  const PoseError off = pose_error(run.steps.front().wMc, start_wMc);
  if (off.translation <= kStartTolerance && off.rotation <= kStartTolerance) return;
  char distance[96];
  std::snprintf(distance, sizeof distance, "%.3f mm and %.3f deg", off.translation * kMm, off.rotation * kDeg);
  throw LogError(run.log + ":" + std::to_string(run.steps.front().line) +
                 ": columns 'camera_tx' to 'camera_tuz': the camera starts " + distance + " from where " +
                 where(scenario) + " starts it with seed " + std::to_string(seed) +
                 ": the log is not a run of this scenario and seed");
}

/// The frame of `step`, the camera coming from `previous_wMc` (motion blur), given to the
/// tracker unless the sensor dropped it or the run's tracker skipped it.
ReplayFrame replay_step(const RecordedStep& step, const vpHomogeneousMatrix& previous_wMc, RgbdSimulator& simulator,
                        TrackerInLoop& tracker) {
  ReplayFrame frame;
  frame.time = step.time;
  frame.recorded_track_t = step.track_t;
  frame.recorded_track_r = step.track_r;
  const auto begin = Clock::now();
  const RgbdCapture& capture = simulator.capture(step.time, step.wMc, previous_wMc);
  frame.render_ms = ms_between(begin, Clock::now());
  frame.dropped = capture.dropped;
  frame.skipped = !capture.dropped && step.skipped;
  if (!frame.dropped && !frame.skipped) {
    const PoseEstimate& taken = tracker.take(capture);
    frame.track_ms = taken.track_ms;
    frame.cues = taken.cues;
  }
  const PoseEstimate& estimate = tracker.estimate();
  frame.lost = estimate.lost;
  // No truth to compare with while the object is away, no estimate before it is found.
  const bool comparable = simulator.object_present(step.time) && tracker.started();
  const PoseError error = pose_error(estimate.cMo, capture.cMo_true);
  frame.track_t = comparable ? error.translation : kNaN;
  frame.track_r = comparable ? error.rotation : kNaN;
  return frame;
}

}  // namespace

unsigned replay_seed(const RecordedRun& run, const Scenario& scenario, std::optional<unsigned> requested) {
  if (!run.seed) return requested.value_or(scenario.seed);
  if (requested && *requested != *run.seed)
    throw std::invalid_argument("--seed " + std::to_string(*requested) + ": the run of " + run.log + " had seed " +
                                std::to_string(*run.seed) + " (" + run.summary +
                                "), and another seed draws another cell: leave --seed out");
  return *run.seed;
}

ReplayResult replay_camera_path(const Scenario& scenario, const RecordedRun& run, unsigned seed,
                                const ReplayOptions& options) {
  check_robot_replayable(scenario);
  check_run_length(scenario);
  check_summary_scenario(scenario, run);
  check_step_times(scenario, run);
  const TrueCalibration truth = draw_true_calibration(scenario, seed);
  // The robot stays at its start: it places the camera, the object and the background
  // there, as it did for the run.
  const std::unique_ptr<SimulatedRobot> robot = make_robot(scenario, truth);
  const vpHomogeneousMatrix start_wMc = robot->world_T_camera();
  check_camera_start(scenario, run, start_wMc, seed);
  RgbdSimulator simulator(scenario, truth, start_wMc, initial_world_T_object(scenario, *robot), seed);
  const std::unique_ptr<PoseEstimator> estimator = make_pose_estimator(scenario.tracker, scenario, simulator);
  // The same captures, in the same order, as the run made: the sensor's noise stream then
  // gives every frame the run's noise.
  const vpHomogeneousMatrix desired = to_homogeneous_matrix(scenario.desired_cMo);
  const vpHomogeneousMatrix goal =
      scenario.control.taught_by_showing
          ? shown_goal(*robot, simulator, *estimator, desired, scenario.tracker.init_by_detection)
          : desired;
  TrackerInLoop tracker(*estimator, scenario.tracker, goal, {});
  if (tracker.starts_from_truth()) tracker.start_at_truth(simulator.capture(0.0, start_wMc, start_wMc));

  ReplayResult result;
  result.log = run.log;
  result.scenario = scenario.name;
  result.tracker = estimator->name();
  result.renderer = name_of(scenario.camera.renderer, renderer_names());
  result.seed = seed;
  result.recorded_steps = run.steps.size();
  const vpHomogeneousMatrix* previous_wMc = &start_wMc;
  for (const RecordedStep& step : run.steps) {
    result.frames.push_back(replay_step(step, *previous_wMc, simulator, tracker));
    previous_wMc = &step.wMc;
    if (options.on_frame) options.on_frame(result.frames.back(), result.frames.size(), run.steps.size());
    if (stop_requested()) break;
  }
  result.interrupted = result.frames.size() < run.steps.size();
  return result;
}

namespace {

/// Mean of the finite values; NaN when there are none.
double finite_mean(const std::vector<double>& values) {
  double sum = 0.0;
  int n = 0;
  for (double v : values)
    if (std::isfinite(v)) {
      sum += v;
      ++n;
    }
  return n > 0 ? sum / n : kNaN;
}

double finite_max(const std::vector<double>& values) {
  double most = kNaN;
  for (double v : values)
    if (std::isfinite(v) && !(v <= most)) most = v;
  return most;
}

/// A cue's key in replay.csv: its name, or with its camera when the cue reads several.
std::vector<std::string> cue_keys(const std::vector<CueSummary>& cues) {
  std::map<std::string, int> count;
  for (const CueSummary& c : cues) ++count[c.cue];
  std::vector<std::string> keys;
  for (const CueSummary& c : cues) keys.push_back(count[c.cue] > 1 ? c.cue + "_" + c.camera : c.cue);
  return keys;
}

/// The cues the tracker reported on any frame, in its order, with their statistics.
std::vector<CueSummary> summarise_cues(const std::vector<ReplayFrame>& frames) {
  std::vector<CueSummary> cues;
  std::map<std::pair<std::string, std::string>, std::vector<const ModalityQuality*>> measured;
  for (const ReplayFrame& frame : frames)
    for (const CueFit& fit : frame.cues) {
      auto it = std::find_if(cues.begin(), cues.end(),
                             [&](const CueSummary& c) { return c.cue == fit.cue && c.camera == fit.camera; });
      if (it == cues.end()) it = cues.insert(cues.end(), CueSummary{fit.cue, fit.camera});
      ++it->frames;
      if (fit.quality.abstained)
        ++it->abstained;
      else
        measured[{fit.cue, fit.camera}].push_back(&fit.quality);
    }
  for (CueSummary& c : cues) {
    std::vector<double> scores, sigmas, valid;
    for (const ModalityQuality* q : measured[{c.cue, c.camera}]) {
      scores.push_back(q->score);
      sigmas.push_back(q->sigma);
      valid.push_back(q->valid_fraction);
    }
    c.mean_score = finite_mean(scores);
    c.min_score = scores.empty() ? kNaN : *std::min_element(scores.begin(), scores.end());
    c.mean_sigma = finite_mean(sigmas);
    c.max_sigma = finite_max(sigmas);
    c.mean_valid_fraction = finite_mean(valid);
  }
  return cues;
}

/// Pixels for the image cues; the depth cue's sigma is metres at 1 m (ModalityQuality).
const char* sigma_unit(const std::string& cue) { return cue == "depth" ? "m at 1 m" : "px"; }

}  // namespace

ReplaySummary summarise_replay(const ReplayResult& replay) {
  ReplaySummary s;
  std::vector<double> t, r, recorded_t, recorded_r, render_ms;
  for (const ReplayFrame& f : replay.frames) {
    ++s.frames;
    s.lost += f.lost;
    s.dropped += f.dropped;
    s.skipped += f.skipped;
    t.push_back(f.track_t);
    r.push_back(f.track_r);
    recorded_t.push_back(f.recorded_track_t);
    recorded_r.push_back(f.recorded_track_r);
    if (!f.dropped) render_ms.push_back(f.render_ms);
  }
  s.mean_track_t = finite_mean(t);
  s.max_track_t = finite_max(t);
  s.mean_track_r = finite_mean(r);
  s.max_track_r = finite_max(r);
  s.recorded_mean_track_t = finite_mean(recorded_t);
  s.recorded_mean_track_r = finite_mean(recorded_r);
  s.median_render_ms = render_ms.empty() ? kNaN : median(render_ms);
  s.cues = summarise_cues(replay.frames);
  return s;
}

void print_replay(std::ostream& out, const ReplayResult& replay) {
  const ReplaySummary s = summarise_replay(replay);
  char line[256];
  std::snprintf(line, sizeof line, "replay         %s: %d of %zu steps, rendered with %s (seed %u)%s\n",
                replay.log.c_str(), s.frames, replay.recorded_steps, replay.renderer.c_str(), replay.seed,
                replay.interrupted ? ", interrupted" : "");
  out << line;
  out << "tracker        " << replay.tracker << "\n";
  std::snprintf(line, sizeof line, "tracker error  mean %s mm, %s deg; max %s mm, %s deg (the run's own: mean %s mm, %s deg)\n",
                fixed(s.mean_track_t * kMm, 3).c_str(), fixed(s.mean_track_r * kDeg, 3).c_str(),
                fixed(s.max_track_t * kMm, 3).c_str(), fixed(s.max_track_r * kDeg, 3).c_str(),
                fixed(s.recorded_mean_track_t * kMm, 3).c_str(),
                fixed(s.recorded_mean_track_r * kDeg, 3).c_str());
  out << line;
  std::snprintf(line, sizeof line, "lost           %d of %d frames (dropped %d, skipped %d); median render %s ms\n",
                s.lost, s.frames, s.dropped, s.skipped, fixed(s.median_render_ms, 1).c_str());
  out << line;
  if (s.cues.empty()) {
    out << "cues           the tracker reports none\n";
    return;
  }
  std::snprintf(line, sizeof line, "%-10s %-8s %7s %8s %11s %10s %15s %10s\n", "cue", "camera", "frames", "no data",
                "score mean", "score min", "sigma mean", "valid");
  out << line;
  for (const CueSummary& c : s.cues) {
    const std::string sigma = std::isfinite(c.mean_sigma) ? data_number(c.mean_sigma) : "-";
    std::snprintf(line, sizeof line, "%-10s %-8s %7d %8d %11s %10s %15s %10s  (sigma in %s)\n", c.cue.c_str(),
                  c.camera.c_str(), c.frames, c.abstained, fixed(c.mean_score, 3).c_str(),
                  fixed(c.min_score, 3).c_str(), sigma.c_str(),
                  fixed(c.mean_valid_fraction, 3).c_str(), sigma_unit(c.cue));
    out << line;
  }
}

void write_replay_csv(const ReplayResult& replay, const std::string& path) {
  const std::vector<CueSummary> cues = summarise_cues(replay.frames);
  const std::vector<std::string> keys = cue_keys(cues);
  std::string text =
      "time,renderer,track_t_mm,track_r_deg,lost,dropped,skipped,render_ms,track_ms,recorded_track_t_mm,"
      "recorded_track_r_deg";
  for (const std::string& key : keys)
    text += "," + key + "_score," + key + "_sigma," + key + "_valid_fraction," + key + "_abstained";
  text += "\n";
  for (const ReplayFrame& f : replay.frames) {
    text += data_number(f.time) + "," + replay.renderer + "," + data_number(f.track_t * kMm) + "," + data_number(f.track_r * kDeg) +
            "," + (f.lost ? "1" : "0") + "," + (f.dropped ? "1" : "0") + "," + (f.skipped ? "1" : "0") + "," +
            data_number(f.render_ms) + "," + data_number(f.track_ms) + "," + data_number(f.recorded_track_t * kMm) + "," +
            data_number(f.recorded_track_r * kDeg);
    for (const CueSummary& c : cues) {
      const auto fit = std::find_if(f.cues.begin(), f.cues.end(),
                                    [&](const CueFit& x) { return x.cue == c.cue && x.camera == c.camera; });
      if (fit == f.cues.end()) {
        text += ",NaN,NaN,NaN,NaN";  // the tracker did not track this frame
        continue;
      }
      const ModalityQuality& q = fit->quality;
      text += "," + data_number(q.score) + "," + data_number(q.sigma) + "," + data_number(q.valid_fraction) + "," +
              (q.abstained ? "1" : "0");
    }
    text += "\n";
  }
  write_text_file(path, text, "replay CSV");
}

void write_replay_json(const ReplayResult& replay, const std::string& path) {
  const ReplaySummary s = summarise_replay(replay);
  std::vector<JsonObject> cues;
  for (const CueSummary& c : s.cues)
    cues.push_back(JsonObject()
                       .add("cue", c.cue)
                       .add("camera", c.camera)
                       .add("frames", c.frames)
                       .add("abstained_frames", c.abstained)
                       .add("score", JsonObject().add("mean", c.mean_score).add("min", c.min_score))
                       .add("sigma", JsonObject().add("mean", c.mean_sigma).add("max", c.max_sigma))
                       .add("sigma_unit", sigma_unit(c.cue))
                       .add("valid_fraction_mean", c.mean_valid_fraction));
  JsonObject()
      .add("log", replay.log)
      .add("scenario", replay.scenario)
      .add("tracker", replay.tracker)
      .add("renderer", replay.renderer)
      .add("seed", static_cast<double>(replay.seed))
      .add("frames", s.frames)
      .add("recorded_steps", static_cast<int>(replay.recorded_steps))
      .add("lost_frames", s.lost)
      .add("dropped_frames", s.dropped)
      .add("skipped_frames", s.skipped)
      .add("track_t_mm", JsonObject().add("mean", s.mean_track_t * kMm).add("max", s.max_track_t * kMm))
      .add("track_r_deg", JsonObject().add("mean", s.mean_track_r * kDeg).add("max", s.max_track_r * kDeg))
      .add("recorded_track_t_mm", JsonObject().add("mean", s.recorded_mean_track_t * kMm))
      .add("recorded_track_r_deg", JsonObject().add("mean", s.recorded_mean_track_r * kDeg))
      .add("median_render_ms", s.median_render_ms)
      .add("cues", cues)
      .add("interrupted", replay.interrupted)
      .write(path);
}

}  // namespace icgp::servo
