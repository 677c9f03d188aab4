// SPDX-License-Identifier: GPL-2.0-or-later
#include "mesh_face_locator.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace icgp {
namespace {

constexpr int kLeafSize = 4;
// Barycentric slack within which a ray strictly meets a triangle: adjacent triangles
// overlap by a hair, so no ray slips through a shared edge.
constexpr double kEdgeTolerance = 1e-7;
// Barycentric slack of a near miss: the rasteriser works in float.
constexpr double kNearMissTolerance = 1e-3;
// Relative depth within which a triangle is where the rendered surface is.
constexpr double kDepthTolerance = 1e-4;

Eigen::Vector3d centroid(const Eigen::Vector3d& a, const Eigen::Vector3d& ab, const Eigen::Vector3d& ac) {
  return a + (ab + ac) / 3.0;
}

}  // namespace

MeshFaceLocator::MeshFaceLocator(const Mesh& mesh) {
  triangles_.reserve(mesh.triangle_count());
  for (const auto& part : mesh.parts)
    for (const auto& t : part.triangles) {
      const Eigen::Vector3d a = part.vertices[t[0]].cast<double>();
      const Eigen::Vector3d ab = part.vertices[t[1]].cast<double>() - a, ac = part.vertices[t[2]].cast<double>() - a;
      const Eigen::Vector3d n = ab.cross(ac);
      if (n.norm() > 0.0) triangles_.push_back({a, ab, ac, n.normalized()});  // degenerate ones show no pixel
    }
  nodes_.reserve(2 * triangles_.size() / kLeafSize + 1);
  if (!triangles_.empty()) build(0, static_cast<int>(triangles_.size()));
}

int MeshFaceLocator::build(int first, int count) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Eigen::AlignedBox3d box, centres;
  for (int i = first; i < first + count; ++i) {
    const Triangle& t = triangles_[i];
    box.extend(t.a).extend(t.a + t.ab).extend(t.a + t.ac);
    centres.extend(centroid(t.a, t.ab, t.ac));
  }
  // Padded, or a point on the surface a rounding error off a flat triangle would leave its box.
  const Eigen::Vector3d pad = Eigen::Vector3d::Constant(kNearMissTolerance * box.diagonal().norm());
  nodes_[index].box = Eigen::AlignedBox3d(box.min() - pad, box.max() + pad);
  if (count <= kLeafSize) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  // Median split along the widest spread of triangle centres.
  int axis = 0;
  centres.sizes().maxCoeff(&axis);
  const int half = count / 2;
  std::nth_element(triangles_.begin() + first, triangles_.begin() + first + half, triangles_.begin() + first + count,
                   [axis](const Triangle& l, const Triangle& r) {
                     return centroid(l.a, l.ab, l.ac)[axis] < centroid(r.a, r.ab, r.ac)[axis];
                   });
  build(first, half);
  const int right = build(first + half, count - half);
  nodes_[index].right = right;
  return index;
}

bool MeshFaceLocator::normal_at(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t,
                                Eigen::Vector3d& normal) const {
  const Eigen::Vector3d surface_point = origin + t * direction;
  const double depth_tolerance = kDepthTolerance * t;
  // Best candidate so far, ranked first by meeting the ray strictly, then by depth error.
  const Triangle* best = nullptr;
  bool best_strict = false;
  double best_error = std::numeric_limits<double>::infinity();
  int stack[64];  // depth is log2(triangles / kLeafSize): 64 levels is beyond any mesh
  int top = 0;
  if (!nodes_.empty()) stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!node.box.contains(surface_point)) continue;
    if (node.count == 0) {
      stack[top++] = node.right;
      stack[top++] = static_cast<int>(&node - nodes_.data()) + 1;
      continue;
    }
    for (int i = node.first; i < node.first + node.count; ++i) {
      // Möller–Trumbore: barycentric (u, v) and ray parameter s of the ray's meeting point.
      const Triangle& tri = triangles_[i];
      const Eigen::Vector3d p = direction.cross(tri.ac);
      const double det = tri.ab.dot(p);
      if (det == 0.0) continue;  // the ray runs in the triangle's plane: it cannot show it
      const Eigen::Vector3d w = origin - tri.a;
      const double u = w.dot(p) / det;
      const Eigen::Vector3d q = w.cross(tri.ab);
      const double v = direction.dot(q) / det;
      const double error = std::abs(tri.ac.dot(q) / det - t);
      const auto within = [u, v](double slack) { return u >= -slack && v >= -slack && u + v <= 1.0 + slack; };
      if (error > depth_tolerance || !within(kNearMissTolerance)) continue;
      const bool strict = within(kEdgeTolerance);
      if (best && (best_strict > strict || (best_strict == strict && best_error <= error))) continue;
      best = &tri;
      best_strict = strict;
      best_error = error;
    }
  }
  if (!best) return false;
  normal = best->normal.dot(direction) > 0.0 ? -best->normal : best->normal;
  return true;
}

}  // namespace icgp
