// SPDX-License-Identifier: GPL-2.0-or-later
// The closed loop with rendering, tracking and ViSP's control laws: PBVS and IBVS converge
// with icgp in the loop (checked against the ground truth), and a tracker that reports lost
// stops the robot within the step; a run that ends lost says the tracker's reason. A control
// law given in code replaces vpServo's.
#include <catch2/catch.hpp>
#include <cmath>
#include <sstream>
#include <visp3/core/vpThetaUVector.h>

#include "icgp/base/stop_request.h"
#include "icgp/servo/scenario.h"
#include "icgp/servo/servo_batch.h"
#include "icgp/servo/servo_controller.h"
#include "icgp/servo/servo_report.h"
#include "icgp/servo/servo_run.h"
#include "icgp/visp/conversions.h"
#include "../unit/test_temp_dir.h"

using namespace icgp::servo;

namespace {

/// A small, fast scenario: 320x240 camera, coarse viewpoint models, the textured box.
Scenario small_scenario(const std::string& law, const std::string& tracker) {
  const icgp::test::TempDir dir("icgp-test-servo-loop");
  std::ostringstream yaml;
  yaml << "profile: ideal\n"
          "object: {model: textured_box}\n"
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

/// Oracle poses, except that it reports lost during steps [first_lost, first_lost + count),
/// with kWhyLost as its reason.
class FailingTracker : public PoseEstimator {
 public:
  static constexpr const char* kWhyLost = "the test hides the object";
  /// `lost_offset`: metres along the camera's x axis that the pose it gives while lost is
  /// off, as a lost tracker's pose may be anywhere.
  FailingTracker(int first_lost, int count, double lost_offset = 0.0)
      : first_lost_(first_lost), count_(count), lost_offset_(lost_offset) {}
  void start(const RgbdCapture&, const vpHomogeneousMatrix&, const std::optional<vpHomogeneousMatrix>&) override {}
  PoseEstimate track(const RgbdCapture& capture) override {
    const int step = steps_++;
    PoseEstimate estimate{capture.cMo_true, step >= first_lost_ && step < first_lost_ + count_, 0.0};
    if (estimate.lost) {
      estimate.why_lost = kWhyLost;
      estimate.cMo = vpHomogeneousMatrix(lost_offset_, 0.0, 0.0, 0.0, 0.0, 0.0) * estimate.cMo;
    }
    return estimate;
  }
  std::string name() const override { return "failing oracle"; }

 private:
  int first_lost_, count_, steps_ = 0;
  double lost_offset_;
};

/// Finds the object turned by a symmetry S of its shape (half a turn about its y axis), as a
/// detector of a symmetric object may, and names the true pose as an equivalent; then
/// tracks on in the frame it was started in (the truth, or the truth turned by S).
class SymmetricDetector : public PoseEstimator {
 public:
  void start(const RgbdCapture& capture, const vpHomogeneousMatrix& cMo,
             const std::optional<vpHomogeneousMatrix>&) override {
    oMo_started_ = capture.cMo_true.inverse() * cMo;
  }
  PoseEstimate detect(const RgbdCapture& capture, const std::optional<vpHomogeneousMatrix>&) override {
    PoseEstimate found;
    found.cMo = capture.cMo_true * half_turn();
    found.equivalents = {capture.cMo_true};
    oMo_started_ = half_turn();
    return found;
  }
  PoseEstimate track(const RgbdCapture& capture) override { return {capture.cMo_true * oMo_started_, false, 0.0}; }
  bool detects() const override { return true; }
  std::string name() const override { return "symmetric detector"; }

 private:
  static vpHomogeneousMatrix half_turn() { return vpHomogeneousMatrix(0, 0, 0, 0, M_PI, 0); }
  vpHomogeneousMatrix oMo_started_;
};

/// tests/servo/data/small_pbvs.yaml with the oracle tracker and a constant PBVS gain `gain`.
Scenario small_pbvs_oracle(double gain) {
  Scenario scenario = load_scenario(ICGP_TEST_DATA_DIR "/../servo/data/small_pbvs.yaml", ICGP_MODELS_DIR);
  scenario.tracker.kind = TrackerKind::kOracle;
  scenario.control.gain.at_zero = scenario.control.gain.at_infinity = gain;
  return scenario;
}

/// PBVS written out for the features vpServo's law uses, s = (t, θu) of cdMc = cdMo cMo^-1
/// with s* = 0. Their interaction matrix is L = [[R, 0], [0, L_θu]] (R the rotation of
/// cdMc), and L_θu θu = θu, so the camera twist that makes ds/dt = -λ s is
/// v = -λ R^T t, ω = -λ θu.
vpColVector hand_written_pbvs(const ControlState& state, double gain) {
  const vpHomogeneousMatrix cdMc = state.desired * state.pose.inverse();
  const vpColVector v = -gain * (cdMc.getRotationMatrix().t() * vpColVector(cdMc.getTranslationVector()));
  const vpThetaUVector tu(cdMc.getRotationMatrix());
  vpColVector twist(6);
  for (unsigned i = 0; i < 3; ++i) {
    twist[i] = v[i];
    twist[3 + i] = -gain * tu[i];
  }
  return twist;
}

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
    return std::make_unique<FailingTracker>(kFirstLost, kLostSteps, 0.05);
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
  CHECK(result.lost_reason.empty());
  CHECK(result.converged);
  // The 5 cm off pose given while lost counts in the tracker error, not on the frames the
  // tracker vouched for, where the oracle is exact.
  CHECK(result.max_track_t == Approx(0.05).epsilon(1e-6));
  CHECK(result.max_vouched_track_t < 1e-9);
  CHECK(result.max_vouched_track_r < 1e-9);
}

TEST_CASE("servo: in a cell with latency and a lagging robot, a loss stops the robot once its zero command arrives") {
  Scenario scenario = small_scenario("pbvs", "oracle");
  scenario.camera.latency = 0.067;  // the realistic profile's, without its jitter
  scenario.tracker.real_timing = true;
  scenario.tracker.compute_time = 0.010;
  scenario.robot_response.lag = 0.030;
  ServoRunOptions options = quiet();
  static constexpr int kFirstLost = 10, kLostSteps = 6;
  options.make_estimator = [](const RgbdSimulator&) -> std::unique_ptr<PoseEstimator> {
    return std::make_unique<FailingTracker>(kFirstLost, kLostSteps);
  };
  const ServoResult result = run_servo(scenario, options);
  REQUIRE(result.steps.size() > kFirstLost + kLostSteps);
  const double dt = 1.0 / scenario.camera.rate_hz;
  const double arrival = kFirstLost * dt + 0.077;  // the first zero command: 0.410 s
  for (int k = kFirstLost; k < kFirstLost + kLostSteps; ++k) {
    INFO("step " << k << ", t " << result.steps[k].time << " s");
    CHECK(result.steps[k].safety_stop);  // zero sent from every frame the tracker lost
    CHECK(result.steps[k].command_delay == Approx(0.077));
    const double speed = result.steps[k].velocity.frobeniusNorm();
    if ((k + 1) * dt <= arrival) {
      CHECK(speed > 1e-3);  // the commands in flight still move it
    } else if (k * dt >= arrival) {
      // No command but zero since the step began: the lag's decay over one period, exactly.
      CHECK(speed == Approx(result.steps[k - 1].velocity.frobeniusNorm() * std::exp(-dt / 0.030)).epsilon(1e-9));
    }
  }
  CHECK(result.safety_stops == 1);
  CHECK(result.converged);
}

TEST_CASE("servo: a run that ends lost says the tracker's reason") {
  ServoRunOptions options = quiet();
  options.make_estimator = [](const RgbdSimulator&) -> std::unique_ptr<PoseEstimator> {
    return std::make_unique<FailingTracker>(3, 1 << 20);
  };
  const ServoResult result = run_servo(small_scenario("pbvs", "oracle"), options);
  CHECK_FALSE(result.recovered);
  CHECK(result.lost_reason == FailingTracker::kWhyLost);
  std::ostringstream report;
  print_run(report, result, small_scenario("pbvs", "oracle").stop);
  CHECK_THAT(report.str(), Catch::Contains(std::string("lost at the end    ") + FailingTracker::kWhyLost));
}

TEST_CASE("servo: a symmetric object's detection is servoed on the equivalent pose nearest the goal") {
  Scenario scenario = small_scenario("pbvs", "oracle");
  scenario.tracker.init_by_detection = true;
  ServoRunOptions options = quiet();
  options.make_estimator = [](const RgbdSimulator&) -> std::unique_ptr<PoseEstimator> {
    return std::make_unique<SymmetricDetector>();
  };
  const ServoResult result = run_servo(scenario, options);
  // Servoed on the pose the detector ranked first, the camera would head for the goal
  // turned half about the object, 180 degrees from the true one.
  check_converged(result, 0.5e-3, 0.05 * kDegree);
  CHECK(result.max_track_t < 1e-9);
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

TEST_CASE("servo: a PBVS law given in code converges, as vpServo's with the same gain") {
  constexpr double kGain = 1.5;
  const Scenario scenario = small_pbvs_oracle(kGain);
  ServoRunOptions options = quiet();
  std::vector<ControlState> states;
  options.control_law = [&states](const ControlState& state) {
    states.push_back(state);
    return hand_written_pbvs(state, kGain);
  };
  const ServoResult custom = run_servo(scenario, options);
  check_converged(custom, 0.5e-3, 0.05 * kDegree);

  // Called once per step, told the step's time, the free-flying camera's 6 values, and the
  // desired pose of the scenario; with the oracle the estimated pose is the true one.
  REQUIRE(states.size() == custom.steps.size());
  for (std::size_t k = 0; k < states.size(); ++k) {
    INFO("step " << k);
    CHECK(states[k].time == custom.steps[k].time);
    CHECK(states[k].robot == RobotKind::kFreeFlyingCamera);
    CHECK(states[k].velocity_size == 6);
    const PoseError to_desired = pose_error(states[k].desired, icgp::to_homogeneous_matrix(scenario.desired_cMo));
    CHECK((to_desired.translation == 0.0 && to_desired.rotation == 0.0));
    CHECK(pose_error(states[k].pose, custom.steps[k].cMo_true).translation < 1e-12);
    CHECK(std::isnan(custom.steps[k].servo_error_norm));  // no features s
  }

  // vpServo's PBVS with the same constant gain commands the same velocities: the same run.
  const ServoResult visp = run_servo(scenario, quiet());
  REQUIRE(visp.steps.size() == custom.steps.size());
  for (std::size_t k = 0; k < visp.steps.size(); ++k) {
    INFO("step " << k);
    CHECK((visp.steps[k].velocity - custom.steps[k].velocity).frobeniusNorm() < 1e-9);
  }
  // Saturated as vpServo's output is: far from the goal, the first step moves slower than
  // the law commands, in the same direction (one factor for the whole twist).
  const vpColVector commanded = hand_written_pbvs(states.front(), kGain);
  const vpColVector& applied = custom.steps.front().velocity;
  const double factor = applied.frobeniusNorm() / commanded.frobeniusNorm();
  CHECK(factor < 0.9);
  CHECK((applied - factor * commanded).frobeniusNorm() < 1e-12);
}

TEST_CASE("servo: a law given in code is not called at a safety stop, and a wrong size is refused") {
  ServoRunOptions options = quiet();
  SECTION("the robot stays still while the tracker is lost, whatever the law") {
    static constexpr int kFirstLost = 10, kLostSteps = 5;
    options.make_estimator = [](const RgbdSimulator&) -> std::unique_ptr<PoseEstimator> {
      return std::make_unique<FailingTracker>(kFirstLost, kLostSteps);
    };
    std::size_t calls = 0;
    options.control_law = [&calls](const ControlState& state) {
      ++calls;
      return hand_written_pbvs(state, 1.5);
    };
    const ServoResult result = run_servo(small_pbvs_oracle(1.5), options);
    CHECK(result.converged);
    CHECK(calls == result.steps.size() - kLostSteps);
    for (int k = kFirstLost; k < kFirstLost + kLostSteps; ++k) CHECK(result.steps[k].velocity.frobeniusNorm() == 0.0);
  }
  SECTION("5 values for the free-flying camera's 6") {
    options.control_law = [](const ControlState&) { return vpColVector(5, 0.0); };
    CHECK_THROWS_AS(run_servo(small_pbvs_oracle(1.5), options), std::invalid_argument);
    CHECK_THROWS_WITH(run_servo(small_pbvs_oracle(1.5), options),
                      "control law: expected 6 values (the camera twist (v, w) in the camera frame, m/s and rad/s), "
                      "got 5");
  }
  SECTION("a value that is not finite") {
    options.control_law = [](const ControlState&) { return vpColVector(6, std::nan("")); };
    CHECK_THROWS_WITH(run_servo(small_pbvs_oracle(1.5), options),
                      Catch::Matchers::StartsWith("control law: expected finite numbers, got nan at index 0"));
  }
}
