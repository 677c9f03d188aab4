// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <vector>

#include "icgp/base/mesh.h"

namespace icgp {

/// An edge of a mesh, with the faces on either side.
struct MeshEdge {
  Eigen::Vector3d a, b;                ///< its ends, body frame
  Eigen::Vector3d normal_1, normal_2;  ///< unit normals of the faces on either side (equal on a border)
  /// Its faces meet at more than the crease angle, or it is a border, or more than two faces
  /// share it: a line a person would draw, and one the image shows as a step of brightness.
  bool crease = false;
};

/// Every edge between two faces or on a border of `mesh`, once. Vertices that share a
/// position are welded first (meshes repeat them per face for normals and texture
/// coordinates), so that neighbouring faces share their edges; degenerate faces give none.
std::vector<MeshEdge> mesh_edges(const Mesh& mesh, double crease_angle_deg);

/// Whether every vertex of `mesh` lies behind or on the plane of every face (within
/// 0.1 % of the mesh's size): a convex body never hides a part of itself that faces the
/// camera. A mesh too large to check in a few tens of milliseconds counts as not convex.
bool is_convex(const Mesh& mesh);

}  // namespace icgp
