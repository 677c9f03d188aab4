// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"
#include "icgp/base/mesh.h"
#include "icgp/geometry/mesh_edges.h"

namespace icgp {

/// A segment in image coordinates (pixels, u right, v down).
struct ImageSegment {
  Eigen::Vector2d a, b;
};

/// The edges a person would draw of a mesh: creases (faces meeting at more than
/// crease_angle), open borders, and at a given pose the silhouette (edges between a face
/// turned towards the camera and one turned away), so that curved surfaces show their
/// outline without their facets. For overlays of a pose estimate.
class ModelEdges {
 public:
  explicit ModelEdges(const Mesh& mesh, double crease_angle_deg = 30.0);

  /// Edges at camera_T_body projected into the image. With a depth render of the body at
  /// that pose (`rendered_depth`, CV_32FC1, the size of `intrinsics`), only the parts not
  /// hidden by the body itself are returned, sampled every `step` pixels; with an empty
  /// one, every crease and silhouette edge in front of the camera is returned whole.
  std::vector<ImageSegment> project(const Intrinsics& intrinsics, const Pose& camera_T_body,
                                    const cv::Mat& rendered_depth, double step = 2.0) const;

 private:
  void visible_parts(const Intrinsics& k, const Pose& camera_T_body, const cv::Mat& depth, const MeshEdge& edge,
                     double step, std::vector<ImageSegment>& out) const;

  std::vector<MeshEdge> edges_;  ///< every edge between two faces or on a border
};

}  // namespace icgp
