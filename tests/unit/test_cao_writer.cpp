// SPDX-License-Identifier: GPL-2.0-or-later
// write_cao checked against truth independent of the writer: the written file is parsed
// here, read back with ViSP's parser (load_cao_mesh) and loaded by ViSP's own tracker.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <visp3/mbt/vpMbGenericTracker.h>

#include "icgp/io/mesh_loader.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/cao_writer.h"
#include "test_meshes.h"
#include "test_temp_dir.h"

namespace fs = std::filesystem;
using Eigen::Vector3d;
using icgp::Mesh;
using icgp::test::for_each_triangle;
using icgp::test::mesh_signed_volume;
using icgp::test::mesh_surface_area;
using icgp::test::TempDir;

namespace {

const fs::path kModels = ICGP_MODELS_DIR;

/// What a "V1, faces from points only" .cao file lists, parsed here from its text.
struct CaoFile {
  std::vector<Vector3d> points;
  std::vector<std::vector<int>> faces;

  std::size_t faces_with_corners(std::size_t n) const {
    return static_cast<std::size_t>(
        std::count_if(faces.begin(), faces.end(), [&](const std::vector<int>& f) { return f.size() == n; }));
  }
};

CaoFile parse_cao(const std::string& path) {
  std::ifstream in(path);
  REQUIRE(in);
  std::stringstream tokens;  // the file without its comments
  for (std::string line; std::getline(in, line);) tokens << line.substr(0, line.find('#')) << '\n';
  std::string version;
  tokens >> version;
  REQUIRE(version == "V1");
  CaoFile cao;
  std::size_t n = 0, zero = 1;
  tokens >> n;
  cao.points.resize(n);
  for (Vector3d& p : cao.points) tokens >> p.x() >> p.y() >> p.z();
  tokens >> zero;
  CHECK(zero == 0);  // lines
  tokens >> zero;
  CHECK(zero == 0);  // faces from lines
  tokens >> n;
  cao.faces.resize(n);
  for (std::vector<int>& face : cao.faces) {
    std::size_t corners = 0;
    tokens >> corners;
    face.resize(corners);
    for (int& c : face) {
      tokens >> c;
      REQUIRE(c >= 0);
      REQUIRE(static_cast<std::size_t>(c) < cao.points.size());
    }
  }
  tokens >> zero;
  CHECK(zero == 0);  // cylinders
  tokens >> zero;
  CHECK(zero == 0);  // circles
  REQUIRE(tokens);
  std::string rest;
  CHECK(!(tokens >> rest));
  return cao;
}

/// Newell's normal of a polygon: its direction follows the winding, its length is twice the area.
Vector3d newell_normal(const CaoFile& cao, const std::vector<int>& face) {
  Vector3d n = Vector3d::Zero();
  for (std::size_t i = 0; i < face.size(); ++i)
    n += cao.points[face[i]].cross(cao.points[face[(i + 1) % face.size()]]);
  return n;
}

/// Every triangle of a convex mesh faces away from `centre`.
void check_outward(const Mesh& mesh, const Vector3d& centre) {
  int inward = 0;
  for_each_triangle(mesh, [&](const Vector3d& a, const Vector3d& b, const Vector3d& c) {
    if ((b - a).cross(c - a).dot((a + b + c) / 3.0 - centre) <= 0.0) ++inward;
  });
  CHECK(inward == 0);
}

/// The written faces of a convex object: planar, and wound counter-clockwise seen from
/// outside (Newell's normal points away from `centre`).
void check_faces_outward_and_planar(const CaoFile& cao, const Vector3d& centre) {
  for (const std::vector<int>& face : cao.faces) {
    const Vector3d n = newell_normal(cao, face);
    REQUIRE(n.norm() > 0.0);
    const Vector3d unit = n.normalized();
    for (const int c : face) CHECK(std::abs(unit.dot(cao.points[c] - cao.points[face[0]])) < 1e-7);
    CHECK(unit.dot(cao.points[face[0]] - centre) > 0.0);
  }
}

void check_points_distinct(const CaoFile& cao) {
  std::set<std::array<double, 3>> seen;
  for (const Vector3d& p : cao.points) seen.insert({p.x(), p.y(), p.z()});
  CHECK(seen.size() == cao.points.size());
}

/// Same surface: same bounds, area and signed volume.
void check_same_surface(const Mesh& original, const Mesh& read_back) {
  Eigen::Vector3f lo0, hi0, lo1, hi1;
  original.bounds(lo0, hi0);
  read_back.bounds(lo1, hi1);
  for (int i = 0; i < 3; ++i) {
    CHECK(lo1[i] == lo0[i]);  // coordinates are written with enough digits to read back exactly
    CHECK(hi1[i] == hi0[i]);
  }
  CHECK(mesh_surface_area(read_back) == Approx(mesh_surface_area(original)).epsilon(1e-9));
  CHECK(mesh_signed_volume(read_back) == Approx(mesh_signed_volume(original)).epsilon(1e-9));
}

/// ViSP's tracker loads the model; returns how many polygons it made of it.
unsigned int visp_polygon_count(const std::string& path) {
  vpMbGenericTracker tracker(vpMbGenericTracker::EDGE_TRACKER);
  tracker.loadModel(path);
  return tracker.getNbPolygon();
}

Mesh flat_mesh(const std::vector<Vector3d>& vertices, const std::vector<Eigen::Vector3i>& triangles) {
  icgp::MeshPart part;
  for (const Vector3d& v : vertices) part.vertices.push_back(v.cast<float>());
  part.triangles = triangles;
  Mesh mesh;
  mesh.source = "flat";
  mesh.parts.push_back(part);
  return mesh;
}

}  // namespace

TEST_CASE("textured box: 8 points, 6 quads, the same outward surface") {
  TempDir dir("icgp-cao-writer");
  const Mesh box = icgp::load_mesh((kModels / "textured_box" / "textured_box.obj").string());
  REQUIRE(box.triangle_count() == 12);
  CHECK(mesh_signed_volume(box) == Approx(0.08 * 0.16 * 0.06).epsilon(1e-6));
  check_outward(box, Vector3d::Zero());

  const std::string path = dir.file("box.cao");
  icgp::write_cao(box, path);
  const CaoFile cao = parse_cao(path);
  CHECK(cao.points.size() == 8);  // the loader's 24 vertices (4 per face) are welded
  CHECK(cao.faces.size() == 6);
  CHECK(cao.faces_with_corners(4) == 6);
  check_points_distinct(cao);
  for (const Vector3d& p : cao.points) CHECK(p.cwiseAbs().isApprox(Vector3d(0.04, 0.08, 0.03), 1e-7));
  check_faces_outward_and_planar(cao, Vector3d::Zero());

  const Mesh read_back = icgp::load_cao_mesh(path);
  check_same_surface(box, read_back);
  CHECK(mesh_surface_area(read_back) == Approx(2 * (0.08 * 0.16 + 0.16 * 0.06 + 0.08 * 0.06)).epsilon(1e-6));
  check_outward(read_back, Vector3d::Zero());

  CHECK(visp_polygon_count(path) == 6);
}

TEST_CASE("two-region box: the two parts' split sides become one quad each") {
  TempDir dir("icgp-cao-writer");
  const Mesh object = icgp::load_mesh((kModels / "two_region" / "object.obj").string());
  REQUIRE(object.parts.size() == 2);
  const std::string path = dir.file("two_region.cao");
  icgp::write_cao(object, path);

  // The side vertices at y = 0.015 where body and lid meet lie on straight edges: dropped.
  const CaoFile cao = parse_cao(path);
  CHECK(cao.points.size() == 8);
  CHECK(cao.faces.size() == 6);
  CHECK(cao.faces_with_corners(4) == 6);
  check_points_distinct(cao);
  check_faces_outward_and_planar(cao, Vector3d::Zero());

  const Mesh read_back = icgp::load_cao_mesh(path);
  check_same_surface(object, read_back);
  CHECK(mesh_signed_volume(read_back) == Approx(0.10 * 0.08 * 0.06).epsilon(1e-6));
  check_outward(read_back, Vector3d::Zero());
  CHECK(visp_polygon_count(path) == 6);
}

TEST_CASE("labelled cylinder: 64 side quads and one 64-corner polygon per cap") {
  TempDir dir("icgp-cao-writer");
  const Mesh cylinder = icgp::load_mesh((kModels / "labelled_cylinder" / "labelled_cylinder.obj").string());
  REQUIRE(cylinder.triangle_count() == 256);  // 64 segments: 2 triangles per side facet, fans of 64 per cap
  const std::string path = dir.file("cylinder.cao");
  icgp::write_cao(cylinder, path);

  const CaoFile cao = parse_cao(path);
  CHECK(cao.points.size() == 128);  // two rings; the fans' centres are no corner of any face
  CHECK(cao.faces.size() == 66);
  CHECK(cao.faces_with_corners(4) == 64);
  CHECK(cao.faces_with_corners(64) == 2);
  check_points_distinct(cao);
  check_faces_outward_and_planar(cao, Vector3d::Zero());

  const Mesh read_back = icgp::load_cao_mesh(path);
  check_same_surface(cylinder, read_back);
  check_outward(read_back, Vector3d::Zero());
  CHECK(visp_polygon_count(path) == 66);
}

TEST_CASE("a non-convex flat face becomes one polygon without its straight-edge vertices") {
  // An L-shaped plate in z = 0 facing +z, made of three 0.01 m squares (0,0)-(2,1) and (0,1)-(1,2).
  TempDir dir("icgp-cao-writer");
  const double s = 0.01;
  const std::vector<Vector3d> v{{0, 0, 0}, {s, 0, 0}, {2 * s, 0, 0}, {0, s, 0},
                                {s, s, 0}, {2 * s, s, 0}, {0, 2 * s, 0}, {s, 2 * s, 0}};
  const Mesh plate = flat_mesh(v, {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}, {3, 4, 7}, {3, 7, 6}});
  const std::string path = dir.file("plate.cao");
  icgp::write_cao(plate, path);

  const CaoFile cao = parse_cao(path);
  REQUIRE(cao.faces.size() == 1);
  CHECK(cao.faces[0].size() == 6);  // (1,0,0) and (0,1,0) are dropped, the reflex corner (1,1,0) kept
  CHECK(cao.points.size() == 6);
  CHECK(newell_normal(cao, cao.faces[0]).normalized().isApprox(Vector3d::UnitZ(), 1e-9));
  CHECK(newell_normal(cao, cao.faces[0]).norm() / 2 == Approx(3 * s * s).epsilon(1e-6));

  const Mesh read_back = icgp::load_cao_mesh(path);
  CHECK(mesh_surface_area(read_back) == Approx(mesh_surface_area(plate)).epsilon(1e-9));
  CHECK(visp_polygon_count(path) == 1);
}

TEST_CASE("a flat face with a hole is written as its triangles") {
  // A square ring in z = 0 facing +z: outer half-size 0.02 m, inner 0.01 m, 8 triangles.
  TempDir dir("icgp-cao-writer");
  const double a = 0.02, b = 0.01;
  const std::vector<Vector3d> v{{-a, -a, 0}, {a, -a, 0}, {a, a, 0}, {-a, a, 0},
                                {-b, -b, 0}, {b, -b, 0}, {b, b, 0}, {-b, b, 0}};
  std::vector<Eigen::Vector3i> triangles;
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    triangles.emplace_back(i, j, 4 + j);
    triangles.emplace_back(i, 4 + j, 4 + i);
  }
  const Mesh ring = flat_mesh(v, triangles);
  REQUIRE(mesh_surface_area(ring) == Approx(4 * a * a - 4 * b * b));
  const std::string path = dir.file("ring.cao");
  icgp::write_cao(ring, path);

  const CaoFile cao = parse_cao(path);
  CHECK(cao.points.size() == 8);
  CHECK(cao.faces.size() == 8);
  CHECK(cao.faces_with_corners(3) == 8);
  for (const auto& face : cao.faces) CHECK(newell_normal(cao, face).normalized().isApprox(Vector3d::UnitZ(), 1e-9));

  const Mesh read_back = icgp::load_cao_mesh(path);
  CHECK(mesh_surface_area(read_back) == Approx(mesh_surface_area(ring)).epsilon(1e-9));
  CHECK(visp_polygon_count(path) == 8);
}

TEST_CASE("write_cao refuses an empty mesh and names a path it cannot write") {
  TempDir dir("icgp-cao-writer");
  CHECK_THROWS_AS(icgp::write_cao(Mesh(), dir.file("empty.cao")), std::invalid_argument);
  CHECK(!fs::exists(dir.file("empty.cao")));

  const Mesh box = icgp::load_mesh((kModels / "textured_box" / "textured_box.obj").string());
  // Not dir.file(), which would create the folder.
  const std::string unwritable = (dir.path() / "no-such-directory" / "box.cao").string();
  try {
    icgp::write_cao(box, unwritable);
    FAIL("no exception for an unwritable path");
  } catch (const std::runtime_error& e) {
    CHECK_THAT(e.what(), Catch::Matchers::Contains(unwritable));
  }
}
