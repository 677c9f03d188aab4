// SPDX-License-Identifier: GPL-2.0-or-later
// The control law: ViSP's vpServo with PBVS or IBVS features, gain and saturation.
#pragma once

#include <memory>
#include <vector>
#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpPoint.h>

#include "icgp/servo/scenario.h"
#include "icgp/servo/simulated_robot.h"

namespace icgp::servo {

/// vpServo set up for the scenario's law: PBVS with s = (t(cdMc), θu(cdRc)) and s* = 0, or
/// IBVS on the projections of `ibvs_points` (object frame) against their projections at
/// the desired pose; interaction matrix at the desired pose for IBVS (constant, as ViSP's
/// examples), the current one for PBVS. Constant or adaptive gain (vpAdaptiveGain).
class ServoController {
 public:
  ServoController(const ControlSpec& spec, const vpHomogeneousMatrix& desired_cMo,
                  const std::vector<vpPoint>& ibvs_points, const SimulatedRobot& robot);
  ~ServoController();
  ServoController(const ServoController&) = delete;
  ServoController& operator=(const ServoController&) = delete;

  /// The velocity for `robot` (camera twist or joint velocities, vpServo's output) that
  /// drives the estimated pose `cMo` toward the desired one.
  vpColVector compute(const vpHomogeneousMatrix& cMo, const SimulatedRobot& robot);
  /// The servo error s - s* of the last compute().
  const vpColVector& error() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The 8 corners of the axis-aligned bounding box of the object's mesh, object frame: the
/// IBVS features.
std::vector<vpPoint> bounding_box_corners(const std::string& mesh_path);

/// How far apart two camera-object poses are: the distance between the object's origins in
/// the camera frame (metres) and the angle of the relative rotation (radians).
struct PoseError {
  double translation = 0.0;
  double rotation = 0.0;
};
PoseError pose_error(const vpHomogeneousMatrix& a_cMo, const vpHomogeneousMatrix& b_cMo);

}  // namespace icgp::servo
