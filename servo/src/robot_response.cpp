// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/servo/robot_response.h"

#include <algorithm>
#include <cmath>

#include "icgp/servo/servo_run.h"

namespace icgp::servo {
namespace {

/// The longest integration step, seconds: a tenth of a 10 ms lag.
constexpr double kMaxStep = 1e-3;

}  // namespace

RobotResponse::RobotResponse(const ResponseSpec& spec, RobotKind kind)
    : spec_(spec), kind_(kind), velocity_(velocity_size(kind), 0.0) {}

vpColVector RobotResponse::follow(SimulatedRobot& robot, const vpColVector& command, double duration) {
  if (spec_.immediate()) {
    velocity_ = robot.move(command, duration);
    return velocity_;
  }
  const vpColVector target = robot.saturated(command);
  const int steps = std::max(1, static_cast<int>(std::ceil(duration / kMaxStep)));
  const double step = duration / steps;
  for (int i = 0; i < steps; ++i) {
    const auto [next, mean] = advance(velocity_, target, step);
    robot.move(mean, step);
    velocity_ = next;
  }
  return velocity_;
}

std::pair<vpColVector, vpColVector> RobotResponse::advance(const vpColVector& from, const vpColVector& target,
                                                           double step) const {
  // The lag's exact solution over the step, v(s) = c + (v0 - c) e^(-s/τ), and its mean.
  vpColVector next = target, mean = target;
  if (spec_.lag > 0.0) {
    const double decay = std::exp(-step / spec_.lag);
    next = target + (from - target) * decay;
    mean = target + (from - target) * (spec_.lag / step * (1.0 - decay));
  }
  // Each part of the velocity changes at most at its acceleration limit: at the limit the
  // acceleration is constant over the step (the mean is the midpoint); without a lag, a
  // smaller change is a ramp at the limit that ends within the step (a trapezoidal profile).
  const auto limit_part = [&](unsigned begin, unsigned end, double max_acceleration) {
    if (max_acceleration == ResponseSpec::kUnlimited) return;
    double change = 0.0;
    for (unsigned i = begin; i < end; ++i) change += (next[i] - from[i]) * (next[i] - from[i]);
    change = std::sqrt(change);
    const double max_change = max_acceleration * step;
    if (change > max_change) {
      for (unsigned i = begin; i < end; ++i) {
        next[i] = from[i] + (next[i] - from[i]) * (max_change / change);
        mean[i] = 0.5 * (from[i] + next[i]);
      }
    } else if (spec_.lag == 0.0) {
      const double ramp_share = change / max_change;  // of the step spent ramping
      for (unsigned i = begin; i < end; ++i) mean[i] = from[i] + (next[i] - from[i]) * (1.0 - 0.5 * ramp_share);
    }
  };
  if (kind_ == RobotKind::kFreeFlyingCamera) {
    limit_part(0, 3, spec_.max_linear_acceleration);
    limit_part(3, 6, spec_.max_angular_acceleration);
  } else {
    for (unsigned i = 0; i < next.size(); ++i) limit_part(i, i + 1, spec_.max_joint_acceleration);
  }
  return {next, mean};
}

}  // namespace icgp::servo
