// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/base/mesh.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

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

void check_mesh(const Mesh& mesh) {
  const auto refuse = [&](const std::string& what) {
    throw std::invalid_argument("mesh '" + mesh.source + "': " + what);
  };
  const std::size_t triangles = mesh.triangle_count();
  if (triangles == 0) refuse("has no triangle (expected a surface mesh with at least one)");
  if (triangles > MeshLimits::kMaxTriangles)
    refuse("has " + std::to_string(triangles) + " triangles (expected at most " + std::to_string(MeshLimits::kMaxTriangles) +
           "; decimate it)");
  for (std::size_t p = 0; p < mesh.parts.size(); ++p) {
    const MeshPart& part = mesh.parts[p];
    const std::string where = "part " + std::to_string(p) + " ";
    for (std::size_t i = 0; i < part.vertices.size(); ++i) {
      const Eigen::Vector3f& v = part.vertices[i];
      if (!v.allFinite() || v.cwiseAbs().maxCoeff() > MeshLimits::kMaxCoordinate)
        refuse(where + "vertex " + std::to_string(i) + " is (" + std::to_string(v.x()) + ", " + std::to_string(v.y()) +
               ", " + std::to_string(v.z()) + ") (expected finite coordinates within +-" +
               std::to_string(int(MeshLimits::kMaxCoordinate)) + " m)");
    }
    const auto n = static_cast<long long>(part.vertices.size());
    for (std::size_t t = 0; t < part.triangles.size(); ++t) {
      const Eigen::Vector3i& tri = part.triangles[t];
      if ((tri.array() < 0).any() || (tri.cast<long long>().array() >= n).any())
        refuse(where + "triangle " + std::to_string(t) + " has index (" + std::to_string(tri.x()) + ", " +
               std::to_string(tri.y()) + ", " + std::to_string(tri.z()) + ") (expected indices 0 to " +
               std::to_string(n - 1) + ")");
    }
    if (!part.texcoords.empty() && part.texcoords.size() != part.vertices.size())
      refuse(where + "has " + std::to_string(part.texcoords.size()) + " texture coordinates for " +
             std::to_string(part.vertices.size()) + " vertices (expected one per vertex or none)");
  }
  Eigen::Vector3f lo, hi;
  mesh.bounds(lo, hi);
  if (!((hi - lo).maxCoeff() > 0.f)) refuse("has all its vertices at one point (expected a surface with an extent)");
}

bool has_texture(const Mesh& mesh) {
  return std::any_of(mesh.parts.begin(), mesh.parts.end(),
                     [](const MeshPart& part) { return !part.material.texture_bgr.empty(); });
}

Mesh box_mesh(const Eigen::Vector3d& size, const Eigen::Vector3f& diffuse_rgb) {
  const Eigen::Vector3f h = (0.5 * size).cast<float>();
  MeshPart part;
  for (int i = 0; i < 8; ++i)
    part.vertices.emplace_back(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z());
  // Two counter-clockwise triangles per face, seen from outside.
  part.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                    {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  part.material.diffuse_rgb = diffuse_rgb;
  Mesh mesh;
  mesh.source = "box";
  mesh.parts.push_back(std::move(part));
  return mesh;
}

Sphere bounding_sphere(const Mesh& mesh) {
  Eigen::Vector3f lo, hi;
  mesh.bounds(lo, hi);
  const Eigen::Vector3f centre = 0.5f * (lo + hi);
  float radius = 0.f;
  for (const MeshPart& part : mesh.parts)
    for (const Eigen::Vector3f& v : part.vertices) radius = std::max(radius, (v - centre).norm());
  return {centre.cast<double>(), radius};
}

}  // namespace icgp
