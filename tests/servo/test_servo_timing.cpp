// SPDX-License-Identifier: GPL-2.0-or-later
// Time in the closed loop: commands that arrive late and are held (CommandChannel), a robot
// that follows them through a lag and acceleration limits (RobotResponse, against the closed
// forms of its step response), and the textbook delay bound of a discrete PBVS loop,
// reproduced by the whole simulator with the oracle tracker.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>
#include <Eigen/Eigenvalues>
#include <visp3/core/vpExponentialMap.h>

#include "../unit/test_temp_dir.h"
#include "icgp/servo/command_channel.h"
#include "icgp/servo/robot_response.h"
#include "icgp/servo/scenario.h"
#include "icgp/servo/servo_run.h"
#include "icgp/servo/simulated_robot.h"

using namespace icgp::servo;

namespace {

vpColVector vec6(double a, double b, double c, double d, double e, double f) {
  vpColVector v(6);
  v[0] = a, v[1] = b, v[2] = c, v[3] = d, v[4] = e, v[5] = f;
  return v;
}

/// A free-flying camera (or a Viper 850 with `robot`) whose velocity limits never bind.
Scenario unlimited_robot(RobotKind robot = RobotKind::kFreeFlyingCamera) {
  Scenario scenario;
  scenario.robot = robot;
  scenario.control.max_linear_velocity = 10.0;
  scenario.control.max_angular_velocity = 60.0;
  scenario.control.max_joint_velocity = 60.0;
  return scenario;
}

/// The camera's position along its optical axis (it starts at the world origin).
double camera_z(const SimulatedRobot& robot) { return robot.world_T_camera()[2][3]; }

}  // namespace

TEST_CASE("command channel: a command is held from its arrival until the next one arrives", "[servo][timing]") {
  const vpColVector rest(6, 0.0), a = vec6(1, 0, 0, 0, 0, 0), b = vec6(0, 2, 0, 0, 0, 0);
  const double period = 0.05;

  SECTION("without latency, the period's command is held for exactly the period") {
    CommandChannel channel(rest);
    channel.send(a, 0.3);
    const auto holds = channel.holds(0.3, period);
    REQUIRE(holds.size() == 1);
    CHECK(holds[0].duration == period);  // bit for bit: the ideal loop's move
    CHECK(holds[0].velocity == a);
  }
  SECTION("a command arriving within the period splits it at its arrival") {
    CommandChannel channel(rest);
    channel.send(a, 0.075);  // sent at 0, 1.5 periods late
    CHECK(channel.holds(0.0, period).size() == 1);
    const auto holds = channel.holds(0.05, period);
    REQUIRE(holds.size() == 2);
    CHECK(holds[0].duration == Approx(0.025));
    CHECK(holds[0].velocity == rest);
    CHECK(holds[1].duration == Approx(0.025));
    CHECK(holds[1].velocity == a);
    CHECK(channel.held() == a);
  }
  SECTION("a latency of whole periods switches on frame times despite rounding") {
    CommandChannel channel(rest);
    channel.send(a, 7 * (1.0 / 30.0) + 2.0 / 30.0);  // k·T + d·T, not bitwise (k + d)·T
    CHECK(channel.holds(8 * (1.0 / 30.0), 1.0 / 30.0).front().velocity == rest);
    const auto holds = channel.holds(9 * (1.0 / 30.0), 1.0 / 30.0);
    REQUIRE(holds.size() == 1);
    CHECK(holds[0].velocity == a);
  }
  SECTION("a command does not overtake the one sent before it") {
    CommandChannel channel(rest);
    channel.send(a, 0.09);
    channel.send(b, 0.06);  // its jitter would make it arrive first
    const auto holds = channel.holds(0.05, period);
    REQUIRE(holds.size() == 2);
    CHECK(holds[0].duration == Approx(0.04));
    CHECK(holds[1].velocity == b);  // both arrive at 0.09, in order: b is held after
    CHECK(holds[1].duration == Approx(0.01));
  }
}

TEST_CASE("robot response: an immediate response moves as the robot itself does", "[servo][timing]") {
  const Scenario scenario = unlimited_robot();
  const auto robot = make_robot(scenario), reference = make_robot(scenario);
  RobotResponse response(scenario.robot_response, scenario.robot);
  const vpColVector v = vec6(0.03, -0.05, 0.04, 0.2, -0.1, 0.3);
  const vpColVector followed = response.follow(*robot, v, 0.04);
  reference->move(v, 0.04);
  CHECK((followed - v).frobeniusNorm() == 0.0);
  CHECK((robot->world_T_camera().getTranslationVector() - reference->world_T_camera().getTranslationVector())
            .frobeniusNorm() == 0.0);
}

TEST_CASE("robot response: a first-order lag follows its closed-form step response", "[servo][timing]") {
  Scenario scenario = unlimited_robot();
  const double tau = 0.03, v = 0.05;
  scenario.robot_response.lag = tau;
  const auto robot = make_robot(scenario);
  RobotResponse response(scenario.robot_response, scenario.robot);
  // A step of 0.05 m/s along the optical axis from rest, held over frames of 1/30 s:
  // v(t) = v (1 - e^(-t/τ)), z(t) = v (t - τ (1 - e^(-t/τ))).
  double t = 0.0;
  for (int frame = 0; frame < 12; ++frame) {
    const vpColVector followed = response.follow(*robot, vec6(0, 0, v, 0, 0, 0), 1.0 / 30.0);
    t += 1.0 / 30.0;
    INFO("t = " << t);
    CHECK(followed[2] == Approx(v * (1.0 - std::exp(-t / tau))).margin(1e-12));
    CHECK(camera_z(*robot) == Approx(v * (t - tau * (1.0 - std::exp(-t / tau)))).margin(1e-12));
  }
  // Where an immediate robot would be: v t; the lag leaves it v τ behind once settled.
  CHECK(v * t - camera_z(*robot) == Approx(v * tau).epsilon(1e-3));
}

TEST_CASE("robot response: acceleration limits ramp the velocity, per part of a twist and per joint",
          "[servo][timing]") {
  SECTION("free-flying camera: the linear velocity ramps at the limit, then holds") {
    Scenario scenario = unlimited_robot();
    const double a = 0.5, v = 0.05;  // reaches v after 0.1 s
    scenario.robot_response.max_linear_acceleration = a;
    const auto robot = make_robot(scenario);
    RobotResponse response(scenario.robot_response, scenario.robot);
    double t = 0.0;
    for (int frame = 0; frame < 6; ++frame) {
      const vpColVector followed = response.follow(*robot, vec6(0, 0, v, 0, 0, 0), 0.04);
      t += 0.04;
      const double ramp_end = v / a;
      const double z = t <= ramp_end ? 0.5 * a * t * t : 0.5 * a * ramp_end * ramp_end + v * (t - ramp_end);
      INFO("t = " << t);
      CHECK(followed[2] == Approx(std::min(v, a * t)).margin(1e-12));
      CHECK(camera_z(*robot) == Approx(z).margin(1e-12));
    }
  }
  SECTION("Viper 850: each joint ramps at its own limit, so a short move ends before a long one") {
    Scenario scenario = unlimited_robot(RobotKind::kViper850EyeInHand);
    const double a = 2.0;  // rad/s²
    scenario.robot_response.max_joint_acceleration = a;
    const auto robot = make_robot(scenario);
    RobotResponse response(scenario.robot_response, scenario.robot);
    const vpColVector command = vec6(0.1, -0.4, 0, 0, 0, 0);
    vpColVector followed = response.follow(*robot, command, 0.1);
    CHECK(followed[0] == Approx(0.1).margin(1e-12));   // reached at 0.05 s
    CHECK(followed[1] == Approx(-0.2).margin(1e-12));  // still ramping: a t
    followed = response.follow(*robot, command, 0.1);
    CHECK(followed[1] == Approx(-0.4).margin(1e-12));
  }
}

namespace {

/// A PBVS run with the oracle tracker on a 160 x 120 camera at 20 Hz (frames 50 ms apart)
/// for `max_time` seconds, with `extra` lines of YAML (camera keys go in `camera`).
ServoResult oracle_run(const std::string& camera, const std::string& extra, double gain, double max_time,
                       unsigned seed = 1) {
  const icgp::test::TempDir dir("icgp-test-servo-timing");
  std::ostringstream yaml;
  // The exact world but for what each test adds: the closed forms hold there.
  yaml << "profile: ideal\n"
          "object: {model: textured_box}\n"
          "camera: {color: {width: 160, height: 120, focal: 150}, rate_hz: 20"
       << (camera.empty() ? "" : ", " + camera)
       << "}\n"
          "start: {t: [0.005, 0, 0.35], r_deg: [131.2, 26.8, -37.57]}\n"
          "desired: {t: [0, 0, 0.35], r_deg: [131.2, 26.8, -37.57]}\n"
          "control: {law: pbvs, gain: "
       << gain
       << ", max_linear_velocity: 10, max_angular_velocity_deg: 3000}\n"
          "stop: {translation_mm: 0.001, rotation_deg: 0.001, max_time: "
       << max_time << "}\n"
       << extra;
  ServoRunOptions options;
  options.progress = false;
  options.seed = seed;
  return run_servo(load_scenario(dir.write("timed.yaml", yaml.str()), ICGP_MODELS_DIR), options);
}

}  // namespace

TEST_CASE("real timing: a frame that comes while the tracker is busy is skipped, and its time delays the command",
          "[servo][timing]") {
  // 70 ms a frame at 20 Hz: the tracker takes every other frame.
  const ServoResult result =
      oracle_run("latency_ms: 30", "tracker: {type: oracle, timing: real, compute_ms: 70}\n", 5.0, 0.5);
  REQUIRE(result.steps.size() == 11);
  for (std::size_t k = 0; k < result.steps.size(); ++k) {
    INFO("step " << k);
    const ServoStep& step = result.steps[k];
    CHECK(step.skipped == (k % 2 == 1));
    if (step.skipped)
      CHECK(std::isnan(step.command_delay));
    else
      CHECK(step.command_delay == Approx(0.1));  // latency + compute time
  }
  // The first command arrives at 0.1 s: the robot stands still until then.
  CHECK(result.steps[1].velocity.frobeniusNorm() == 0.0);
  CHECK(result.steps[2].velocity.frobeniusNorm() > 0.0);

  // Ideal timing with the same latency takes every frame.
  const ServoResult ideal = oracle_run("latency_ms: 30", "tracker: {type: oracle}\n", 5.0, 0.5);
  for (const ServoStep& step : ideal.steps) {
    CHECK_FALSE(step.skipped);
    CHECK(step.command_delay == Approx(0.03));
  }
}

TEST_CASE("jitter: latencies drawn from the scenario's distribution, the same with the same seed", "[servo][timing]") {
  const std::string camera = "latency_ms: 40, jitter: {distribution: uniform, ms: 10}";
  const auto delays = [&](unsigned seed) {
    std::vector<double> d;
    for (const ServoStep& step : oracle_run(camera, "tracker: {type: oracle}\n", 5.0, 1.0, seed).steps)
      d.push_back(step.command_delay);
    return d;
  };
  const std::vector<double> a = delays(3), b = delays(3), c = delays(4);
  CHECK(a == b);
  CHECK(a != c);
  const auto [low, high] = std::minmax_element(a.begin(), a.end());
  CHECK(*low >= 0.030);
  CHECK(*high <= 0.050);
  CHECK(*high - *low > 0.01);  // spread over most of the ±10 ms over 21 frames
}

namespace {

/// The error of a PBVS loop with the oracle tracker at constant gain `gain` (1/s), frame
/// period 50 ms, `delay_frames` frames of latency and a robot lag of `lag_ms`, started 5 mm
/// from its goal by a pure translation (the loop is then linear; without a lag,
/// e(k+1) = e(k) - λT e(k - d)). Returns the largest translation error over the last 10
/// steps divided by the first step's.
double pbvs_error_growth(double gain, int delay_frames, double lag_ms = 0.0) {
  const std::string response = lag_ms > 0.0 ? "robot_response: {lag_ms: " + std::to_string(lag_ms) + "}\n" : "";
  const ServoResult result = oracle_run("latency_ms: " + std::to_string(50 * delay_frames),
                                        "tracker: {type: oracle}\n" + response, gain, 6.0);
  REQUIRE(result.steps.size() > 20);
  double last = 0.0;
  for (std::size_t k = result.steps.size() - 10; k < result.steps.size(); ++k)
    last = std::max(last, result.steps[k].servo_t);
  return last / result.steps.front().servo_t;
}

}  // namespace

TEST_CASE("delay: PBVS with d frames of latency is stable exactly below λT = 2 sin(π / (2(2d + 1)))",
          "[servo][timing][textbook]") {
  const double period = 0.05;
  for (int d = 0; d <= 2; ++d) {
    const double bound = 2.0 * std::sin(icgp::kPi / (2.0 * (2 * d + 1))) / period;
    INFO(d << " frame(s) of delay, gain bound " << bound << " /s");
    // 10 % either side of the bound: the slowest root decays to 0.97 or grows to 1.03 per
    // step (d = 2), so 120 steps tell them apart by orders of magnitude.
    const double below = pbvs_error_growth(0.9 * bound, d), above = pbvs_error_growth(1.1 * bound, d);
    INFO("error growth " << below << " at 0.9 x the bound, " << above << " at 1.1 x");
    CHECK(below < 0.5);
    CHECK(above > 2.0);
  }
}

namespace {

/// The largest gain at which the discrete PBVS loop with `delay_frames` frames of delay, period
/// `period` and a first-order robot lag `lag` (both seconds) is stable: the commanded velocity
/// u held over each period drives v' = (u - v)/τ, p' = v (exactly discretised: a = e^(-T/τ),
/// v(k+1) = a v(k) + (1 - a) u(k), p(k+1) = p(k) + τ(1 - a) v(k) + (T - τ(1 - a)) u(k)), with
/// u(k) = -λ p(k - d). Found by bisection on the spectral radius of the loop's state matrix:
/// the root locus of the discrete loop crossing the unit circle.
double critical_gain(double period, int delay_frames, double lag) {
  const double a = std::exp(-period / lag);
  const auto spectral_radius = [&](double gain) {
    // State: p(k), v(k), p(k-1), ..., p(k-d).
    const int n = 2 + delay_frames;
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
    const int delayed = delay_frames == 0 ? 0 : 1 + delay_frames;
    A(0, 0) = 1.0;
    A(0, 1) = lag * (1.0 - a);
    A(1, 1) = a;
    A(0, delayed) += -gain * (period - lag * (1.0 - a));
    A(1, delayed) += -gain * (1.0 - a);
    for (int i = 0; i < delay_frames; ++i) A(2 + i, i == 0 ? 0 : 1 + i) = 1.0;
    return Eigen::EigenSolver<Eigen::MatrixXd>(A).eigenvalues().cwiseAbs().maxCoeff();
  };
  double stable = 0.0, unstable = 1000.0;
  for (int i = 0; i < 60; ++i) {
    const double gain = 0.5 * (stable + unstable);
    (spectral_radius(gain) < 1.0 ? stable : unstable) = gain;
  }
  return stable;
}

}  // namespace

TEST_CASE("delay with a lagging robot: PBVS is stable below the critical gain of the discrete loop's root locus",
          "[servo][timing][textbook]") {
  // Without a lag the locus gives the closed form back.
  CHECK(critical_gain(0.05, 1, 1e-9) == Approx(20.0).epsilon(1e-6));
  // A 50 ms lag at 20 Hz with one frame of delay: the bound falls from 20 to 16.1 /s, and the
  // slowest root decays to 0.975 or grows to 1.024 per step 10 % either side.
  const double bound = critical_gain(0.05, 1, 0.05);
  CHECK(bound == Approx(16.09).epsilon(1e-3));
  const double below = pbvs_error_growth(0.9 * bound, 1, 50.0), above = pbvs_error_growth(1.1 * bound, 1, 50.0);
  INFO("gain bound " << bound << " /s: error growth " << below << " at 0.9 x, " << above << " at 1.1 x");
  CHECK(below < 0.5);
  CHECK(above > 2.0);
  // Without the lag, 1.1 x this bound would be stable: the lag is what the loop feels.
  CHECK(pbvs_error_growth(1.1 * bound, 1) < 0.5);
}
