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

ShapeTemplates::ShapeTemplates(const Mesh& mesh, std::vector<const ViewpointModel*> region_models,
                               const ViewpointModel* depth_model, int view_divides, double roll_step_deg, int points,
                               Filling filling)
    : sphere_(bounding_sphere(mesh)),
      points_(points),
      region_models_(std::move(region_models)),
      depth_model_(depth_model) {
  if (region_models_.empty()) throw std::invalid_argument("detection needs the body's region model");
  n_rolls_ = std::max(1, static_cast<int>(std::lround(360.0 / roll_step_deg)));
  roll_step_ = 2.0 * kPi / n_rolls_;
  for (const Eigen::Vector3f& direction : icosphere_directions(view_divides)) {
    View view;
    view.direction = direction;
    views_.push_back(std::move(view));
    const Eigen::Matrix3d R_view = view_rotation(direction.cast<double>());
    for (int k = 0; k < n_rolls_; ++k)
      templates_.push_back({Eigen::AngleAxisd(k * roll_step_, Eigen::Vector3d::UnitZ()).toRotationMatrix() * R_view, {}});
  }
  if (filling == Filling::kOnDemand) return;
  fill_all();
  if (std::none_of(views_.begin(), views_.end(), [](const View& v) { return v.usable; }))
    throw std::invalid_argument("detection: the region model has no usable contour in any view");
}

void ShapeTemplates::fill(std::size_t index) const {
  View& view = views_[index];
  if (view.filled) return;
  view.filled = true;
  if (depth_model_) {
    const int v = depth_model_->closest_view(view.direction);
    depth_model_->require_view(v);
    const ModelPoint* surface = depth_model_->points(v);
    for (int p = 0; p < std::min(kSurfacePoints, depth_model_->view_point_count(v)); ++p)
      view.surface.push_back(surface[p].position);
  }
  std::vector<BodyContourPoint> contour = spread_contour(region_models_, view.direction, points_);
  if (static_cast<int>(contour.size()) < kMinContourPoints) return;
  view.contour = std::move(contour);
  view.usable = true;
  const Eigen::Vector3f centre = sphere_.centre.cast<float>();
  for (int k = 0; k < n_rolls_; ++k) {
    Template& t = templates_[index * n_rolls_ + k];
    const Eigen::Matrix3f R = t.camera_R_body.cast<float>();
    std::vector<ContourPoint> points;
    for (const BodyContourPoint& p : view.contour) {
      const Eigen::Vector3f n = R * p.normal;
      if (n.head<2>().norm() < 0.3f) continue;  // a normal along the ray has no image orientation
      points.push_back({R * (p.position - centre), n.head<2>().normalized(), OrientationResponses::bin_of(n.x(), n.y())});
    }
    if (static_cast<int>(points.size()) >= kMinContourPoints) t.contour = std::move(points);
  }
}

void ShapeTemplates::fill_all() const {
  for (std::size_t v = 0; v < views_.size(); ++v) fill(v);
}

void ShapeTemplates::fill_near(const Eigen::Matrix3d& near_R, double max_rotation) const {
  // A template's rotation differs from near_R by at least the angle between their optical
  // axes, which is the angle between the directions they see the body from.
  const Eigen::Vector3f seen_from = (-near_R.transpose() * Eigen::Vector3d::UnitZ()).cast<float>();
  const float min_cos = static_cast<float>(std::cos(std::min(max_rotation, kPi)));
  for (std::size_t v = 0; v < views_.size(); ++v)
    if (views_[v].direction.dot(seen_from) >= min_cos - 1e-5f) fill(v);
}

const ShapeTemplates::View& ShapeTemplates::closest_view(const Pose& camera_T_body) const {
  // The camera's position seen from the sphere centre, in the body frame.
  const Eigen::Vector3d towards_camera = -(camera_T_body.rotation().transpose() * camera_T_body.translation()) - sphere_.centre;
  const Eigen::Vector3f d = towards_camera.normalized().cast<float>();
  // The closest view not known to be unusable, filled; again while it turns out unusable.
  for (;;) {
    const View* best = nullptr;
    for (const View& view : views_)
      if ((!view.filled || view.usable) && (!best || view.direction.dot(d) > best->direction.dot(d))) best = &view;
    if (!best) throw std::invalid_argument("detection: the region model has no usable contour in any view");
    fill(static_cast<std::size_t>(best - views_.data()));
    if (best->usable) return *best;
  }
}

Pose ShapeTemplates::pose(const Template& t, const Eigen::Vector3d& ray, double distance) const {
  const Eigen::Matrix3d turn = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), ray).toRotationMatrix();
  const Eigen::Matrix3d R = turn * t.camera_R_body;
  return Pose(R, distance * ray - R * sphere_.centre);
}

}  // namespace icgp
