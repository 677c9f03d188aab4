// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/detection/shape_templates.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "icgp/detection/orientation_responses.h"
#include "icgp/model/icosphere.h"

namespace icgp {
namespace {

/// Depth points kept per view for the depth check.
constexpr int kSurfacePoints = 48;
/// A template with fewer contour points than this says too little to be matched.
constexpr int kMinContourPoints = 8;

/// camera_R_body of a camera on `direction` (body frame, towards the camera) looking at
/// the body, with the up vector view_camera uses.
Eigen::Matrix3d view_rotation(const Eigen::Vector3d& direction) {
  const Eigen::Vector3d up = std::abs(direction.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
  return look_at<double>(direction, Eigen::Vector3d::Zero(), up).rotation();
}

using BodyContourPoint = ShapeTemplates::ViewContourPoint;

/// The contour points of every region model in the view closest to `direction`, picked
/// in their (random) order so that no two lie closer than an even spread of `count` points
/// along the contour would put them.
std::vector<BodyContourPoint> spread_contour(const std::vector<const ViewpointModel*>& models,
                                             const Eigen::Vector3f& direction, int count) {
  std::vector<BodyContourPoint> all;
  double length = 0.0;
  for (const ViewpointModel* model : models) {
    const int v = model->closest_view(direction);
    model->require_view(v);
    length += model->view(v).measure;
    const ModelPoint* points = model->points(v);
    for (int p = 0; p < model->view_point_count(v); ++p) all.push_back({points[p].position, points[p].normal});
  }
  const float spacing = static_cast<float>(0.7 * length / std::max(count, 1));
  std::vector<BodyContourPoint> kept;
  for (const BodyContourPoint& p : all) {
    if (static_cast<int>(kept.size()) >= count) break;
    bool far = true;
    for (const BodyContourPoint& k : kept) far = far && (k.position - p.position).norm() >= spacing;
    if (far) kept.push_back(p);
  }
  return kept;
}

}  // namespace

ShapeTemplates::ShapeTemplates(const Mesh& mesh, const std::vector<const ViewpointModel*>& region_models,
                               const ViewpointModel* depth_model, int view_divides, double roll_step_deg, int points)
    : sphere_(bounding_sphere(mesh)), roll_step_(roll_step_deg * kPi / 180.0) {
  if (region_models.empty()) throw std::invalid_argument("detection needs the body's region model");
  const int n_rolls = std::max(1, static_cast<int>(std::lround(360.0 / roll_step_deg)));
  roll_step_ = 2.0 * kPi / n_rolls;
  const Eigen::Vector3f centre = sphere_.centre.cast<float>();
  for (const Eigen::Vector3f& direction : icosphere_directions(view_divides)) {
    View view;
    view.direction = direction;
    if (depth_model) {
      const int v = depth_model->closest_view(direction);
      depth_model->require_view(v);
      const ModelPoint* surface = depth_model->points(v);
      for (int p = 0; p < std::min(kSurfacePoints, depth_model->view_point_count(v)); ++p)
        view.surface.push_back(surface[p].position);
    }
    const std::vector<BodyContourPoint> contour = spread_contour(region_models, direction, points);
    if (static_cast<int>(contour.size()) < kMinContourPoints) continue;
    view.contour = contour;
    views_.push_back(std::move(view));
    const Eigen::Matrix3d R_view = view_rotation(direction.cast<double>());
    for (int k = 0; k < n_rolls; ++k) {
      Template t;
      t.camera_R_body = Eigen::AngleAxisd(k * roll_step_, Eigen::Vector3d::UnitZ()).toRotationMatrix() * R_view;
      const Eigen::Matrix3f R = t.camera_R_body.cast<float>();
      for (const BodyContourPoint& p : contour) {
        const Eigen::Vector3f n = R * p.normal;
        if (n.head<2>().norm() < 0.3f) continue;  // a normal along the ray has no image orientation
        t.contour.push_back({R * (p.position - centre), n.head<2>().normalized(), OrientationResponses::bin_of(n.x(), n.y())});
      }
      if (static_cast<int>(t.contour.size()) >= kMinContourPoints) templates_.push_back(std::move(t));
    }
  }
  if (templates_.empty()) throw std::invalid_argument("detection: the region model has no usable contour in any view");
}

const ShapeTemplates::View& ShapeTemplates::closest_view(const Pose& camera_T_body) const {
  // The camera's position seen from the sphere centre, in the body frame.
  const Eigen::Vector3d towards_camera = -(camera_T_body.rotation().transpose() * camera_T_body.translation()) - sphere_.centre;
  const Eigen::Vector3f d = towards_camera.normalized().cast<float>();
  return *std::max_element(views_.begin(), views_.end(),
                           [&](const View& a, const View& b) { return a.direction.dot(d) < b.direction.dot(d); });
}

Pose ShapeTemplates::pose(const Template& t, const Eigen::Vector3d& ray, double distance) const {
  const Eigen::Matrix3d turn = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), ray).toRotationMatrix();
  const Eigen::Matrix3d R = turn * t.camera_R_body;
  return Pose(R, distance * ray - R * sphere_.centre);
}

}  // namespace icgp
