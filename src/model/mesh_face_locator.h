// SPDX-License-Identifier: GPL-2.0-or-later
// Private to model generation: which triangle a pixel of a rendered view shows.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "icgp/base/mesh.h"

namespace icgp {

/// Finds the mesh triangle the rasteriser drew at a pixel, from the pixel's ray and the
/// rendered depth there, through a bounding volume hierarchy. Model generation asks it for
/// the face normal at the few hundred pixels per view it samples: a normal image costs a
/// 48 MB readback per 2000x2000 view. Thread-safe once built.
class MeshFaceLocator {
 public:
  explicit MeshFaceLocator(const Mesh& mesh);

  /// The unit normal, turned towards the origin as the renderer's normal image has it, of
  /// the triangle that the ray origin + s·direction meets at s = t (the rendered depth when
  /// direction is the camera ray (x, y, 1) rotated into the mesh frame). Among triangles met
  /// within a rounding error of t, one that contains the ray strictly wins (at a crease
  /// either face is right); a triangle the ray misses by a rounding error counts too, as
  /// the float rasteriser may draw pixel centres just outside a silhouette edge. False when
  /// no triangle is there.
  bool normal_at(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t,
                 Eigen::Vector3d& normal) const;

 private:
  struct Triangle {
    Eigen::Vector3d a, ab, ac, normal;
  };
  struct Node {
    Eigen::AlignedBox3d box;   ///< of its triangles, padded by the rounding tolerance
    int first = 0, count = 0;  ///< leaf: triangles_[first, first + count)
    int right = 0;             ///< inner node: the left child follows it, the right child is here
  };

  int build(int first, int count);

  std::vector<Triangle> triangles_;
  std::vector<Node> nodes_;
};

}  // namespace icgp
