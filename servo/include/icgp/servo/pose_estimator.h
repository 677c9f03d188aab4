// SPDX-License-Identifier: GPL-2.0-or-later
// The trackers a scenario can close the loop with, behind one interface.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>
#include <visp3/core/vpHomogeneousMatrix.h>

#include "icgp/modality/modality.h"
#include "icgp/servo/rgbd_simulator.h"
#include "icgp/servo/scenario.h"

namespace icgp::servo {

/// How one cue of the tracker fit a frame, as the tracker reports it
/// (vpMbIcgTracker::getCueQualities).
struct CueFit {
  std::string cue;     ///< "region", "depth", "texture", ...
  std::string camera;  ///< the camera it reads: "Camera1" (colour), "Camera2" (depth)
  /// Its score in [0, 1] (the tracker's quality is their median), the noise sigma it was
  /// weighed with (pixels; depth: metres at 1 m), the share of its points with data, and
  /// whether it had nothing to measure (abstained).
  ModalityQuality quality;
};

/// What a tracker says after a frame.
struct PoseEstimate {
  vpHomogeneousMatrix cMo;
  bool lost = false;     ///< the tracker's own verdict (vpMbTracker::testTracking threw)
  double track_ms = 0.0;  ///< the track() call alone
  /// Grasp: the gripper's pose, when the tracker gives it (icgp tracks it as a second body,
  /// the oracle knows it). Empty: the loop takes it from the arm's kinematics.
  std::optional<vpHomogeneousMatrix> cMg;
  /// After a detection: further poses of the object (cMo) the tracker verified as well as
  /// cMo, which a symmetry of the object makes indistinguishable from it.
  std::vector<vpHomogeneousMatrix> equivalents;
  std::string why_lost;  ///< when lost, the tracker's reason, when it gives one
  /// After track(): each cue's fit on the frame, from a tracker that reports it (icgp);
  /// empty from the others, and after a detection.
  std::vector<CueFit> cues;
};

/// A pose tracker fed with the simulated RGB-D captures through ViSP's API.
class PoseEstimator {
 public:
  virtual ~PoseEstimator() = default;
  /// Starts tracking at `cMo` on `first`; in a grasp, the gripper at `cMg` (trackers that
  /// do not follow the gripper ignore it).
  virtual void start(const RgbdCapture& first, const vpHomogeneousMatrix& cMo,
                     const std::optional<vpHomogeneousMatrix>& cMg) = 0;
  virtual PoseEstimate track(const RgbdCapture& capture) = 0;
  /// Finds the object in `capture` without a given pose and starts tracking there (in a
  /// grasp, the gripper at `cMg`, which the arm's kinematics give); `lost` when no pose is
  /// verified (or the tracker cannot detect), with the time the search took.
  virtual PoseEstimate detect(const RgbdCapture&, const std::optional<vpHomogeneousMatrix>&) {
    PoseEstimate none;
    none.lost = true;
    return none;
  }
  /// Whether the tracker can detect (detect() may find something).
  virtual bool detects() const { return false; }
  /// Whether the tracker searches for the object itself after a loss; otherwise the loop
  /// restarts it at the last trusted pose.
  virtual bool recovers() const { return false; }
  virtual std::string name() const = 0;  ///< e.g. "icgp (region + depth)"
};

/// The tracker of `spec` for `scenario`'s object and the simulator's cameras: vpMbIcgTracker
/// (icgp; in a grasp it tracks the gripper too, as a second body), vpMbGenericTracker
/// (visp, the object alone, on a .cao written from the object's mesh into a temp folder),
/// or the ground truth (oracle, of the gripper too). Model generation for icgp shows its progress on
/// stderr the first time and is cached.
std::unique_ptr<PoseEstimator> make_pose_estimator(const TrackerSpec& spec, const Scenario& scenario,
                                                   const RgbdSimulator& simulator);

}  // namespace icgp::servo
