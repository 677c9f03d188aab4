// SPDX-License-Identifier: GPL-2.0-or-later
// A run's log holds the camera's true pose at each step, and a replay of that path renders
// the run's own frames again: with the run's seed and renderer the tracker errs as it did.
// Logs that are not runs of the scenario, or not logs at all, are refused naming the file,
// the line and the column.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "icgp/base/stop_request.h"
#include "icgp/servo/recorded_run.h"
#include "icgp/servo/scenario.h"
#include "icgp/servo/servo_controller.h"
#include "icgp/servo/servo_replay.h"
#include "icgp/servo/servo_report.h"
#include "icgp/servo/servo_run.h"
#include "icgp/visp/conversions.h"
#include "../unit/test_temp_dir.h"

using namespace icgp::servo;
using icgp::test::TempDir;

namespace {

/// tests/servo/data/replay_short.yaml: 1.5 s of a realistic cell's approach with a noisy
/// sensor that drops frames, started by detection (seed 7).
Scenario replay_short() {
  return load_scenario(ICGP_TEST_DATA_DIR "/../servo/data/replay_short.yaml", ICGP_MODELS_DIR);
}

ServoRunOptions quiet(unsigned seed) {
  ServoRunOptions options;
  options.progress = false;
  options.seed = seed;
  return options;
}

/// A run's log and summary in `dir`, as `icgp servo` writes them.
std::string write_run(const TempDir& dir, const ServoResult& run, const StopSpec& stop) {
  const std::string log = dir.file("run/log.csv");
  write_step_csv(run, log);
  write_summary_json({summarise({run}, stop)}, dir.file("run/summary.json"));
  return log;
}

/// The columns a replay needs and a step per line of `steps` (time and camera pose).
std::string camera_log(const std::vector<std::string>& steps) {
  std::string text = "time,camera_tx,camera_ty,camera_tz,camera_tux,camera_tuy,camera_tuz\n";
  for (const std::string& step : steps) text += step + "\n";
  return text;
}

/// The message of what read_recorded_run throws for the log `text`.
std::string refusal(const TempDir& dir, const std::string& text) {
  const std::string log = dir.write("bad/log.csv", text);
  try {
    read_recorded_run(log);
  } catch (const LogError& e) {
    return e.what();
  }
  FAIL("the log was read: " << text);
  return {};
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// Clears the process-wide stop request when a test ends, however it ends.
struct StopRequestReset {
  ~StopRequestReset() { icgp::clear_stop_request(); }
};

}  // namespace

TEST_CASE("replay: a free-flying camera's log holds its true pose at each step, from the scenario's start") {
  Scenario scenario = replay_short();
  scenario.tracker.kind = TrackerKind::kOracle;
  const ServoResult run = run_servo(scenario, quiet(scenario.seed));
  REQUIRE(run.steps.size() > 10);

  // The free-flying camera starts at the world's origin and the object stands still where
  // the scenario's start pose puts it: wMo = wMc(0) start_cMo. Every step's true cMo is
  // then its camera pose's inverse times wMo.
  const vpHomogeneousMatrix start_cMo = icgp::to_homogeneous_matrix(scenario.initial_cMo);
  CHECK(run.steps.front().wMc_true == vpHomogeneousMatrix());
  const vpHomogeneousMatrix wMo = run.steps.front().wMc_true * start_cMo;
  for (const ServoStep& step : run.steps) {
    const PoseError off = pose_error(step.wMc_true.inverse() * wMo, step.cMo_true);
    CHECK(off.translation < 1e-9);
    CHECK(off.rotation < 1e-9);
  }
  // It moved: poses all zero would not show that.
  CHECK(pose_error(run.steps.back().wMc_true, run.steps.front().wMc_true).translation > 0.005);

  // The log holds those poses to the last digit, after the columns it had before.
  const TempDir dir("icgp-test-servo-replay-log");
  const std::string log = write_run(dir, run, scenario.stop);
  std::ifstream in(log);
  std::string header;
  std::getline(in, header);
  CHECK(header.size() > 6);
  CHECK(header.rfind("time,servo_t_mm,servo_r_deg,track_t_mm,track_r_deg,error_norm,", 0) == 0);
  CHECK(header.find(",command_delay_ms,camera_tx,camera_ty,camera_tz,camera_tux,camera_tuy,camera_tuz") !=
        std::string::npos);
  const RecordedRun recorded = read_recorded_run(log);
  REQUIRE(recorded.steps.size() == run.steps.size());
  for (std::size_t k = 0; k < run.steps.size(); ++k) {
    INFO("step " << k);
    const PoseError off = pose_error(recorded.steps[k].wMc, run.steps[k].wMc_true);
    CHECK(off.translation < 1e-12);
    CHECK(off.rotation < 1e-12);
    CHECK(recorded.steps[k].line == static_cast<int>(k) + 2);
  }
  // At step 0 the logged pose puts the object where the scenario starts it.
  const PoseError start = pose_error(recorded.steps.front().wMc.inverse() * wMo, start_cMo);
  CHECK(start.translation < 1e-12);
  CHECK(recorded.seed == scenario.seed);
  CHECK(recorded.scenario == scenario.name);
}

TEST_CASE("replay: the run's own renderer and seed render its frames again, and the tracker errs as it did") {
  const Scenario scenario = replay_short();
  const ServoResult run = run_servo(scenario, quiet(scenario.seed));
  const TempDir dir("icgp-test-servo-replay-same");
  const RecordedRun recorded = read_recorded_run(write_run(dir, run, scenario.stop));
  const unsigned seed = replay_seed(recorded, scenario, std::nullopt);
  REQUIRE(seed == run.seed);

  const ReplayResult replay = replay_camera_path(scenario, recorded, seed);
  REQUIRE(replay.frames.size() == run.steps.size());
  CHECK_FALSE(replay.interrupted);
  CHECK(replay.renderer == "opengl");
  // The cell is the run's (its calibration, object and background drawn from the seed), and
  // the sensor's captures come in the run's order, so the noise stream gives every frame the
  // run's noise and drops the run's frames; the tracker, deterministic, errs as it did. The
  // poses are read back from 17 digits through θu, a rotation 1e-16 off: 1 % is room for a
  // pixel at an edge that this could flip, where the error of a frame tracked anew would
  // differ by far more.
  int dropped = 0;
  for (std::size_t k = 0; k < run.steps.size(); ++k) {
    INFO("step " << k << " at " << run.steps[k].time << " s");
    CHECK(replay.frames[k].dropped == run.steps[k].dropped);
    dropped += replay.frames[k].dropped;
    CHECK(replay.frames[k].lost == run.steps[k].lost);
    CHECK(replay.frames[k].track_t == Approx(run.steps[k].track_t).epsilon(0.01).margin(1e-6));
    CHECK(replay.frames[k].track_r == Approx(run.steps[k].track_r).epsilon(0.01).margin(1e-5));
  }
  CHECK(dropped > 0);  // the scenario's 10 % drops: the noise stream was followed

  const ReplaySummary s = summarise_replay(replay);
  INFO("replay mean " << 1e3 * s.mean_track_t << " mm, run's " << 1e3 * run.mean_track_t << " mm");
  CHECK(s.mean_track_t == Approx(run.mean_track_t).epsilon(0.01));
  CHECK(s.mean_track_r == Approx(run.mean_track_r).epsilon(0.01));
  CHECK(s.recorded_mean_track_t == Approx(run.mean_track_t).epsilon(1e-6));
  // icgp reports its region and depth cues on every frame it tracked.
  REQUIRE(s.cues.size() == 2);
  CHECK(s.cues[0].cue == "region");
  CHECK(s.cues[1].cue == "depth");
  for (const CueSummary& cue : s.cues) {
    CHECK(cue.frames > 0);
    CHECK(cue.mean_score > 0.5);
    CHECK(cue.mean_score <= 1.0);
    CHECK(cue.mean_sigma > 0.0);
  }

  // replay.csv: a line per frame with its cues; replay.json: the summary.
  write_replay_csv(replay, dir.file("replay/replay.csv"));
  write_replay_json(replay, dir.file("replay/replay.json"));
  const std::vector<std::string> lines = lines_of(icgp::test::read_bytes(dir.path() / "replay/replay.csv"));
  REQUIRE(lines.size() == 1 + replay.frames.size());
  CHECK(lines[0].rfind("time,renderer,track_t_mm,track_r_deg,lost,", 0) == 0);
  CHECK(lines[0].find(",region_score,region_sigma,region_valid_fraction,region_abstained,depth_score,") !=
        std::string::npos);
  CHECK(lines[1].find(",opengl,") != std::string::npos);
}

TEST_CASE("replay: a stop request ends a replay after the frame it comes in, marked interrupted") {
  const StopRequestReset reset;
  Scenario scenario = replay_short();
  scenario.tracker.kind = TrackerKind::kOracle;
  const ServoResult run = run_servo(scenario, quiet(scenario.seed));
  const TempDir dir("icgp-test-servo-replay-stop");
  const RecordedRun recorded = read_recorded_run(write_run(dir, run, scenario.stop));
  ReplayOptions options;
  options.on_frame = [](const ReplayFrame&, std::size_t done, std::size_t) {
    if (done == 3) icgp::request_stop();
  };
  const ReplayResult replay = replay_camera_path(scenario, recorded, recorded.seed.value(), options);
  CHECK(replay.interrupted);
  CHECK(replay.frames.size() == 3);
  CHECK(replay.recorded_steps == run.steps.size());
}

TEST_CASE("replay: a log that cannot be read is refused naming the file, the line and the column") {
  const TempDir dir("icgp-test-servo-replay-bad");
  const std::string good = "0,0,0,0,0,0,0";
  CHECK_THAT(refusal(dir, "time,camera_tx,camera_ty,camera_tz,camera_tux,camera_tuy\n0,0,0,0,0,0\n"),
             Catch::Contains("bad/log.csv:1: no column 'camera_tuz'"));
  CHECK_THAT(refusal(dir, "servo_t_mm\n1\n"), Catch::Contains("log.csv:1: no column 'time'"));
  CHECK_THAT(refusal(dir, camera_log({good, "0.0333,0,fast,0,0,0,0"})),
             Catch::Contains("log.csv:3: column 'camera_ty': expected a number, got 'fast'"));
  CHECK_THAT(refusal(dir, camera_log({good, "0.0333,0,0,NaN,0,0,0"})),
             Catch::Contains("log.csv:3: column 'camera_tz': expected a finite number, got 'NaN'"));
  CHECK_THAT(refusal(dir, camera_log({good, "0.0333,0,0,0,4,0,0"})),
             Catch::Contains("log.csv:3: column 'camera_tux' to 'camera_tuz': (4.000000, 0.000000, 0.000000) is "
                             "not a rotation's θu vector"));
  CHECK_THAT(refusal(dir, camera_log({good, "0.0333,0,0,0,0,0"})),
             Catch::Contains("log.csv:3: 6 values, but the header has 7 columns"));
  CHECK_THAT(refusal(dir, camera_log({})), Catch::Contains("log.csv: no steps, only the header"));
  CHECK_THAT(refusal(dir, ""), Catch::Contains("log.csv: empty"));
  CHECK_THAT(refusal(dir, "time,skipped,camera_tx,camera_ty,camera_tz,camera_tux,camera_tuy,camera_tuz\n"
                          "0,yes,0,0,0,0,0,0\n"),
             Catch::Contains("log.csv:2: column 'skipped': expected 0 or 1, got 'yes'"));
  // A summary.json beside it is read for its seed.
  const std::string log = dir.write("with_summary/log.csv", camera_log({good}));
  dir.write("with_summary/summary.json", "{\"scenario\": \"x\", \"seed\": -3}\n");
  CHECK_THROWS_WITH(read_recorded_run(log), Catch::Contains("summary.json: seed: expected an integer in [0, "));
}

TEST_CASE("replay: a log that is not a run of the scenario is refused before anything is rendered") {
  const TempDir dir("icgp-test-servo-replay-mismatch");
  const Scenario scenario = replay_short();  // 30 Hz, 1.5 s: 46 steps
  const auto replay_of = [&](const std::string& name, const std::string& text, const Scenario& s) {
    return replay_camera_path(s, read_recorded_run(dir.write(name + "/log.csv", text)), 7);
  };
  CHECK_THROWS_WITH(replay_of("rate", camera_log({"0,0,0,0,0,0,0", "0.05,0,0,0,0,0,0"}), scenario),
                    Catch::Contains("rate/log.csv:3: column 'time': 0.05 s, but step 1 of the scenario's 30 Hz "
                                    "camera is at 0.0333") &&
                        Catch::Contains("the log is not a run of"));
  std::vector<std::string> too_many;
  for (int k = 0; k < 47; ++k) too_many.push_back(std::to_string(k / 30.0) + ",0,0,0,0,0,0");
  CHECK_THROWS_WITH(replay_of("long", camera_log(too_many), scenario),
                    Catch::Contains("long/log.csv:48: column 'time': step 46 is beyond the 46 steps"));
  CHECK_THROWS_WITH(replay_of("start", camera_log({"0,0.01,0,0,0,0,0"}), scenario),
                    Catch::Contains("start/log.csv:2: columns 'camera_tx' to 'camera_tuz': the camera starts 10.000 "
                                    "mm and 0.000 deg from where"));
  dir.write("other/summary.json", "{\"scenario\": \"default\", \"seed\": 7}\n");
  CHECK_THROWS_WITH(replay_of("other", camera_log({"0,0,0,0,0,0,0"}), scenario),
                    Catch::Contains("other/summary.json: scenario: the log is of a run of 'default', not of "
                                    "'replay_short'"));
  const Scenario grasp = load_scenario(ICGP_TEST_DATA_DIR "/../../scenarios/grasp_approach.yaml", ICGP_MODELS_DIR);
  CHECK_THROWS_WITH(replay_of("grasp", camera_log({"0,0,0,0,0,0,0"}), grasp),
                    Catch::Contains("grasp_approach.yaml: robot viper850_grasp: replay renders a run's recorded "
                                    "camera path, and this robot moves the gripper"));
}

TEST_CASE("replay: the seed is the run's summary's, else the one asked for, else the scenario's") {
  Scenario scenario;
  scenario.seed = 4;
  RecordedRun run;
  run.log = "out/log.csv";
  CHECK(replay_seed(run, scenario, std::nullopt) == 4);
  CHECK(replay_seed(run, scenario, 9u) == 9);
  run.seed = 7;
  run.summary = "out/summary.json";
  CHECK(replay_seed(run, scenario, std::nullopt) == 7);
  CHECK(replay_seed(run, scenario, 7u) == 7);
  CHECK_THROWS_WITH(replay_seed(run, scenario, 9u),
                    Catch::Contains("--seed 9: the run of out/log.csv had seed 7 (out/summary.json)"));
}
