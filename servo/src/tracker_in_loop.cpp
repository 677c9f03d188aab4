// SPDX-License-Identifier: GPL-2.0-or-later
#include "tracker_in_loop.h"

#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "icgp/servo/servo_controller.h"

namespace icgp::servo {
namespace {

/// How many times the tracker refines its pose on the frame a goal is taught with: the
/// robot stands still there, so a tracker settles as it would over so many frames.
constexpr int kTeachingIterations = 10;

/// Of the detected pose and its symmetric equivalents, the one whose servoed pose is the
/// least rotation (then translation) from the goal `desired`.
vpHomogeneousMatrix nearest_to_goal(const PoseEstimate& estimate, const vpHomogeneousMatrix& desired) {
  vpHomogeneousMatrix nearest = estimate.cMo;
  PoseError least = pose_error(servoed_pose(nearest, estimate.cMg), desired);
  for (const vpHomogeneousMatrix& cMo : estimate.equivalents) {
    const PoseError error = pose_error(servoed_pose(cMo, estimate.cMg), desired);
    if (std::tie(error.rotation, error.translation) < std::tie(least.rotation, least.translation)) {
      nearest = cMo;
      least = error;
    }
  }
  return nearest;
}

}  // namespace

vpHomogeneousMatrix servoed_pose(const vpHomogeneousMatrix& cMo, const std::optional<vpHomogeneousMatrix>& cMg) {
  return cMg ? cMg->inverse() * cMo : cMo;
}

vpHomogeneousMatrix shown_goal(const SimulatedRobot& robot, RgbdSimulator& simulator, PoseEstimator& estimator,
                               const vpHomogeneousMatrix& desired_cMo, bool by_detection) {
  vpHomogeneousMatrix wMc = robot.world_T_camera();
  std::optional<vpHomogeneousMatrix> held = robot.world_T_held_object();
  if (held)
    held = wMc * desired_cMo;
  else
    wMc = simulator.world_T_object(0.0) * desired_cMo.inverse();
  const RgbdCapture& shown = simulator.capture(0.0, wMc, wMc, held, robot.world_T_gripper());
  PoseEstimate estimate;
  if (by_detection && estimator.detects()) {
    estimate = estimator.detect(shown, std::nullopt);
    if (estimate.lost)
      throw std::runtime_error("teaching by showing: the tracker did not find the object at the desired pose" +
                               (estimate.why_lost.empty() ? std::string() : " (" + estimate.why_lost + ")"));
  } else {
    estimator.start(shown, shown.cMo_true, shown.cMg_true);
  }
  for (int i = 0; i < kTeachingIterations; ++i) estimate = estimator.track(shown);
  return estimate.cMo;
}

TrackerInLoop::TrackerInLoop(PoseEstimator& estimator, const TrackerSpec& spec, const vpHomogeneousMatrix& goal,
                             KinematicGripper kinematic_cMg)
    : estimator_(estimator),
      goal_(goal),
      kinematic_cMg_(std::move(kinematic_cMg)),
      started_(!(spec.init_by_detection && estimator.detects())) {}

void TrackerInLoop::start_at_truth(const RgbdCapture& first) {
  trusted_cMo_ = first.cMo_true;
  trusted_cMg_ = first.cMg_true;
  estimator_.start(first, trusted_cMo_, trusted_cMg_);
}

const PoseEstimate& TrackerInLoop::take(const RgbdCapture& capture) {
  if (started_)
    track(capture);
  else
    detect(capture);
  if (estimate_.lost && !estimate_.why_lost.empty()) last_why_lost_ = estimate_.why_lost;
  return estimate_;
}

void TrackerInLoop::detect(const RgbdCapture& capture) {
  estimate_ = estimator_.detect(capture, kinematic_cMg());
  started_ = !estimate_.lost;
  if (!estimate_.cMg) estimate_.cMg = kinematic_cMg();
  if (!started_) return;
  if (!estimate_.equivalents.empty()) {
    // A symmetric object looks the same at each of these poses: servo on the one that
    // needs the smallest motion to the goal, not on whichever the detector ranked first.
    const vpHomogeneousMatrix nearest = nearest_to_goal(estimate_, goal_);
    if (nearest != estimate_.cMo) {
      estimate_.cMo = nearest;
      estimator_.start(capture, estimate_.cMo, estimate_.cMg);
    }
  }
  trusted_cMo_ = estimate_.cMo;
  trusted_cMg_ = estimate_.cMg;
}

void TrackerInLoop::track(const RgbdCapture& capture) {
  estimate_ = estimator_.track(capture);
  if (!estimate_.cMg) estimate_.cMg = kinematic_cMg();
  if (estimate_.lost && !estimator_.recovers()) {
    // The robot stops, so the poses last trusted still hold for a static object: restart
    // the tracker there for the next frame rather than let it wander while lost.
    estimator_.start(capture, trusted_cMo_, trusted_cMg_);
  } else if (!estimate_.lost) {
    trusted_cMo_ = estimate_.cMo;
    trusted_cMg_ = estimate_.cMg;
  }
}

std::optional<vpHomogeneousMatrix> TrackerInLoop::kinematic_cMg() const {
  return kinematic_cMg_ ? kinematic_cMg_() : std::nullopt;
}

}  // namespace icgp::servo
