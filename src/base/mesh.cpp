// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/base/mesh.h"

#include <stdexcept>

namespace icgp {

std::size_t Mesh::vertex_count() const {
  std::size_t n = 0;
  for (const auto& p : parts) n += p.vertices.size();
  return n;
}

std::size_t Mesh::triangle_count() const {
  std::size_t n = 0;
  for (const auto& p : parts) n += p.triangles.size();
  return n;
}

std::vector<Eigen::Vector3f> Mesh::all_vertices() const {
  std::vector<Eigen::Vector3f> all;
  all.reserve(vertex_count());
  for (const auto& p : parts) all.insert(all.end(), p.vertices.begin(), p.vertices.end());
  return all;
}

void Mesh::bounds(Eigen::Vector3f& min_corner, Eigen::Vector3f& max_corner) const {
  if (vertex_count() == 0) throw std::runtime_error("mesh '" + source + "' has no vertices");
  min_corner.setConstant(std::numeric_limits<float>::max());
  max_corner.setConstant(std::numeric_limits<float>::lowest());
  for (const auto& p : parts)
    for (const auto& v : p.vertices) {
      min_corner = min_corner.cwiseMin(v);
      max_corner = max_corner.cwiseMax(v);
    }
}

float Mesh::radius_about_origin() const {
  float r2 = 0.f;
  for (const auto& p : parts)
    for (const auto& v : p.vertices) r2 = std::max(r2, v.squaredNorm());
  return std::sqrt(r2);
}

void Mesh::transform(const Posef& T) {
  for (auto& p : parts)
    for (auto& v : p.vertices) v = T * v;
}

void Mesh::append(const Mesh& other) { parts.insert(parts.end(), other.parts.begin(), other.parts.end()); }

}  // namespace icgp
