// SPDX-License-Identifier: GPL-2.0-or-later
#include "cao_mesh_builder.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <visp3/core/vpException.h>
#include <visp3/core/vpPoint.h>
#include <visp3/mbt/vpMbtPolygon.h>

#include "icgp/base/standard_stream_capture.h"
#include "icgp/io/cao_file_check.h"

namespace icgp {
namespace {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

/// Twice the signed area of the triangle abc: positive when it turns counter-clockwise.
double signed_area2(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 ab = b - a;
  const Vec2 ac = c - a;
  return ab.x() * ac.y() - ab.y() * ac.x();
}

/// Triangulates a simple counter-clockwise polygon by ear clipping. Returns counter-
/// clockwise index triples. Corners turning by less than `tolerance` (twice an area) count
/// as straight and are dropped, as they bound no area. Throws std::invalid_argument when
/// no ear is left, which only happens to self-intersecting polygons.
std::vector<Eigen::Vector3i> ear_clip(const std::vector<Vec2>& points, double tolerance) {
  std::vector<int> remaining(points.size());
  std::iota(remaining.begin(), remaining.end(), 0);
  std::vector<Eigen::Vector3i> triangles;

  // An ear's triangle must not contain, even on its border, any other remaining corner:
  // that corner would be cut off or its edge crossed.
  const auto is_ear = [&](int a, int b, int c) {
    for (const int p : remaining) {
      if (p == a || p == b || p == c) continue;
      const Vec2& q = points[p];
      if (signed_area2(points[a], points[b], q) >= -tolerance && signed_area2(points[b], points[c], q) >= -tolerance &&
          signed_area2(points[c], points[a], q) >= -tolerance)
        return false;
    }
    return true;
  };

  // Walk round the polygon clipping as we go; after a clip, re-test the previous corner,
  // whose neighbour changed. A full lap without a clip means there is no ear.
  std::size_t i = 0, corners_without_clip = 0;
  while (remaining.size() >= 3) {
    const std::size_t n = remaining.size();
    if (corners_without_clip >= n)
      throw std::invalid_argument("the polygon intersects itself, so it cannot be triangulated");
    i %= n;
    const int a = remaining[(i + n - 1) % n];
    const int b = remaining[i];
    const int c = remaining[(i + 1) % n];
    const double turn = signed_area2(points[a], points[b], points[c]);
    const bool straight = std::abs(turn) <= tolerance;
    if (!straight && (turn < 0.0 || !is_ear(a, b, c))) {
      ++i;
      ++corners_without_clip;
      continue;
    }
    if (!straight) triangles.emplace_back(a, b, c);
    remaining.erase(remaining.begin() + static_cast<std::ptrdiff_t>(i));
    i = (i + n - 2) % (n - 1);
    corners_without_clip = 0;
  }
  return triangles;
}

/// Appends the triangulated primitives of a .cao model to one MeshPart, keeping outward
/// (ViSP) orientation: faces keep their winding, cylinders face away from their axis.
class PartBuilder {
 public:
  explicit PartBuilder(MeshPart& part) : part_(part) {}

  void add_polygon(std::vector<Vec3> corners) {
    drop_repeated_corners(corners);
    if (corners.size() < 3) return;  // a 3D line: no surface

    // Relative to the first corner, so that models far from their origin keep precision.
    std::vector<Vec3> local;
    double extent = 0.0;
    for (const Vec3& p : corners) {
      local.push_back(p - corners.front());
      extent = std::max(extent, local.back().norm());
    }
    // Newell's normal: right for non-convex polygons too, and its length is twice the area.
    Vec3 normal = Vec3::Zero();
    for (std::size_t i = 0; i < local.size(); ++i) normal += local[i].cross(local[(i + 1) % local.size()]);
    const double tolerance = 1e-10 * extent * extent;
    if (normal.norm() <= tolerance) return;  // all corners on one line: no area

    // Plane axes with u x v = normal, so that the polygon is counter-clockwise in (u, v).
    const Vec3 w = normal.normalized();
    const Vec3 u = w.unitOrthogonal();
    const Vec3 v = w.cross(u);
    std::vector<Vec2> in_plane;
    in_plane.reserve(corners.size());
    for (const Vec3& p : local) in_plane.emplace_back(p.dot(u), p.dot(v));

    const std::vector<Eigen::Vector3i> triangles = ear_clip(in_plane, tolerance);
    const int base = add_vertices(corners);
    for (const Eigen::Vector3i& t : triangles) part_.triangles.push_back(t + Eigen::Vector3i::Constant(base));
  }

  /// Open lateral surface of the cylinder of the given radius around the segment p1-p2.
  void add_cylinder(const Vec3& p1, const Vec3& p2, double radius, int segments) {
    require_positive_radius(radius);
    const Vec3 w = (p2 - p1).normalized();  // ViSP itself drops cylinders whose axis points coincide
    const Vec3 u = w.unitOrthogonal();
    const Vec3 v = w.cross(u);  // (u, v, w) right-handed: triangles below face outwards

    std::vector<Vec3> rings;  // bottom and top vertex of each segment, interleaved
    for (int i = 0; i < segments; ++i) {
      const double angle = 2.0 * kPi * i / segments;
      const Vec3 offset = radius * (std::cos(angle) * u + std::sin(angle) * v);
      rings.push_back(p1 + offset);
      rings.push_back(p2 + offset);
    }
    const int base = add_vertices(rings);
    for (int i = 0; i < segments; ++i) {
      const int j = (i + 1) % segments;
      const int bottom_i = base + 2 * i, top_i = bottom_i + 1;
      const int bottom_j = base + 2 * j, top_j = bottom_j + 1;
      part_.triangles.emplace_back(bottom_i, bottom_j, top_j);
      part_.triangles.emplace_back(bottom_i, top_j, top_i);
    }
  }

  /// Disc of the given radius around `centre` in the plane through centre, p2 and p3,
  /// facing along (p2 - centre) x (p3 - centre): ViSP's circle convention.
  void add_disc(const Vec3& centre, const Vec3& p2, const Vec3& p3, double radius, int segments) {
    require_positive_radius(radius);
    const Vec3 normal = (p2 - centre).cross(p3 - centre);
    if (normal.norm() <= 1e-12 * (p2 - centre).norm() * (p3 - centre).norm())
      throw std::invalid_argument("its centre and two plane points are collinear, so they define no plane");
    const Vec3 w = normal.normalized();
    const Vec3 u = (p2 - centre).normalized();
    const Vec3 v = w.cross(u);

    std::vector<Vec3> fan{centre};
    for (int i = 0; i < segments; ++i) {
      const double angle = 2.0 * kPi * i / segments;
      fan.push_back(centre + radius * (std::cos(angle) * u + std::sin(angle) * v));
    }
    const int base = add_vertices(fan);
    for (int i = 0; i < segments; ++i) part_.triangles.emplace_back(base, base + 1 + i, base + 1 + (i + 1) % segments);
  }

 private:
  /// Faces from lines come back closed (first corner repeated at the end); repeated
  /// corners would also make zero-length edges that ear clipping cannot order.
  static void drop_repeated_corners(std::vector<Vec3>& corners) {
    double extent = 0.0;
    for (const Vec3& p : corners) extent = std::max(extent, (p - corners.front()).norm());
    const auto same = [&](const Vec3& a, const Vec3& b) { return (a - b).norm() <= 1e-9 * extent; };
    corners.erase(std::unique(corners.begin(), corners.end(), same), corners.end());
    while (corners.size() > 1 && same(corners.front(), corners.back())) corners.pop_back();
  }

  static void require_positive_radius(double radius) {
    if (!(radius > 0.0) || !std::isfinite(radius))
      throw std::invalid_argument("its radius must be positive (got " + std::to_string(radius) + ")");
  }

  int add_vertices(const std::vector<Vec3>& points) {
    const int base = static_cast<int>(part_.vertices.size());
    for (const Vec3& p : points) part_.vertices.push_back(p.cast<float>());
    return base;
  }

  MeshPart& part_;
};

/// ViSP's multi-line diagnostics as one parenthesised clause, or nothing.
std::string as_clause(const std::string& diagnostics) {
  std::istringstream lines(diagnostics);
  std::string line, joined;
  while (std::getline(lines, line)) {
    line.erase(line.find_last_not_of(" \t\r") + 1);
    if (!line.empty()) joined += (joined.empty() ? "" : "; ") + line;
  }
  return joined.empty() ? "" : " (" + joined + ")";
}

}  // namespace

CaoMeshBuilder::CaoMeshBuilder(std::string path, const CaoTessellation& tessellation, const Pose& undo)
    : path_(std::move(path)), tessellation_(tessellation), undo_(undo) {
  mesh_.source = path_;
  mesh_.parts.emplace_back();
}

Eigen::Vector3d CaoMeshBuilder::meshed(const vpPoint& p) const {
  // R^T (P - t), exactly P for the identity.
  return undo_.rotation().transpose() * (Vec3(p.get_oX(), p.get_oY(), p.get_oZ()) - undo_.translation());
}

template <typename Add>
void CaoMeshBuilder::collect(const std::string& kind, int ordinal, const std::string& name, Add&& add) {
  try {
    PartBuilder part(mesh_.parts.front());
    add(part);
  } catch (const std::exception& e) {
    if (first_error_.empty())
      first_error_ = kind + " #" + std::to_string(ordinal) + (name.empty() ? "" : " '" + name + "'") + ": " + e.what();
  }
}

void CaoMeshBuilder::add_face(vpMbtPolygon& polygon) {
  std::vector<Vec3> corners;
  for (unsigned int i = 0; i < polygon.getNbPoint(); ++i) corners.push_back(meshed(polygon.getPoint(i)));
  collect("face", ++faces_, polygon.getName(), [&](PartBuilder& part) { part.add_polygon(std::move(corners)); });
}

void CaoMeshBuilder::add_cylinder(const vpPoint& p1, const vpPoint& p2, double radius, const std::string& name) {
  collect("cylinder", ++cylinders_, name, [&](PartBuilder& part) {
    part.add_cylinder(meshed(p1), meshed(p2), radius, tessellation_.cylinder_segments);
  });
}

void CaoMeshBuilder::add_circle(const vpPoint& p1, const vpPoint& p2, const vpPoint& p3, double radius,
                                const std::string& name) {
  collect("circle", ++circles_, name, [&](PartBuilder& part) {
    part.add_disc(meshed(p1), meshed(p2), meshed(p3), radius, tessellation_.circle_segments);
  });
}

namespace {

/// Checks a .cao file before ViSP's parser reads it (that parser does not check indices
/// or empty faces, and reaches memory it does not own), and its triangles against the mesh
/// budget before any is made.
void check_before_parse(const std::string& path, const CaoTessellation& tessellation) {
  const CaoFileSummary cao = check_cao_file(path);
  const std::size_t triangles = cao.face_corners + cao.cylinders * 2 * std::size_t(tessellation.cylinder_segments) +
                                cao.circles * std::size_t(tessellation.circle_segments);
  if (triangles > MeshLimits::kMaxTriangles)
    throw std::invalid_argument(path + ": would make up to " + std::to_string(triangles) + " triangles (expected at most " +
                                std::to_string(MeshLimits::kMaxTriangles) + ")");
}

}  // namespace

Mesh CaoMeshBuilder::build(const std::function<void()>& parse) {
  if (is_cao_path(path_)) {
    try {
      check_before_parse(path_, tessellation_);
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error("cannot load ViSP model '" + path_ + "': " + e.what());
    }
  }
  std::string visp_error, diagnostics;
  {
    // When ViSP's parser fails it prints the reason on std::cerr and throws only "cannot read line".
    const StandardStreamCapture capture(std::cerr);
    try {
      parse();
    } catch (const vpException& e) {
      visp_error = e.getStringMessage();
    }
    diagnostics = capture.text();
  }
  // ViSP's diagnostics go into every error: it also drops primitives it finds broken (e.g.
  // a cylinder whose axis points coincide) with only a warning, which explains an empty mesh.
  std::string problem;
  if (!visp_error.empty())
    problem = visp_error;
  else if (!first_error_.empty())
    problem = first_error_;
  else if (mesh_.empty())
    problem = "it describes no surface (no faces, cylinders or circles)";
  if (!problem.empty())
    throw std::runtime_error("cannot load ViSP model '" + path_ + "': " + problem + as_clause(diagnostics));

  std::cerr << diagnostics;  // warnings of a successful parse stay visible
  check_mesh(mesh_);
  return std::move(mesh_);
}

}  // namespace icgp
