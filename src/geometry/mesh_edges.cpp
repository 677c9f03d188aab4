// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/geometry/mesh_edges.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

#include "icgp/base/pose.h"

namespace icgp {
namespace {

using Vec3 = Eigen::Vector3d;

/// Welds vertices that share a position, so that neighbouring faces share edges.
class VertexWelder {
 public:
  explicit VertexWelder(double tolerance) : tolerance_(tolerance) {}
  int index(const Vec3& p) {
    const std::array<long long, 3> key{std::llround(p.x() / tolerance_), std::llround(p.y() / tolerance_),
                                       std::llround(p.z() / tolerance_)};
    const auto [it, inserted] = indices_.try_emplace(key, static_cast<int>(positions_.size()));
    if (inserted) positions_.push_back(p);
    return it->second;
  }
  const Vec3& position(int i) const { return positions_[i]; }

 private:
  double tolerance_;
  std::map<std::array<long long, 3>, int> indices_;
  std::vector<Vec3> positions_;
};

/// Face–vertex tests is_convex makes at most (a few tens of milliseconds).
constexpr double kMaxConvexityTests = 5e7;

double mesh_size(const Mesh& mesh) {
  Eigen::Vector3f lo, hi;
  mesh.bounds(lo, hi);
  return std::max(1e-9, static_cast<double>((hi - lo).norm()));
}

}  // namespace

std::vector<MeshEdge> mesh_edges(const Mesh& mesh, double crease_angle_deg) {
  VertexWelder welder(1e-6 * mesh_size(mesh));
  std::map<std::pair<int, int>, std::vector<Vec3>> normals_of_edge;
  for (const MeshPart& part : mesh.parts)
    for (const Eigen::Vector3i& t : part.triangles) {
      const int v[3] = {welder.index(part.vertices[t[0]].cast<double>()),
                        welder.index(part.vertices[t[1]].cast<double>()),
                        welder.index(part.vertices[t[2]].cast<double>())};
      const Vec3 n =
          (welder.position(v[1]) - welder.position(v[0])).cross(welder.position(v[2]) - welder.position(v[0]));
      if (n.norm() <= 0.0) continue;  // degenerate: no face, no edge
      for (int i = 0; i < 3; ++i) normals_of_edge[std::minmax(v[i], v[(i + 1) % 3])].push_back(n.normalized());
    }
  const double cos_crease = std::cos(deg_to_rad(crease_angle_deg));
  std::vector<MeshEdge> edges;
  edges.reserve(normals_of_edge.size());
  for (const auto& [ends, normals] : normals_of_edge) {
    MeshEdge e{welder.position(ends.first), welder.position(ends.second), normals.front(),
               normals.size() > 1 ? normals[1] : normals.front(), false};
    e.crease = normals.size() != 2 || e.normal_1.dot(e.normal_2) < cos_crease;
    edges.push_back(e);
  }
  return edges;
}

bool is_convex(const Mesh& mesh) {
  const std::vector<Eigen::Vector3f> vertices = mesh.all_vertices();
  std::size_t n_faces = 0;
  for (const MeshPart& part : mesh.parts) n_faces += part.triangles.size();
  if (static_cast<double>(n_faces) * static_cast<double>(vertices.size()) > kMaxConvexityTests) return false;
  const float tolerance = static_cast<float>(1e-3 * mesh_size(mesh));
  for (const MeshPart& part : mesh.parts)
    for (const Eigen::Vector3i& t : part.triangles) {
      const Eigen::Vector3f& p = part.vertices[t[0]];
      const Eigen::Vector3f n = (part.vertices[t[1]] - p).cross(part.vertices[t[2]] - p);
      if (n.norm() <= 0.f) continue;
      const Eigen::Vector3f unit = n.normalized();
      for (const Eigen::Vector3f& v : vertices)
        if (unit.dot(v - p) > tolerance) return false;
    }
  return true;
}

}  // namespace icgp
