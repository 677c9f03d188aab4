// SPDX-License-Identifier: GPL-2.0-or-later
// Meshes with exactly known geometry, built in code so tests do not depend on loaders.
#pragma once

#include <opencv2/imgproc.hpp>
#include <vector>

#include "icgp/base/intrinsics.h"
#include "icgp/base/mesh.h"

namespace icgp::test {

/// Axis-aligned box centred on the origin with the given side lengths (12 triangles).
inline Mesh make_box(float sx, float sy, float sz) {
  MeshPart part;
  const float x = sx / 2, y = sy / 2, z = sz / 2;
  for (int i = 0; i < 8; ++i)
    part.vertices.emplace_back((i & 1) ? x : -x, (i & 2) ? y : -y, (i & 4) ? z : -z);
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    part.triangles.emplace_back(q[0], q[1], q[2]);
    part.triangles.emplace_back(q[0], q[2], q[3]);
  }
  Mesh mesh;
  mesh.source = "box";
  mesh.parts.push_back(part);
  return mesh;
}

/// The image outline of an origin-centred box with half-sizes `half` at camera_T_box: the
/// convex hull of its projected corners (a box is convex, so this is its silhouette).
inline std::vector<cv::Point2f> projected_box_outline(const Intrinsics& k, const Pose& camera_T_box,
                                                      const Eigen::Vector3d& half) {
  std::vector<cv::Point2f> corners, hull;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d corner((c & 1) ? half.x() : -half.x(), (c & 2) ? half.y() : -half.y(),
                                 (c & 4) ? half.z() : -half.z());
    const Eigen::Vector2d x = k.project<double>(camera_T_box * corner);
    corners.emplace_back(static_cast<float>(x.x()), static_cast<float>(x.y()));
  }
  cv::convexHull(corners, hull);
  return hull;
}

/// One triangle with the given vertices.
inline Mesh make_triangle(const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c) {
  MeshPart part;
  part.vertices = {a, b, c};
  part.triangles = {Eigen::Vector3i(0, 1, 2)};
  Mesh mesh;
  mesh.source = "triangle";
  mesh.parts.push_back(part);
  return mesh;
}

/// Calls f(a, b, c) with the corners (as Eigen::Vector3d) of every triangle of the mesh.
template <typename F>
void for_each_triangle(const Mesh& mesh, F&& f) {
  for (const MeshPart& part : mesh.parts)
    for (const Eigen::Vector3i& t : part.triangles)
      f(part.vertices[t[0]].cast<double>(), part.vertices[t[1]].cast<double>(), part.vertices[t[2]].cast<double>());
}

/// The total area of the mesh's triangles.
inline double mesh_surface_area(const Mesh& mesh) {
  double area = 0.0;
  for_each_triangle(mesh, [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    area += 0.5 * (b - a).cross(c - a).norm();
  });
  return area;
}

/// Divergence theorem: the enclosed volume, positive, for a closed surface whose triangles
/// face outwards.
inline double mesh_signed_volume(const Mesh& mesh) {
  double volume = 0.0;
  for_each_triangle(mesh, [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    volume += a.dot(b.cross(c)) / 6.0;
  });
  return volume;
}

}  // namespace icgp::test
