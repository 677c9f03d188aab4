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
///
/// Filled on demand, a view's templates are made the first time a search may reach them
/// (fill_near, fill_all, closest_view): on a cold cache the detection then waits only for
/// the model views it reads, as the tracker does (ViewpointModel::require_view). Templates
/// keep their index whatever order their views are filled in, so searches give the same
/// matches either way.
class ShapeTemplates {
 public:
  enum class Filling { kNow, kOnDemand };

  /// A contour point relative to the sphere centre, rotated into the template camera.
  struct ContourPoint {
    Eigen::Vector3f position;      ///< camera_R_body (X - centre)
    Eigen::Vector2f image_normal;  ///< its outward normal in the image, unit
    int bin;                       ///< orientation bin of that normal (OrientationResponses)
  };
  struct Template {
    Eigen::Matrix3d camera_R_body;
    std::vector<ContourPoint> contour;  ///< empty: its view is not filled yet, or shows too little
  };
  /// A contour point of a view in the body frame, with its outward normal.
  struct ViewContourPoint {
    Eigen::Vector3f position, normal;
  };
  struct View {
    Eigen::Vector3f direction;              ///< body frame, sphere centre -> camera
    std::vector<Eigen::Vector3f> surface;   ///< depth model points, body frame
    std::vector<ViewContourPoint> contour;  ///< the template points, body frame
    bool filled = false;
    bool usable = false;  ///< filled with enough contour points to be matched
  };

  /// `region_models`: every region model of the body (one for the whole body, or one per
  /// colour region; their contours all show in the image); `depth_model`: null without
  /// depth. Views are the directions of an icosphere of `view_divides` subdivisions, each at
  /// in-plane rotations `roll_step_deg` apart; `points` contour points per template, spread
  /// along the contour.
  /// kNow fills every view here and throws std::invalid_argument when none is usable;
  /// kOnDemand leaves them to the searches. The models must outlive the templates.
  ShapeTemplates(const Mesh& mesh, std::vector<const ViewpointModel*> region_models, const ViewpointModel* depth_model,
                 int view_divides, double roll_step_deg, int points, Filling filling = Filling::kNow);

  const Sphere& sphere() const { return sphere_; }
  /// Every view's templates, at fixed indices; those of views not filled yet have no
  /// contour points and match nothing.
  const std::vector<Template>& templates() const { return templates_; }
  /// Fills the views whose templates may lie within `max_rotation` of `near_R` (a
  /// camera_R_body looking at the sphere centre): those seen from within that angle.
  void fill_near(const Eigen::Matrix3d& near_R, double max_rotation) const;
  void fill_all() const;
  /// The usable view closest to how a camera at camera_T_body sees the body, filled if
  /// need be.
  const View& closest_view(const Pose& camera_T_body) const;
  int n_views() const { return static_cast<int>(views_.size()); }  ///< usable or not
  double roll_step() const { return roll_step_; }  ///< radians

  /// camera_T_body of template `t` with the sphere centre at `distance` metres along the
  /// camera ray `ray` (unit): the template's rotation turned with the ray, so that the
  /// object looks the same wherever it is in the image.
  Pose pose(const Template& t, const Eigen::Vector3d& ray, double distance) const;

 private:
  void fill(std::size_t view) const;

  Sphere sphere_;
  double roll_step_ = 0.0;
  int n_rolls_ = 1;
  int points_ = 0;
  std::vector<const ViewpointModel*> region_models_;
  const ViewpointModel* depth_model_ = nullptr;
  // Filled on demand: a cache of what the models hold, not state a caller sees change.
  mutable std::vector<View> views_;
  mutable std::vector<Template> templates_;  ///< view v's rolls at v * n_rolls_ + k
};

}  // namespace icgp
