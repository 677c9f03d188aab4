// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/visp/cao_writer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

namespace icgp {
namespace {

using Vec3 = Eigen::Vector3d;
using Polygon = std::vector<int>;  // corner indices, counter-clockwise seen from outside

constexpr double kWeldTolerance = 1e-7;  // m: positions closer than this are one point
constexpr double kCoplanarAngle = 1e-3;  // rad: triangles closer than this to a plane lie in it

/// Triangles over one shared, welded point list: parts often repeat positions (one copy
/// per texture seam or material), and faces can only be merged across shared corners.
struct WeldedMesh {
  std::vector<Vec3> points;
  std::vector<std::array<int, 3>> triangles;  // non-degenerate only
  std::vector<Vec3> normals;                  // unit, per triangle
  std::vector<double> areas;                  // per triangle
};

/// Welds with a grid of kWeldTolerance cells: two points within the tolerance are always
/// in the same or adjacent cells. Each point joins the first earlier point it is close to.
WeldedMesh weld(const Mesh& mesh) {
  using Cell = std::array<std::int64_t, 3>;
  const auto cell_of = [](const Vec3& p) {
    return Cell{static_cast<std::int64_t>(std::floor(p.x() / kWeldTolerance)),
                static_cast<std::int64_t>(std::floor(p.y() / kWeldTolerance)),
                static_cast<std::int64_t>(std::floor(p.z() / kWeldTolerance))};
  };
  WeldedMesh out;
  std::map<Cell, std::vector<int>> grid;
  const auto point_index = [&](const Vec3& p) {
    const Cell c = cell_of(p);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto found = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (found == grid.end()) continue;
          for (const int i : found->second)
            if ((out.points[i] - p).norm() <= kWeldTolerance) return i;
        }
    out.points.push_back(p);
    grid[c].push_back(static_cast<int>(out.points.size()) - 1);
    return static_cast<int>(out.points.size()) - 1;
  };

  for (const MeshPart& part : mesh.parts) {
    std::vector<int> welded(part.vertices.size());
    for (std::size_t i = 0; i < part.vertices.size(); ++i) {
      const Vec3 p = part.vertices[i].cast<double>();
      if (!p.allFinite()) throw std::invalid_argument("write_cao: mesh '" + mesh.source + "' has a non-finite vertex");
      welded[i] = point_index(p);
    }
    for (const Eigen::Vector3i& t : part.triangles) {
      std::array<int, 3> w{};
      for (int k = 0; k < 3; ++k) {
        if (t[k] < 0 || static_cast<std::size_t>(t[k]) >= welded.size())
          throw std::invalid_argument("write_cao: mesh '" + mesh.source + "' has a vertex index out of range");
        w[k] = welded[t[k]];
      }
      // Triangles without area (collapsed by welding, or slivers) bound nothing and have
      // no normal to group them by; leaving them out does not change the surface.
      const Vec3 &a = out.points[w[0]], &b = out.points[w[1]], &c = out.points[w[2]];
      const Vec3 cross = (b - a).cross(c - a);
      const double longest2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
      if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0] || !(cross.norm() > 1e-12 * longest2)) continue;
      out.triangles.push_back(w);
      out.normals.push_back(cross.normalized());
      out.areas.push_back(0.5 * cross.norm());
    }
  }
  return out;
}

/// Groups edge-adjacent triangles lying in one plane. Each group grows from its largest
/// triangle (the most reliable normal) and every member is compared with that seed's
/// plane, not with its neighbour, so that a finely tessellated curved surface cannot drift
/// into one "flat" face a little at a time.
std::vector<std::vector<int>> coplanar_groups(const WeldedMesh& m) {
  std::map<std::pair<int, int>, std::vector<int>> triangles_of_edge;  // undirected edge
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3];
      triangles_of_edge[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(t));
    }

  std::vector<int> by_area(m.triangles.size());
  std::iota(by_area.begin(), by_area.end(), 0);
  std::stable_sort(by_area.begin(), by_area.end(), [&](int a, int b) { return m.areas[a] > m.areas[b]; });

  const double cos_tolerance = std::cos(kCoplanarAngle);
  const double sin_tolerance = std::sin(kCoplanarAngle);
  std::vector<bool> assigned(m.triangles.size(), false);
  std::vector<std::vector<int>> groups;
  for (const int seed : by_area) {
    if (assigned[seed]) continue;
    const Vec3& normal = m.normals[seed];
    const Vec3 centre = (m.points[m.triangles[seed][0]] + m.points[m.triangles[seed][1]] +
                         m.points[m.triangles[seed][2]]) / 3.0;
    const auto in_plane = [&](int t) {
      if (m.normals[t].dot(normal) < cos_tolerance) return false;
      for (const int i : m.triangles[t]) {
        const Vec3 d = m.points[i] - centre;
        if (std::abs(d.dot(normal)) > kWeldTolerance + sin_tolerance * d.norm()) return false;
      }
      return true;
    };
    std::vector<int> group{seed};
    assigned[seed] = true;
    for (std::size_t g = 0; g < group.size(); ++g) {
      const auto& t = m.triangles[group[g]];
      for (int k = 0; k < 3; ++k) {
        const int a = t[k], b = t[(k + 1) % 3];
        for (const int n : triangles_of_edge[{std::min(a, b), std::max(a, b)}])
          if (!assigned[n] && in_plane(n)) {
            assigned[n] = true;
            group.push_back(n);
          }
      }
    }
    groups.push_back(std::move(group));
  }
  return groups;
}

/// The outline of a group of triangles as one loop in their winding direction, or nothing
/// when the group has holes or touches itself at a corner (boundary not one simple loop).
std::optional<Polygon> outline(const WeldedMesh& m, const std::vector<int>& group) {
  // A boundary edge is a directed edge of the group whose reverse is not: interior edges
  // appear once in each direction and cancel.
  std::map<std::pair<int, int>, int> count;
  for (const int t : group)
    for (int k = 0; k < 3; ++k) ++count[{m.triangles[t][k], m.triangles[t][(k + 1) % 3]}];
  std::map<int, std::vector<int>> next;
  std::size_t edges = 0;
  for (const auto& [edge, n] : count) {
    const auto reverse = count.find({edge.second, edge.first});
    const int boundary = n - (reverse == count.end() ? 0 : reverse->second);
    for (int i = 0; i < boundary; ++i, ++edges) next[edge.first].push_back(edge.second);
  }
  if (edges < 3) return std::nullopt;
  for (const auto& [from, to] : next)
    if (to.size() != 1) return std::nullopt;

  Polygon loop{next.begin()->first};
  while (loop.size() <= edges) {
    const auto step = next.find(loop.back());
    if (step == next.end()) return std::nullopt;  // open chain: cannot happen for balanced edges
    if (step->second.front() == loop.front()) break;
    loop.push_back(step->second.front());
  }
  if (loop.size() != edges) return std::nullopt;  // more than one loop: a face with holes
  return loop;
}

/// Drops corners lying on the straight line between their neighbours: the polygon keeps its
/// shape, and an edge split only because the triangulation had a vertex there (e.g. where
/// two parts meet) stays one edge, which ViSP can then share with the adjacent face.
Polygon drop_straight_corners(const WeldedMesh& m, const Polygon& loop) {
  Polygon kept;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec3& prev = m.points[kept.empty() ? loop.back() : kept.back()];
    const Vec3& here = m.points[loop[i]];
    const Vec3& following = m.points[loop[(i + 1) % loop.size()]];
    const Vec3 span = following - prev;
    const bool straight = span.norm() > 0.0 && (here - prev).dot(span) > 0.0 && (following - here).dot(span) > 0.0 &&
                          span.cross(here - prev).norm() / span.norm() <= kWeldTolerance;
    if (!straight) kept.push_back(loop[i]);
  }
  return kept.size() >= 3 ? kept : loop;
}

}  // namespace

void write_cao(const Mesh& mesh, const std::string& path) {
  if (mesh.empty()) throw std::invalid_argument("write_cao: mesh '" + mesh.source + "' has no triangles");
  const WeldedMesh welded = weld(mesh);
  if (welded.triangles.empty())
    throw std::invalid_argument("write_cao: mesh '" + mesh.source + "' has only degenerate triangles");

  std::vector<Polygon> faces;
  for (const std::vector<int>& group : coplanar_groups(welded)) {
    if (const std::optional<Polygon> loop = outline(welded, group)) {
      faces.push_back(drop_straight_corners(welded, *loop));
    } else {
      // One ViSP polygon cannot have holes: such a face is written as its triangles, whose
      // inner diagonals then also become model edges.
      for (const int t : group) faces.push_back({welded.triangles[t].begin(), welded.triangles[t].end()});
    }
  }

  // Only points some face uses are written, numbered in order of first use.
  std::vector<int> number(welded.points.size(), -1);
  std::vector<int> written;
  for (Polygon& face : faces)
    for (int& corner : face) {
      if (number[corner] < 0) {
        number[corner] = static_cast<int>(written.size());
        written.push_back(corner);
      }
      corner = number[corner];
    }

  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write .cao model '" + path + "'");
  out.precision(9);  // %.9g: every float coordinate reads back exactly
  out << "V1\n# 3D Points\n" << written.size() << "  # Number of points\n";
  for (const int i : written) {
    const Vec3& p = welded.points[i];
    out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  }
  out << "# 3D Lines\n0  # Number of lines\n# Faces from 3D lines\n0  # Number of faces\n";
  out << "# Faces from 3D points\n" << faces.size() << "  # Number of faces: [number of points] [point indices]...\n";
  for (const Polygon& face : faces) {
    out << face.size();
    for (const int corner : face) out << ' ' << corner;
    out << '\n';
  }
  out << "# 3D cylinders\n0  # Number of cylinders\n# 3D circles\n0  # Number of circles\n";
  out.close();
  if (!out) throw std::runtime_error("cannot write .cao model '" + path + "'");
}

}  // namespace icgp
