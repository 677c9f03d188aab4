// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <vector>

#include "icgp/base/mesh.h"
#include "icgp/base/pose.h"
#include "icgp/model/viewpoint_model.h"

namespace icgp {

/// A body's detection templates, taken from what its sparse viewpoint models already hold
/// (docs/detection.md): for every template view, the contour points and outward normals of
/// the region models, and the surface points of the depth model. A template is a view at
/// an in-plane rotation: the camera looks at the centre of the body's bounding sphere with
/// rotation `camera_R_body`. Nothing is rendered.
class ShapeTemplates {
 public:
  /// A contour point relative to the sphere centre, rotated into the template camera.
  struct ContourPoint {
    Eigen::Vector3f position;      ///< camera_R_body (X - centre)
    Eigen::Vector2f image_normal;  ///< its outward normal in the image, unit
    int bin;                       ///< orientation bin of that normal (OrientationResponses)
  };
  struct Template {
    Eigen::Matrix3d camera_R_body;
    std::vector<ContourPoint> contour;
  };
  /// A contour point of a view in the body frame, with its outward normal.
  struct ViewContourPoint {
    Eigen::Vector3f position, normal;
  };
  struct View {
    Eigen::Vector3f direction;              ///< body frame, sphere centre -> camera
    std::vector<Eigen::Vector3f> surface;   ///< depth model points, body frame
    std::vector<ViewContourPoint> contour;  ///< the template points, body frame
  };

  /// `region_models`: every region model of the body (one for the whole body, or one per
  /// colour region; their contours all show in the image); `depth_model`: null without
  /// depth. Views are the directions of an icosphere of `view_divides` subdivisions, each at
  /// in-plane rotations `roll_step_deg` apart; `points` contour points per template, spread
  /// along the contour.
  ShapeTemplates(const Mesh& mesh, const std::vector<const ViewpointModel*>& region_models,
                 const ViewpointModel* depth_model, int view_divides, double roll_step_deg, int points);

  const Sphere& sphere() const { return sphere_; }
  const std::vector<Template>& templates() const { return templates_; }
  /// The view closest to how a camera at camera_T_body sees the body.
  const View& closest_view(const Pose& camera_T_body) const;
  int n_views() const { return static_cast<int>(views_.size()); }
  double roll_step() const { return roll_step_; }  ///< radians

  /// camera_T_body of template `t` with the sphere centre at `distance` metres along the
  /// camera ray `ray` (unit): the template's rotation turned with the ray, so that the
  /// object looks the same wherever it is in the image.
  Pose pose(const Template& t, const Eigen::Vector3d& ray, double distance) const;

 private:
  Sphere sphere_;
  double roll_step_ = 0.0;
  std::vector<View> views_;
  std::vector<Template> templates_;
};

}  // namespace icgp
