// SPDX-License-Identifier: GPL-2.0-or-later
// Sweeps of a scenario field: the field written into the file's document and read as the
// file's own values are (errors naming it), the list of values, and a sweep of the PBVS gain
// with a frame of latency that finds the delay bound's onset, with the same starts at every
// value.
#include <catch2/catch.hpp>
#include <sstream>
#include <string>

#include "../unit/test_temp_dir.h"
#include "icgp/servo/scenario.h"
#include "icgp/servo/servo_sweep.h"

using Catch::Matchers::Contains;
using namespace icgp::servo;

namespace {

/// An oracle PBVS loop at 20 Hz with one frame of latency and a constant gain of 10 /s.
const std::string kDelayed =
    "profile: ideal\n"
    "object: {model: textured_box}\n"
    "camera: {color: {width: 160, height: 120, focal: 150}, rate_hz: 20, latency_ms: 50}\n"
    "start: {t: [0.005, 0, 0.35], r_deg: [131.2, 26.8, -37.57]}\n"
    "desired: {t: [0, 0, 0.35], r_deg: [131.2, 26.8, -37.57]}\n"
    "tracker: {type: oracle}\n"
    "control: {law: pbvs, gain: 10, max_linear_velocity: 10, max_angular_velocity_deg: 3000}\n"
    "stop: {translation_mm: 0.1, rotation_deg: 0.1, max_time: 6}\n"
    "trials: {translation_mm: 3, rotation_deg: 0}\n";

/// The ScenarioError message of loading `file` with `field` set to `value`; "" if none.
std::string override_error(const std::string& file, const std::string& field, double value) {
  try {
    load_scenario(file, ICGP_MODELS_DIR, {{field, value}});
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("sweep: a field set by its key path is read as the file's own value", "[servo][sweep]") {
  const icgp::test::TempDir dir("icgp-test-sweep");
  const std::string file = dir.write("delayed.yaml", kDelayed);
  CHECK(load_scenario(file, ICGP_MODELS_DIR, {{"camera.latency_ms", 100}}).camera.latency == Approx(0.1));
  CHECK(load_scenario(file, ICGP_MODELS_DIR, {{"control.gain", 3}}).control.gain.at_zero == 3.0);
  // A section the file leaves out is made.
  const Scenario s = load_scenario(file, ICGP_MODELS_DIR, {{"robot_response.lag_ms", 20}});
  CHECK(s.robot_response.lag == Approx(0.02));

  CHECK_THAT(override_error(file, "camera.latency_mss", 10), Contains(file + ": camera.latency_mss"));
  CHECK_THAT(override_error(file, "camera.latency_ms", -5),
             Contains(file + ": camera.latency_ms: expected a number in [0, 86400000], got -5"));
  CHECK_THAT(override_error(file, "tracker.type", 1),
             Contains(file + ": tracker.type: holds 'oracle', not a number: only a numeric field can be set to 1"));
  CHECK_THAT(override_error(file, "camera.color", 1), Contains(file + ": camera.color: holds a map, not a number"));
  CHECK_THAT(override_error(file, "control.gain.at_zero", 1), Contains(file + ": control.gain: is not a section"));
  CHECK_THAT(override_error(file, "camera..rate_hz", 1), Contains("is not a field (an empty key)"));
}

TEST_CASE("sweep: FIELD=V1,V2,... is read, or refused naming what is wrong", "[servo][sweep]") {
  const SweepSpec sweep = parse_sweep("camera.latency_ms=0,33.3,1e2");
  CHECK(sweep.field == "camera.latency_ms");
  CHECK(sweep.values == std::vector<double>{0, 33.3, 100});
  CHECK_THROWS_WITH(parse_sweep("camera.latency_ms"), Contains("expected FIELD=V1,V2,..."));
  CHECK_THROWS_WITH(parse_sweep("=1,2"), Contains("expected FIELD=V1,V2,..."));
  CHECK_THROWS_WITH(parse_sweep("control.gain=1,fast"),
                    Contains("--sweep control.gain: expected a list of numbers, got 'fast'"));
  CHECK_THROWS_WITH(parse_sweep("control.gain=1,,2"), Contains("got ''"));
  CHECK_THROWS_WITH(parse_sweep("control.gain="), Contains("no values given"));
  CHECK_THROWS_WITH(parse_sweep("control.gain=1,nan"), Contains("got 'nan'"));
}

TEST_CASE("sweep: the PBVS gain with a frame of latency succeeds below the delay bound, not above",
          "[servo][sweep][textbook]") {
  // With d = 1 frame of delay at T = 50 ms the loop is stable for λ < 2 sin(π/6) / T = 20 /s.
  const icgp::test::TempDir dir("icgp-test-sweep");
  const std::string file = dir.write("delayed.yaml", kDelayed);
  const SweepSpec sweep = parse_sweep("control.gain=16,22");
  std::vector<SweepValue> values;
  for (std::size_t i = 0; i < sweep.values.size(); ++i)
    values.push_back(run_sweep_value(file, ICGP_MODELS_DIR, sweep, i, {TrackerKind::kOracle}, 2, 0, std::nullopt, {}));
  REQUIRE(values.size() == 2);
  for (const SweepValue& v : values) {
    INFO("gain " << v.value << ": " << v.error);
    CHECK(v.error.empty());
    REQUIRE(v.rows.size() == 1);
    CHECK(v.rows[0].summary.trials == 2);
  }
  CHECK(values[0].rows[0].summary.success_rate == 1.0);
  CHECK(values[1].rows[0].summary.success_rate == 0.0);
  CHECK(values[1].rows[0].summary.final_t_median > 0.01);  // diverged: centimetres off
  // The same seeded starts at every value: a sweep is a comparison.
  const SweepValue again = run_sweep_value(file, ICGP_MODELS_DIR, sweep, 0, {TrackerKind::kOracle}, 2, 0, std::nullopt, {});
  CHECK(again.rows[0].summary.final_t_median == values[0].rows[0].summary.final_t_median);
}

TEST_CASE("sweep: a row says whether its tracker started by detection or from the truth", "[servo][sweep]") {
  const auto runs_of = [](const std::string& tracker) {
    ServoResult run;
    run.tracker = tracker;
    run.converged = true;
    run.steps.resize(1);
    return std::vector<ServoResult>{run};
  };
  Scenario scenario;
  const std::vector<std::vector<ServoResult>> runs = {
      runs_of("icgp (region + depth + texture)"), runs_of("visp (edge + KLT + dense depth)"),
      runs_of("oracle (ground truth)")};
  const SweepValue detected = sweep_value(50, runs, scenario, false);
  REQUIRE(detected.rows.size() == 3);
  CHECK_FALSE(detected.rows[0].starts_from_truth);  // icgp finds the object itself
  CHECK(detected.rows[1].starts_from_truth);        // ViSP's tracker cannot detect
  CHECK(detected.rows[2].starts_from_truth);
  scenario.tracker.init_by_detection = false;
  CHECK(sweep_value(50, runs, scenario, false).rows[0].starts_from_truth);
  std::ostringstream table;
  print_sweep(table, SweepSpec{"camera.latency_ms", {50}}, {detected});
  CHECK_THAT(table.str(), Contains("icgp (region + depth + texture)    detect"));
  CHECK_THAT(table.str(), Contains("visp (edge + KLT + dense depth)    truth"));
}

TEST_CASE("sweep: a trial that throws is reported with its number and tracker, and the sweep goes on",
          "[servo][sweep]") {
  // A Viper 850 started outside its joint limits: every run of it throws.
  const icgp::test::TempDir dir("icgp-test-sweep");
  const std::string file = dir.write(
      "bad_arm.yaml", "robot: viper850_eye_in_hand\narm: {initial_joints_deg: [0, -60, 300, 0, 70, 0]}\n" +
                          kDelayed.substr(0, kDelayed.find("stop:")) + "stop: {max_time: 1}\n");
  const SweepSpec sweep = parse_sweep("camera.latency_ms=0,50");
  for (std::size_t i = 0; i < sweep.values.size(); ++i) {
    const SweepValue v = run_sweep_value(file, ICGP_MODELS_DIR, sweep, i, {TrackerKind::kOracle}, 2, 0, std::nullopt, {});
    INFO(v.error);
    CHECK(v.rows.empty());
    CHECK_THAT(v.error, Contains("trial 1 (oracle): Viper 850: initial joint 3"));
    CHECK_THAT(v.error, Contains("; trial 2 (oracle): "));
  }
}
