// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/servo/servo_controller.h"

#include <visp3/core/vpThetaUVector.h>
#include <visp3/visual_features/vpFeatureBuilder.h>
#include <visp3/visual_features/vpFeaturePoint.h>
#include <visp3/visual_features/vpFeatureThetaU.h>
#include <visp3/visual_features/vpFeatureTranslation.h>
#include <visp3/vs/vpAdaptiveGain.h>
#include <visp3/vs/vpServo.h>

#include "icgp/visp/cao_mesh_loader.h"

namespace icgp::servo {

struct ServoController::Impl {
  vpServo task;
  vpHomogeneousMatrix desired_cMo;
  // PBVS
  vpFeatureTranslation translation{vpFeatureTranslation::cdMc};
  vpFeatureThetaU rotation{vpFeatureThetaU::cdRc};
  // IBVS: current and desired projections of the model points
  std::vector<vpPoint> points;
  std::vector<vpFeaturePoint> current, desired;
  ControlLawKind law;
  vpColVector error;  ///< s - s* of the last compute()
};

ServoController::ServoController(const ControlSpec& spec, const vpHomogeneousMatrix& desired_cMo,
                                 const std::vector<vpPoint>& ibvs_points, const SimulatedRobot& robot)
    : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.desired_cMo = desired_cMo;
  d.law = spec.law;
  d.task.setServo(robot.servo_type());
  if (spec.gain.adaptive())
    d.task.setLambda(vpAdaptiveGain(spec.gain.at_zero, spec.gain.at_infinity, spec.gain.slope_at_zero));
  else
    d.task.setLambda(spec.gain.at_zero);

  if (spec.law == ControlLawKind::kPbvs) {
    // s = (t(cdMc), θu(cdRc)) with s* = 0; the interaction matrix at the current pose is
    // exact for these features, so the camera moves along a straight line.
    d.task.setInteractionMatrixType(vpServo::CURRENT);
    d.task.addFeature(d.translation);
    d.task.addFeature(d.rotation);
    return;
  }
  // IBVS with the interaction matrix at the desired pose: constant, well conditioned near
  // convergence, and what ViSP's point-based examples use.
  d.task.setInteractionMatrixType(vpServo::DESIRED, vpServo::PSEUDO_INVERSE);
  d.points = ibvs_points;
  d.current.resize(d.points.size());
  d.desired.resize(d.points.size());
  for (std::size_t i = 0; i < d.points.size(); ++i) {
    vpPoint point = d.points[i];
    point.track(desired_cMo);
    vpFeatureBuilder::create(d.desired[i], point);
    d.task.addFeature(d.current[i], d.desired[i]);
  }
}

ServoController::~ServoController() = default;

vpColVector ServoController::compute(const vpHomogeneousMatrix& cMo, const SimulatedRobot& robot) {
  Impl& d = *impl_;
  if (d.law == ControlLawKind::kPbvs) {
    const vpHomogeneousMatrix cdMc = d.desired_cMo * cMo.inverse();
    d.translation.buildFrom(cdMc);
    d.rotation.buildFrom(cdMc);
  } else {
    for (std::size_t i = 0; i < d.points.size(); ++i) {
      d.points[i].track(cMo);
      vpFeatureBuilder::create(d.current[i], d.points[i]);
    }
  }
  robot.update_jacobians(d.task);
  const vpColVector velocity = d.task.computeControlLaw();
  d.error = d.task.getError();
  return velocity;
}

const vpColVector& ServoController::error() const { return impl_->error; }

std::vector<vpPoint> bounding_box_corners(const std::string& mesh_path) {
  Eigen::Vector3f lo, hi;
  load_any_mesh(mesh_path).bounds(lo, hi);
  std::vector<vpPoint> corners;
  for (int i = 0; i < 8; ++i)
    corners.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  return corners;
}

PoseError pose_error(const vpHomogeneousMatrix& a_cMo, const vpHomogeneousMatrix& b_cMo) {
  const vpTranslationVector dt = a_cMo.getTranslationVector() - b_cMo.getTranslationVector();
  const vpRotationMatrix dR = a_cMo.getRotationMatrix() * b_cMo.getRotationMatrix().t();
  return {dt.frobeniusNorm(), vpThetaUVector(dR).getTheta()};
}

}  // namespace icgp::servo
