// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/servo/servo_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include "icgp/base/splitmix64.h"
#include "icgp/base/stop_request.h"
#include "icgp/eval/metrics.h"
#include "icgp/servo/command_channel.h"
#include "icgp/servo/robot_response.h"
#include "icgp/servo/servo_controller.h"
#include "icgp/servo/simulated_robot.h"
#include "icgp/visp/conversions.h"
#include "tracker_in_loop.h"

namespace icgp::servo {
namespace {

using Clock = std::chrono::steady_clock;

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

/// Converged: the estimated error has been within half the thresholds for the settle time
/// (StopSpec).
class ConvergenceMonitor {
 public:
  explicit ConvergenceMonitor(const StopSpec& stop) : stop_(stop) {}

  /// True once settled; `time` of the step, `error` of the estimated pose to the desired one.
  bool update(double time, const PoseError& error, bool may_converge) {
    const bool within = may_converge && error.translation <= 0.5 * stop_.converged_translation &&
                        error.rotation <= 0.5 * stop_.converged_rotation;
    if (!within) {
      since_ = -1.0;
      return false;
    }
    if (since_ < 0.0) since_ = time;
    return time - since_ >= stop_.settle_time - 1e-9;
  }
  double since() const { return since_; }

 private:
  StopSpec stop_;
  double since_ = -1.0;
};

/// "[servo] t 1.20 s | error 12.4 mm 3.10 deg | track 0.6 ms" at most every half second of
/// wall time, so long runs show they are alive without flooding a log.
class ProgressLine {
 public:
  explicit ProgressLine(bool enabled) : enabled_(enabled) {}
  void show(const ServoStep& step, bool force = false) {
    if (!enabled_) return;
    const auto now = Clock::now();
    if (!force && ms_between(last_, now) < 500.0) return;
    last_ = now;
    std::fprintf(stderr, "\r[servo] t %6.2f s | error %8.2f mm %6.2f deg | tracker %6.2f mm | track %5.2f ms%s", step.time,
                 1e3 * step.servo_t, step.servo_r / kDegree, 1e3 * step.track_t, step.track_ms,
                 step.safety_stop ? " | SAFETY STOP" : "            ");
    if (force) std::fprintf(stderr, "\n");
  }

 private:
  bool enabled_;
  Clock::time_point last_{};
};

/// The seed's stream of latency jitter (icgp::seeded_stream purposes are per use).
constexpr std::uint64_t kJitterStream = 17;

/// When the command computed from a frame reaches the robot (CameraSpec::latency and
/// jitter, plus the tracker's time with TrackerSpec::real_timing), and whether the tracker
/// is free to take a frame. The jitter is drawn from its own stream of the run's seed, so
/// that it leaves the images' noise as it is.
class PipelineTiming {
 public:
  PipelineTiming(const Scenario& scenario, unsigned seed)
      : camera_(scenario.camera), tracker_(scenario.tracker), random_(seeded_stream(seed, kJitterStream)) {}

  /// Whether a frame exposed at `time` finds the tracker free (always, with ideal timing).
  bool tracker_free(double time) const { return time >= busy_until_ - kSameInstant; }

  /// The tracker took `measured` seconds on the frame exposed at `time`: it is busy until it
  /// is done (real timing). Returns when the command computed from that frame arrives.
  double command_arrival(double time, double measured) {
    double delay = camera_.latency + jitter();
    if (tracker_.real_timing) {
      const double compute = tracker_.compute_time.value_or(measured);
      busy_until_ = time + compute;
      delay += compute;
    }
    return time + std::max(delay, 0.0);
  }

 private:
  double jitter() {
    switch (camera_.jitter.distribution) {
      case JitterSpec::Distribution::kUniform:
        return random_.uniform(-camera_.jitter.spread, camera_.jitter.spread);
      case JitterSpec::Distribution::kNormal:
        return camera_.jitter.spread * random_.normal();
      case JitterSpec::Distribution::kNone:
        break;
    }
    return 0.0;
  }

  CameraSpec camera_;
  TrackerSpec tracker_;
  SplitMix64 random_;
  double busy_until_ = -std::numeric_limits<double>::infinity();
};

/// What the values of a velocity for `robot` are (velocity_size), for error messages.
std::string velocity_meaning(RobotKind robot) {
  if (robot == RobotKind::kFreeFlyingCamera) return "the camera twist (v, w) in the camera frame, m/s and rad/s";
  return "the Viper 850's joint velocities, rad/s";
}

/// options.control_law's velocity at a step, checked: the size the robot takes, finite.
vpColVector custom_velocity(const ControlLaw& law, const ControlState& state) {
  const vpColVector velocity = law(state);
  if (velocity.size() != state.velocity_size)
    throw std::invalid_argument("control law: expected " + std::to_string(state.velocity_size) + " values (" +
                                velocity_meaning(state.robot) + "), got " + std::to_string(velocity.size()));
  for (unsigned i = 0; i < velocity.size(); ++i)
    if (!std::isfinite(velocity[i]))
      throw std::invalid_argument("control law: expected finite numbers, got " + std::to_string(velocity[i]) +
                                  " at index " + std::to_string(i) + " (at t = " + std::to_string(state.time) + " s)");
  return velocity;
}

/// ControlState::jacobian of `robot` at its current configuration: the product of the
/// Jacobians vpServo is given for its servo type.
vpMatrix robot_jacobian(const SimulatedRobot& robot) {
  vpServo task;
  task.setServo(robot.servo_type());
  robot.update_jacobians(task);
  switch (robot.servo_type()) {
    case vpServo::EYEINHAND_CAMERA: {
      vpMatrix identity;
      identity.eye(6);
      return identity;
    }
    case vpServo::EYEINHAND_L_cVe_eJe:
      return vpMatrix(task.get_cVe()) * task.get_eJe();
    case vpServo::EYETOHAND_L_cVf_fVe_eJe:
      return vpMatrix(task.get_cVf()) * vpMatrix(task.get_fVe()) * task.get_eJe();
    default:
      throw std::logic_error("robot_jacobian: a robot controlled with vpServo type " +
                             std::to_string(static_cast<int>(robot.servo_type())));
  }
}

void summarise_tracking(ServoResult& result) {
  std::vector<double> ms;
  double sum_t = 0.0, sum_r = 0.0;
  int n_present = 0;
  for (const ServoStep& s : result.steps) {
    if (std::isnan(s.track_t)) continue;  // the object out of the scene: no truth to compare
    ++n_present;
    sum_t += s.track_t;
    sum_r += s.track_r;
    result.max_track_t = std::max(result.max_track_t, s.track_t);
    result.max_track_r = std::max(result.max_track_r, s.track_r);
    if (!s.lost && !s.dropped && !s.skipped) {
      result.max_vouched_track_t = std::max(result.max_vouched_track_t, s.track_t);
      result.max_vouched_track_r = std::max(result.max_vouched_track_r, s.track_r);
    }
    if (!s.dropped) ms.push_back(s.track_ms);
  }
  const double n = static_cast<double>(std::max(1, n_present));
  result.mean_track_t = sum_t / n;
  result.mean_track_r = sum_r / n;
  result.median_track_ms = ms.empty() ? 0.0 : median(ms);
}

}  // namespace

unsigned velocity_size(RobotKind) {
  return 6;  // a camera twist, or the Viper 850's 6 joints
}

ServoResult run_servo(const Scenario& original, const ServoRunOptions& options) {
  check_run_length(original);
  Scenario scenario = original;
  // A grasp's camera and object stand still: its trials start the gripper elsewhere.
  if (scenario.grasp)
    scenario.grasp->start_gMo = options.start_offset * original.grasp->start_gMo;
  else
    scenario.initial_cMo = options.start_offset * original.initial_cMo;
  // Where the servo must bring the cell: the truth scores the run against it.
  const vpHomogeneousMatrix desired =
      to_homogeneous_matrix(scenario.grasp ? scenario.grasp->desired_gMo : scenario.desired_cMo);

  const TrueCalibration truth = draw_true_calibration(scenario, options.seed);
  std::unique_ptr<SimulatedRobot> robot = make_robot(scenario, truth);
  RgbdSimulator simulator(scenario, truth, robot->world_T_camera(), initial_world_T_object(scenario, *robot),
                          options.seed);
  std::unique_ptr<PoseEstimator> estimator =
      options.make_estimator ? options.make_estimator(simulator) : make_pose_estimator(scenario.tracker, scenario, simulator);
  // The goal the law and the tracker work toward: the desired pose, or what the cell
  // measured there when it was taught by showing.
  const vpHomogeneousMatrix goal =
      scenario.control.taught_by_showing
          ? shown_goal(*robot, simulator, *estimator, desired, scenario.tracker.init_by_detection)
          : desired;
  // The scenario's law, unless one is given in code.
  std::unique_ptr<ServoController> controller;
  if (!options.control_law)
    controller = std::make_unique<ServoController>(scenario.control, goal,
                                                   bounding_box_corners(scenario.object.model), *robot);
  // A tracker that follows the object alone gets the gripper from the arm's encoders,
  // kinematics and calibrated camera pose, as a real cell's would.
  TrackerInLoop tracker(*estimator, scenario.tracker, goal, [&] { return robot->kinematic_camera_T_gripper(); });

  ServoResult result;
  result.scenario = scenario.name;
  result.tracker = estimator->name();
  result.seed = options.seed;

  const double dt = 1.0 / scenario.camera.rate_hz;
  const double motion_end = scenario.object.settled_time();
  vpHomogeneousMatrix previous_wMc = robot->world_T_camera();
  // Detection: the tracker finds the object in the frames of the loop itself, the robot
  // holding still until it does. Otherwise it starts at the true poses (for comparison).
  if (tracker.starts_from_truth())
    tracker.start_at_truth(
        simulator.capture(0.0, previous_wMc, previous_wMc, robot->world_T_held_object(), robot->world_T_gripper()));

  PipelineTiming timing(scenario, options.seed);
  CommandChannel channel(vpColVector(velocity_size(scenario.robot), 0.0));
  RobotResponse response(scenario.robot_response, scenario.robot);
  ConvergenceMonitor convergence(scenario.stop);
  ProgressLine progress(options.progress);
  bool stopped = false;
  const auto loop_begin = Clock::now();
  // check_run_length bounds it to [1, kMaxSimulatedSteps]: the conversion cannot overflow.
  const int steps = static_cast<int>(simulated_steps(scenario.stop.max_time, scenario.camera.rate_hz));
  for (int k = 0; k < steps; ++k) {
    ServoStep step;
    step.time = k * dt;
    const vpHomogeneousMatrix wMc = robot->world_T_camera();
    const auto t0 = Clock::now();
    const RgbdCapture& capture =
        simulator.capture(step.time, wMc, previous_wMc, robot->world_T_held_object(), robot->world_T_gripper());
    const auto t1 = Clock::now();
    previous_wMc = wMc;
    step.dropped = capture.dropped;
    step.skipped = !capture.dropped && !timing.tracker_free(step.time);
    const bool tracked = !capture.dropped && !step.skipped;
    if (tracked) tracker.take(capture);
    const PoseEstimate& estimate = tracker.estimate();
    const vpHomogeneousMatrix servoed_estimate = servoed_pose(estimate.cMo, estimate.cMg);
    const vpHomogeneousMatrix servoed_truth = servoed_pose(capture.cMo_true, capture.cMg_true);
    const auto t2 = Clock::now();

    step.lost = estimate.lost;
    // With real timing a command follows only a frame the tracker took; ideally the law also
    // runs again on the last estimate when the sensor lost the frame.
    step.command_delay = std::numeric_limits<double>::quiet_NaN();
    if (tracked || !scenario.tracker.real_timing) {
      vpColVector velocity;
      if (estimate.lost) {
        // Safety stop: never move on a pose the tracker itself does not trust.
        velocity = vpColVector(velocity_size(scenario.robot), 0.0);
        step.safety_stop = true;
        if (!stopped) ++result.safety_stops;
      } else if (controller) {
        velocity = controller->compute(servoed_estimate, *robot);
        step.servo_error_norm = controller->error().frobeniusNorm();
      } else {
        velocity = custom_velocity(options.control_law, {step.time, servoed_estimate, goal, scenario.robot,
                                                         velocity_size(scenario.robot), robot_jacobian(*robot)});
        step.servo_error_norm = std::numeric_limits<double>::quiet_NaN();  // no features s
      }
      stopped = estimate.lost;
      const double arrival = timing.command_arrival(step.time, tracked ? 1e-3 * ms_between(t1, t2) : 0.0);
      step.command_delay = arrival - step.time;
      channel.send(velocity, arrival);
    }
    // Counted per frame period, however many moves the holds and the response take in it.
    const int limit_stops_before = robot->joint_limit_stops();
    for (const CommandChannel::Hold& hold : channel.holds(step.time, dt))
      step.velocity = response.follow(*robot, hold.velocity, hold.duration);
    if (robot->joint_limit_stops() > limit_stops_before) ++result.joint_limit_stops;
    const auto t3 = Clock::now();

    step.wMc_true = wMc;
    step.cMo_true = capture.cMo_true;
    step.cMo_estimated = estimate.cMo;
    const PoseError servo = pose_error(servoed_truth, desired);
    const PoseError tracking = pose_error(servoed_estimate, servoed_truth);
    step.servo_t = servo.translation;
    step.servo_r = servo.rotation;
    step.track_t = tracking.translation;
    step.track_r = tracking.rotation;
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    if (!simulator.object_present(step.time)) step.servo_t = step.servo_r = kNaN;
    // No truth to compare with while the object is away, no estimate before it is found.
    if (!simulator.object_present(step.time) || !tracker.started()) step.track_t = step.track_r = kNaN;
    step.render_ms = ms_between(t0, t1);
    step.track_ms = step.dropped ? 0.0 : estimate.track_ms;
    step.control_ms = ms_between(t2, t3);
    result.steps.push_back(step);
    if (options.on_step) options.on_step(capture, step);
    progress.show(step);

    const bool settled = !estimate.lost && convergence.update(step.time, pose_error(servoed_estimate, goal),
                                                              step.time >= motion_end);
    if (settled) {
      result.converged = true;
      result.converged_time = convergence.since();
      result.converged_step = static_cast<int>(std::lround(convergence.since() / dt));
      break;
    }
    // Polled after the step is logged, so that an interrupted run has at least one.
    if (stop_requested()) {
      result.interrupted = true;
      break;
    }
  }
  const double loop_seconds = std::chrono::duration<double>(Clock::now() - loop_begin).count();
  progress.show(result.steps.back(), true);

  result.final_t = result.steps.back().servo_t;
  result.final_r = result.steps.back().servo_r;
  result.recovered = !result.steps.back().lost;
  if (result.steps.back().lost) result.lost_reason = tracker.last_why_lost();
  result.steps_per_s = result.steps.size() / std::max(loop_seconds, 1e-9);
  summarise_tracking(result);
  return result;
}

Pose perturbed_start(const TrialSpec& trials, unsigned seed, int trial) {
  std::mt19937_64 random(seed * 0x9E3779B97F4A7C15ull + static_cast<unsigned>(trial));
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const auto direction = [&] {
    Eigen::Vector3d d(normal(random), normal(random), normal(random));
    return d.normalized();
  };
  const Eigen::Vector3d t = direction() * trials.translation * uniform(random);
  const Eigen::Vector3d r = direction() * trials.rotation * uniform(random);
  return Pose::from_rotation_vector(r, t);
}

}  // namespace icgp::servo
