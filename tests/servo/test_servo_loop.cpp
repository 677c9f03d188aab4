// SPDX-License-Identifier: GPL-2.0-or-later
// The closed loop with rendering, tracking and ViSP's control laws: PBVS and IBVS converge
// with icgp in the loop (checked against the ground truth), and a tracker that reports lost
// stops the robot within the step.
#include <catch2/catch.hpp>
#include <cmath>
#include <sstream>

#include "icgp/base/stop_request.h"
#include "icgp/servo/scenario.h"
#include "icgp/servo/servo_batch.h"
#include "icgp/servo/servo_controller.h"
#include "icgp/servo/servo_run.h"
#include "../unit/test_temp_dir.h"

using namespace icgp::servo;

namespace {

/// A small, fast scenario: 320x240 camera, coarse viewpoint models, the textured box.
Scenario small_scenario(const std::string& law, const std::string& tracker) {
  const icgp::test::TempDir dir("icgp-test-servo-loop");
  std::ostringstream yaml;
  yaml << "object: {model: textured_box}\n"
                         "camera:\n"
                         "  color: {width: 320, height: 240, focal: 300}\n"
                         "  depth_T_color: {t: [-0.025, 0, 0], r_deg: [0, 0, 0]}\n"
                         "start: {t: [0.03, -0.02, 0.45], r_deg: [131.29, 38.07, -12.74]}\n"
                         "desired: {t: [0, 0, 0.35], r_deg: [131.2, 26.8, -37.57]}\n"
                         "tracker: {type: " << tracker << ", modalities: [region, depth], config: "
                      << ICGP_TEST_DATA_DIR "/../configs/coarse_models.yaml}\n"
                         "control:\n"
                         "  law: " << law << "\n"
                         "  gain: {at_zero: 1.5, at_infinity: 0.6, slope_at_zero: 30}\n"
                         "  max_linear_velocity: 0.1\n"
                         "  max_angular_velocity_deg: 30\n"
                         "stop: {translation_mm: 1, rotation_deg: 0.1, settle_time: 0.2, max_time: 8}\n";
  return load_scenario(dir.write(law + "_" + tracker + ".yaml", yaml.str()), ICGP_MODELS_DIR);
}

ServoRunOptions quiet() {
  ServoRunOptions options;
  options.progress = false;
  return options;
}

void check_converged(const ServoResult& result, double max_t, double max_r) {
  INFO(result.tracker << ": " << result.steps.size() << " steps, final " << 1e3 * result.final_t << " mm "
                      << result.final_r / kDegree << " deg, tracker mean " << 1e3 * result.mean_track_t << " mm");
  CHECK(result.converged);
  CHECK(result.final_t < max_t);
  CHECK(result.final_r < max_r);
  CHECK(result.safety_stops == 0);
  // The error really came down from the start.
  CHECK(result.steps.front().servo_t > 0.1);
}

/// Oracle poses, except that it reports lost during steps [first_lost, first_lost + count).
class FailingTracker : public PoseEstimator {
 public:
  FailingTracker(int first_lost, int count) : first_lost_(first_lost), count_(count) {}
  void start(const RgbdCapture&, const vpHomogeneousMatrix&, const std::optional<vpHomogeneousMatrix>&) override {}
  PoseEstimate track(const RgbdCapture& capture) override {
    const int step = steps_++;
    return {capture.cMo_true, step >= first_lost_ && step < first_lost_ + count_, 0.0};
  }
  std::string name() const override { return "failing oracle"; }

 private:
  int first_lost_, count_, steps_ = 0;
};

/// Clears the process-wide stop request when a test ends, however it ends, so that it does
/// not stop the tests after it.
struct StopRequestReset {
  ~StopRequestReset() { icgp::clear_stop_request(); }
};

}  // namespace

TEST_CASE("servo: PBVS with the oracle settles within half the thresholds") {
  const ServoResult result = run_servo(small_scenario("pbvs", "oracle"), quiet());
  check_converged(result, 0.5e-3, 0.05 * kDegree);
}

TEST_CASE("servo: PBVS with icgp in the loop converges to the desired pose") {
  const ServoResult result = run_servo(small_scenario("pbvs", "icgp"), quiet());
  check_converged(result, 1e-3, 0.1 * kDegree);
  // The tracker followed the moving camera (coarse test models allow a few-millimetre
  // outlier frame).
  CHECK(result.mean_track_t < 0.2e-3);
  CHECK(result.max_track_t < 5e-3);
}

TEST_CASE("servo: IBVS with icgp in the loop converges to the desired pose") {
  const ServoResult result = run_servo(small_scenario("ibvs", "icgp"), quiet());
  check_converged(result, 1e-3, 0.1 * kDegree);
}

TEST_CASE("servo: a tracking loss stops the robot within the step, and the run resumes after it") {
  ServoRunOptions options = quiet();
  static constexpr int kFirstLost = 10, kLostSteps = 5;
  options.make_estimator = [](const RgbdSimulator&) -> std::unique_ptr<PoseEstimator> {
    return std::make_unique<FailingTracker>(kFirstLost, kLostSteps);
  };
  const ServoResult result = run_servo(small_scenario("pbvs", "oracle"), options);

  REQUIRE(result.steps.size() > kFirstLost + kLostSteps);
  // Moving before the loss, exactly still from the step the tracker reports lost.
  CHECK(result.steps[kFirstLost - 1].velocity.frobeniusNorm() > 1e-3);
  for (int k = kFirstLost; k < kFirstLost + kLostSteps; ++k) {
    INFO("step " << k);
    CHECK(result.steps[k].lost);
    CHECK(result.steps[k].safety_stop);
    CHECK(result.steps[k].velocity.frobeniusNorm() == 0.0);
    // Standing still: the camera did not move during the stop.
    if (k > kFirstLost) CHECK(pose_error(result.steps[k].cMo_true, result.steps[k - 1].cMo_true).translation < 1e-12);
  }
  CHECK_FALSE(result.steps[kFirstLost + kLostSteps].safety_stop);
  CHECK(result.safety_stops == 1);
  CHECK(result.recovered);
  CHECK(result.converged);
}

TEST_CASE("servo: random trial starts stay within the scenario's ranges and repeat with the seed") {
  TrialSpec trials;
  trials.translation = 0.02;
  trials.rotation = 10 * kDegree;
  for (int i = 0; i < 50; ++i) {
    const icgp::Pose offset = perturbed_start(trials, 7, i);
    CHECK(offset.translation().norm() <= 0.02 + 1e-12);
    CHECK(Eigen::AngleAxisd(offset.rotation()).angle() <= 10 * kDegree + 1e-12);
    CHECK(offset.matrix() == perturbed_start(trials, 7, i).matrix());
  }
  CHECK(perturbed_start(trials, 7, 0).matrix() != perturbed_start(trials, 8, 0).matrix());
}

TEST_CASE("servo: a stop request ends a run after the step it comes in, marked interrupted") {
  const StopRequestReset reset;
  ServoRunOptions options = quiet();
  static constexpr std::size_t kStopAt = 5;  // the step during which the stop is requested
  std::size_t steps = 0;
  options.on_step = [&steps](const RgbdCapture&, const ServoStep&) {
    if (steps++ == kStopAt) icgp::request_stop();
  };
  const ServoResult result = run_servo(small_scenario("pbvs", "oracle"), options);
  CHECK(result.interrupted);
  CHECK_FALSE(result.converged);
  CHECK(result.steps.size() == kStopAt + 1);  // steps 0..kStopAt, all logged
  CHECK(result.final_t == result.steps.back().servo_t);
}

TEST_CASE("servo: a run length out of bounds is refused before anything is rendered") {
  Scenario scenario = small_scenario("pbvs", "oracle");
  scenario.stop.max_time = 1e300;  // built in code: load_scenario would have refused it
  CHECK_THROWS_WITH(run_servo(scenario, quiet()),
                    Catch::Matchers::Contains("stop.max_time: 1e+300 s at camera.rate_hz 30 Hz is 3e+301 simulated "
                                              "steps, outside the [1, 1000000]"));
  scenario.stop.max_time = 8.0;
  scenario.camera.rate_hz = 1e12;
  CHECK_THROWS_AS(run_servo(scenario, quiet()), ScenarioError);
  scenario.camera.rate_hz = std::nan("");
  CHECK_THROWS_AS(run_servo(scenario, quiet()), ScenarioError);
  scenario.camera.rate_hz = 30.0;
  scenario.stop.max_time = -1.0;  // no step at all: refused too, rather than an empty log
  CHECK_THROWS_AS(run_servo(scenario, quiet()), ScenarioError);
}

TEST_CASE("servo: a batch stopped early keeps only the trials every tracker finished") {
  const StopRequestReset reset;
  Scenario scenario = small_scenario("pbvs", "oracle");
  scenario.stop.max_time = 0.5;  // 16 steps: the bookkeeping is under test, not convergence
  const std::vector<TrackerKind> trackers = {TrackerKind::kOracle, TrackerKind::kOracle};

  SECTION("between runs, in the middle of a trial") {
    std::vector<std::pair<int, std::size_t>> seen;  // (trial, steps) of each run done
    const TrialBatch batch = run_trials(scenario, trackers, 5, [&](int trial, const ServoResult& run) {
      seen.emplace_back(trial, run.steps.size());
      if (seen.size() == 3) icgp::request_stop();  // trial 0 by both, trial 1 by the first only
    });
    // No run starts after the request.
    CHECK(seen == std::vector<std::pair<int, std::size_t>>{{0, 16}, {0, 16}, {1, 16}});
    CHECK(batch.interrupted);
    CHECK(batch.trials_done == 1);
    REQUIRE(batch.runs.size() == 2);
    CHECK((batch.runs[0].size() == 1 && batch.runs[1].size() == 1));
    // Identical trials: the same start (the same first true pose) for both trackers.
    const PoseError start = pose_error(batch.runs[0][0].steps.front().cMo_true, batch.runs[1][0].steps.front().cMo_true);
    CHECK((start.translation == 0.0 && start.rotation == 0.0));
  }
  SECTION("within a run: the run cut short is left out") {
    ServoRunOptions each_run;
    int steps = 0;
    // Trial 0 takes 16 steps; the request comes during trial 1's 5th step.
    each_run.on_step = [&steps](const RgbdCapture&, const ServoStep&) {
      if (++steps == 16 + 5) icgp::request_stop();
    };
    int runs_done = 0;
    const TrialBatch batch =
        run_trials(scenario, {TrackerKind::kOracle}, 5, [&](int, const ServoResult&) { ++runs_done; }, each_run);
    CHECK(steps == 16 + 5);  // the run stopped at the step of the request
    CHECK(runs_done == 1);
    CHECK(batch.interrupted);
    CHECK(batch.trials_done == 1);
    REQUIRE(batch.runs.size() == 1);
    REQUIRE(batch.runs[0].size() == 1);
    CHECK_FALSE(batch.runs[0][0].interrupted);
  }
}
