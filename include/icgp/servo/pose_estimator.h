// SPDX-License-Identifier: GPL-2.0-or-later
// The trackers a scenario can close the loop with, behind one interface.
#pragma once

#include <memory>
#include <string>
#include <visp3/core/vpHomogeneousMatrix.h>

#include "icgp/servo/rgbd_simulator.h"
#include "icgp/servo/scenario.h"

namespace icgp::servo {

/// What a tracker says after a frame.
struct PoseEstimate {
  vpHomogeneousMatrix cMo;
  bool lost = false;     ///< the tracker's own verdict (vpMbTracker::testTracking threw)
  double track_ms = 0.0;  ///< the track() call alone
};

/// A pose tracker fed with the simulated RGB-D captures through ViSP's API.
class PoseEstimator {
 public:
  virtual ~PoseEstimator() = default;
  /// Starts tracking at `cMo` on `first`.
  virtual void start(const RgbdCapture& first, const vpHomogeneousMatrix& cMo) = 0;
  virtual PoseEstimate track(const RgbdCapture& capture) = 0;
  virtual std::string name() const = 0;  ///< e.g. "icgp (region + depth)"
};

/// The tracker of `spec` for `scenario`'s object and the simulator's cameras: vpMbIcgTracker
/// (icgp), vpMbGenericTracker (visp, on a .cao written from the object's mesh into a temp
/// folder), or the ground truth (oracle). Model generation for icgp shows its progress on
/// stderr the first time and is cached.
std::unique_ptr<PoseEstimator> make_pose_estimator(const TrackerSpec& spec, const Scenario& scenario,
                                                   const RgbdSimulator& simulator);

}  // namespace icgp::servo
