// SPDX-License-Identifier: GPL-2.0-or-later
// .cao models meshed through ViSP's parser, checked against truth computed here from the
// numbers in the files (never from the code under test).
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <sstream>

#include "icgp/visp/cao_mesh_loader.h"
#include "test_meshes.h"
#include "test_temp_dir.h"

namespace fs = std::filesystem;
using Eigen::Vector3d;
using icgp::kPi;
using icgp::Mesh;
using icgp::Pose;
using icgp::test::for_each_triangle;
using icgp::test::mesh_signed_volume;
using icgp::test::mesh_surface_area;
using icgp::test::TempDir;

namespace {

const fs::path kData = ICGP_TEST_DATA_DIR;
const fs::path kModels = kData / "realsense-cube" / "models";

double box_area(double x, double y, double z) { return 2.0 * (x * y + y * z + x * z); }

void check_bounds(const Mesh& mesh, const Vector3d& expected_min, const Vector3d& expected_max, double tolerance) {
  Eigen::Vector3f lo, hi;
  mesh.bounds(lo, hi);
  for (int i = 0; i < 3; ++i) {
    CHECK(lo[i] == Approx(expected_min[i]).margin(tolerance));
    CHECK(hi[i] == Approx(expected_max[i]).margin(tolerance));
  }
}

/// Bounds of a point set, for expected values.
void bounds_of(const std::vector<Vector3d>& points, Vector3d& lo, Vector3d& hi) {
  lo = hi = points.front();
  for (const Vector3d& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
}

std::vector<Vector3d> box_corners(const Vector3d& lo, const Vector3d& hi) {
  std::vector<Vector3d> corners;
  for (int i = 0; i < 8; ++i)
    corners.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  return corners;
}

std::vector<Vector3d> transformed(const std::vector<Vector3d>& points, const Eigen::Matrix3d& R, const Vector3d& t) {
  std::vector<Vector3d> out;
  for (const Vector3d& p : points) out.push_back(R * p + t);
  return out;
}

Eigen::Matrix3d rotation_about(const Vector3d& theta_u) {
  return theta_u.norm() == 0.0 ? Eigen::Matrix3d::Identity()
                               : Eigen::AngleAxisd(theta_u.norm(), theta_u.normalized()).toRotationMatrix();
}

/// Every mesh vertex is one of the expected points, and every expected point is used.
void check_vertices_are(const Mesh& mesh, const std::vector<Vector3d>& expected, double tolerance) {
  std::vector<bool> used(expected.size(), false);
  for (const Eigen::Vector3f& v : mesh.all_vertices()) {
    bool found = false;
    for (std::size_t i = 0; i < expected.size(); ++i)
      if ((v.cast<double>() - expected[i]).norm() < tolerance) found = used[i] = true;
    CHECK(found);
  }
  for (std::size_t i = 0; i < expected.size(); ++i) CHECK(used[i]);
}

/// The .cao text of points, lines, faces from lines, faces from points, cylinders and
/// circles (each list already formatted, one entry per line).
std::string cao(const std::vector<Vector3d>& points, const std::vector<std::string>& lines = {},
                const std::vector<std::string>& faces_from_lines = {},
                const std::vector<std::string>& faces_from_points = {}, const std::vector<std::string>& cylinders = {},
                const std::vector<std::string>& circles = {}, const std::string& includes = "") {
  std::ostringstream out;
  out << std::setprecision(17) << "V1\n" << includes << "# 3D points\n" << points.size() << "\n";
  for (const Vector3d& p : points) out << p.x() << " " << p.y() << " " << p.z() << "\n";
  for (const auto* section : {&lines, &faces_from_lines, &faces_from_points, &cylinders, &circles}) {
    out << "# section\n" << section->size() << "\n";
    for (const std::string& entry : *section) out << entry << "\n";
  }
  return out.str();
}

std::string number(double value) {
  std::ostringstream out;
  out << std::setprecision(17) << value;
  return out.str();
}

/// Shoelace area of a 2D polygon.
double polygon_area(const std::vector<Eigen::Vector2d>& points) {
  double twice = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d& a = points[i];
    const Eigen::Vector2d& b = points[(i + 1) % points.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * std::abs(twice);
}

std::string face_of_all(std::size_t count) {
  std::string face = std::to_string(count);
  for (std::size_t i = 0; i < count; ++i) face += " " + std::to_string(i);
  return face;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no std::runtime_error";
}

}  // namespace

TEST_CASE("every .cao model in the test data loads into a non-empty finite mesh") {
  int models = 0;
  for (const auto& entry : fs::recursive_directory_iterator(kData)) {
    if (entry.path().extension() != ".cao") continue;
    ++models;
    INFO(entry.path());
    const Mesh mesh = icgp::load_cao_mesh(entry.path().string());
    CHECK(mesh.source == entry.path().string());
    REQUIRE(mesh.parts.size() == 1);
    CHECK(mesh.triangle_count() > 0);
    for (const Eigen::Vector3f& v : mesh.all_vertices()) CHECK(v.allFinite());
  }
  CHECK(models >= 5);  // at least teabox-blender, cube, teabox, lego-square and its brick
}

TEST_CASE("cube.cao: a 0.042 m cube with outward faces") {
  const Mesh mesh = icgp::load_cao_mesh((kModels / "cube" / "cube.cao").string());
  const double side = 0.042;
  CHECK(mesh.triangle_count() == 12);
  CHECK(mesh_surface_area(mesh) == Approx(6 * side * side).epsilon(1e-6));
  CHECK(mesh_signed_volume(mesh) == Approx(side * side * side).epsilon(1e-6));
  check_bounds(mesh, {-side, 0, 0}, {0, side, side}, 1e-7);
}

TEST_CASE("realsense teabox.cao: a 0.165 x 0.068 x 0.08 m box") {
  const Mesh mesh = icgp::load_cao_mesh((kModels / "teabox" / "teabox.cao").string());
  CHECK(mesh.triangle_count() == 12);
  CHECK(mesh_surface_area(mesh) == Approx(box_area(0.165, 0.068, 0.08)).epsilon(1e-6));
  CHECK(mesh_signed_volume(mesh) == Approx(0.165 * 0.068 * 0.08).epsilon(1e-6));
  check_bounds(mesh, {0, 0, -0.08}, {0.165, 0.068, 0}, 1e-7);
}

TEST_CASE("realsense teabox.wrl: ViSP's VRML path (Coin3D) gives the box its .cao describes") {
  const fs::path folder = kData / "realsense-cube" / "models" / "teabox";
  const Mesh wrl = icgp::load_cao_mesh((folder / "teabox.wrl").string());
  const Mesh cao = icgp::load_cao_mesh((folder / "teabox.cao").string());
  CHECK(wrl.triangle_count() == 12);
  CHECK(mesh_surface_area(wrl) == Approx(box_area(0.165, 0.068, 0.08)).epsilon(1e-6));
  CHECK(std::abs(mesh_signed_volume(wrl)) == Approx(0.165 * 0.068 * 0.08).epsilon(1e-6));
  check_bounds(wrl, {0, 0, -0.08}, {0.165, 0.068, 0}, 1e-7);
  CHECK(mesh_signed_volume(wrl) == Approx(mesh_signed_volume(cao)).epsilon(1e-6));  // same winding

  // The model transform applies to VRML as to .cao, and load_any_mesh dispatches to ViSP.
  const Pose T = Pose::from_rotation_vector({0, 0, 0}, {0.1, 0.2, 0.3});
  check_bounds(icgp::load_cao_mesh((folder / "teabox.wrl").string(), T), {0.1, 0.2, 0.22}, {0.265, 0.268, 0.3}, 1e-6);
  check_bounds(icgp::load_any_mesh((folder / "teabox.wrl").string(), 1.0, T), {0.1, 0.2, 0.22}, {0.265, 0.268, 0.3},
               1e-6);
}

TEST_CASE("teabox-blender teabox.cao: a slanted prism with the file's dimensions") {
  const Mesh mesh = icgp::load_cao_mesh((kData / "teabox-blender" / "teabox.cao").string());
  // The file's 8 points and its 6 quads.
  const std::vector<Vector3d> p = {{0.031598, -0.04, 0.001594},   {0.034, 0.037166, 0.001594},
                                   {0.034, 0.037166, 0.166594},   {0.031598, -0.04, 0.166594},
                                   {-0.034, -0.037166, 0.166594}, {-0.031598, 0.04, 0.166594},
                                   {-0.031598, 0.04, 0.001594},   {-0.034, -0.037166, 0.001594}};
  const std::vector<std::array<int, 4>> quads = {{0, 1, 2, 3}, {1, 6, 5, 2}, {4, 5, 6, 7},
                                                 {0, 3, 4, 7}, {5, 4, 3, 2}, {0, 7, 6, 1}};
  double area = 0.0;  // a planar quad's area is half the cross product of its diagonals
  for (const auto& q : quads) area += 0.5 * (p[q[2]] - p[q[0]]).cross(p[q[3]] - p[q[1]]).norm();
  const double height = 0.166594 - 0.001594;
  const double base_area = polygon_area({{0.031598, -0.04}, {0.034, 0.037166}, {-0.031598, 0.04}, {-0.034, -0.037166}});

  CHECK(mesh.triangle_count() == 12);
  CHECK(mesh_surface_area(mesh) == Approx(area).epsilon(1e-6));
  CHECK(mesh_signed_volume(mesh) == Approx(base_area * height).epsilon(1e-6));
  Vector3d lo, hi;
  bounds_of(p, lo, hi);
  check_bounds(mesh, lo, hi, 1e-7);
}

TEST_CASE("lego-square.cao: four bricks placed by the load() transforms") {
  const double x = 0.032, y = 0.016, z = 0.0096;
  const Mesh brick = icgp::load_cao_mesh((kModels / "lego-square" / "lego_parts" / "brick-2x4.cao").string());
  CHECK(brick.triangle_count() == 12);
  CHECK(mesh_surface_area(brick) == Approx(box_area(x, y, z)).epsilon(1e-6));
  CHECK(mesh_signed_volume(brick) == Approx(x * y * z).epsilon(1e-6));
  check_bounds(brick, {0, 0, 0}, {x, y, z}, 1e-7);

  // The load() lines of lego-square.cao: X' = R(tu) X + t.
  const std::vector<Vector3d> corners = box_corners({0, 0, 0}, {x, y, z});
  std::vector<Vector3d> placed;
  for (const auto& [t, tu] : std::vector<std::pair<Vector3d, Vector3d>>{{{0, 0, 0}, {0, 0, 0}},
                                                                        {{0.048, 0, 0}, {0, 0, kPi / 2}},
                                                                        {{0.016, 0.032, 0}, {0, 0, 0}},
                                                                        {{0.016, 0.016, 0}, {0, 0, 1.57}}}) {
    const std::vector<Vector3d> one = transformed(corners, rotation_about(tu), t);
    placed.insert(placed.end(), one.begin(), one.end());
  }

  const std::string square_path = (kModels / "lego-square" / "lego-square.cao").string();
  const Mesh square = icgp::load_cao_mesh(square_path);
  CHECK(square.triangle_count() == 4 * brick.triangle_count());
  CHECK(mesh_surface_area(square) == Approx(4 * mesh_surface_area(brick)).epsilon(1e-6));
  CHECK(mesh_signed_volume(square) == Approx(4 * x * y * z).epsilon(1e-5));
  check_vertices_are(square, placed, 1e-6);
  Vector3d lo, hi;
  bounds_of(placed, lo, hi);
  check_bounds(square, lo, hi, 1e-6);

  SECTION("with a model transform T on top") {
    const Vector3d theta_u(0.2, -0.5, 0.9), t(0.1, -0.2, 0.3);
    const Mesh moved = icgp::load_cao_mesh(square_path, Pose::from_rotation_vector(theta_u, t));
    const std::vector<Vector3d> expected = transformed(placed, rotation_about(theta_u), t);
    check_vertices_are(moved, expected, 1e-6);
    bounds_of(expected, lo, hi);
    check_bounds(moved, lo, hi, 1e-6);
  }
}

TEST_CASE("a T transform moves the cube's bounds") {
  const Pose T = Pose::from_rotation_vector({0, 0, kPi / 2}, {0.1, 0.2, 0.3});
  const Mesh mesh = icgp::load_cao_mesh((kModels / "cube" / "cube.cao").string(), T);
  // Rotating by 90 degrees about z maps (x, y, z) to (-y, x, z).
  check_bounds(mesh, {0.1 - 0.042, 0.2 - 0.042, 0.3}, {0.1, 0.2, 0.3 + 0.042}, 1e-6);
  CHECK(mesh_signed_volume(mesh) == Approx(0.042 * 0.042 * 0.042).epsilon(1e-5));
}

TEST_CASE("a cylinder becomes its open lateral surface") {
  TempDir dir("icgp-cao");
  const Vector3d p1(0.1, -0.2, 0.3), p2(0.15, -0.08, 0.5);
  const double radius = 0.04, height = (p2 - p1).norm();
  const std::string path = dir.write("cylinder.cao", cao({p1, p2}, {}, {}, {}, {"0 1 " + number(radius)}));
  const Mesh mesh = icgp::load_cao_mesh(path);

  CHECK(mesh.triangle_count() == 2 * 48);
  CHECK(mesh_surface_area(mesh) == Approx(2 * kPi * radius * height).epsilon(0.01));
  const Vector3d axis = (p2 - p1).normalized();
  for (const Eigen::Vector3f& v : mesh.all_vertices()) {
    const Vector3d d = v.cast<double>() - p1;
    const double along = d.dot(axis);
    CHECK((d - along * axis).norm() == Approx(radius).margin(1e-6));
    CHECK((std::abs(along) < 1e-6 || std::abs(along - height) < 1e-6));
  }
  for_each_triangle(mesh, [&](const Vector3d& a, const Vector3d& b, const Vector3d& c) {
    const Vector3d centroid = (a + b + c) / 3.0 - p1;
    const Vector3d outwards = centroid - centroid.dot(axis) * axis;
    CHECK((b - a).cross(c - a).dot(outwards) > 0.0);
  });

  const Mesh coarse = icgp::load_cao_mesh(path, Pose(), icgp::CaoTessellation{8, 48});
  CHECK(coarse.triangle_count() == 16);
}

TEST_CASE("a circle becomes a disc in the plane of its three points") {
  TempDir dir("icgp-cao");
  const Vector3d centre(0.2, 0.1, -0.05), p2 = centre + Vector3d(0.03, 0.01, 0.02),
                                          p3 = centre + Vector3d(-0.01, 0.04, 0.01);
  const double radius = 0.06;
  const std::string path = dir.write("circle.cao", cao({centre, p2, p3}, {}, {}, {}, {}, {number(radius) + " 0 1 2"}));
  const Mesh mesh = icgp::load_cao_mesh(path);

  CHECK(mesh.triangle_count() == 48);
  CHECK(mesh_surface_area(mesh) == Approx(kPi * radius * radius).epsilon(0.01));
  const Vector3d normal = (p2 - centre).cross(p3 - centre).normalized();
  for (const Eigen::Vector3f& v : mesh.all_vertices()) {
    CHECK(std::abs((v.cast<double>() - centre).dot(normal)) < 1e-6);
    CHECK((v.cast<double>() - centre).norm() < radius + 1e-6);
  }
  for_each_triangle(mesh, [&](const Vector3d& a, const Vector3d& b, const Vector3d& c) {
    CHECK((b - a).cross(c - a).dot(normal) > 0.0);  // faces along (p2 - p1) x (p3 - p1)
  });
}

TEST_CASE("non-convex faces are ear-clipped exactly") {
  TempDir dir("icgp-cao");
  SECTION("an L listed from a corner that does not see the whole face") {
    const double z = 0.01;
    const std::vector<Vector3d> L = {{0.2, 0, z}, {0.2, 0.1, z}, {0.1, 0.1, z}, {0.1, 0.2, z}, {0, 0.2, z}, {0, 0, z}};
    const Mesh mesh = icgp::load_cao_mesh(dir.write("L.cao", cao(L, {}, {}, {face_of_all(L.size())})));
    CHECK(mesh.triangle_count() == 4);
    CHECK(mesh_surface_area(mesh) == Approx(0.03).epsilon(1e-6));
    for_each_triangle(mesh, [&](const Vector3d& a, const Vector3d& b, const Vector3d& c) {
      CHECK((b - a).cross(c - a).z() > 0.0);  // the file's counter-clockwise winding kept
      const Vector3d centroid = (a + b + c) / 3.0;
      CHECK_FALSE((centroid.x() > 0.1 && centroid.y() > 0.1));  // nothing in the L's notch
    });
  }
  SECTION("a comb in a tilted plane, with a straight corner") {
    const std::vector<Eigen::Vector2d> comb = {{0, 0},     {0.25, 0},  {0.5, 0},   {0.5, 0.3}, {0.4, 0.3},
                                               {0.4, 0.1}, {0.3, 0.1}, {0.3, 0.3}, {0.2, 0.3}, {0.2, 0.1},
                                               {0.1, 0.1}, {0.1, 0.3}, {0, 0.3}};
    const Eigen::Matrix3d R = rotation_about({0.4, -0.7, 0.2});
    const Vector3d offset(0.05, 0.1, -0.2);
    std::vector<Vector3d> points;
    for (const Eigen::Vector2d& q : comb) points.push_back(R * Vector3d(q.x(), q.y(), 0) + offset);
    const Mesh mesh = icgp::load_cao_mesh(dir.write("comb.cao", cao(points, {}, {}, {face_of_all(points.size())})));
    CHECK(mesh.triangle_count() == comb.size() - 3);  // the straight corner adds no triangle
    CHECK(mesh_surface_area(mesh) == Approx(polygon_area(comb)).epsilon(1e-6));
    const Vector3d normal = R.col(2);
    for_each_triangle(mesh, [&](const Vector3d& a, const Vector3d& b, const Vector3d& c) {
      CHECK((b - a).cross(c - a).dot(normal) > 0.0);
    });
  }
}

TEST_CASE("faces from lines are meshed, lone lines are not") {
  TempDir dir("icgp-cao");
  const std::vector<Vector3d> points = {{0, 0, 0}, {0.1, 0, 0}, {0.1, 0.1, 0}, {0, 0.1, 0}, {0, 0, 0.5}, {0, 0, 0.7}};
  const std::string path = dir.write("lines.cao", cao(points, {"0 1", "1 2", "2 3", "3 0", "4 5"}, {"4 0 1 2 3"}));
  const Mesh mesh = icgp::load_cao_mesh(path);
  CHECK(mesh.triangle_count() == 2);
  CHECK(mesh_surface_area(mesh) == Approx(0.01).epsilon(1e-6));
  check_bounds(mesh, {0, 0, 0}, {0.1, 0.1, 0}, 1e-7);

  const std::string lines_only = dir.write("lines-only.cao", cao(points, {"4 5"}));
  CHECK_THAT(error_of([&] { icgp::load_cao_mesh(lines_only); }),
             Catch::Contains(lines_only) && Catch::Contains("no faces"));
}

TEST_CASE("load() includes apply their transform, and T applies on top") {
  TempDir dir("icgp-cao");
  const Vector3d lo(0.01, 0.02, 0.03), hi(0.05, 0.04, 0.09);
  const std::vector<Vector3d> corners = box_corners(lo, hi);
  // Faces of box_corners' numbering (bit 0: x, bit 1: y, bit 2: z), counter-clockwise from outside.
  dir.write("parts/box.cao",
            cao(corners, {}, {}, {"4 0 2 3 1", "4 4 5 7 6", "4 0 1 5 4", "4 2 6 7 3", "4 0 4 6 2", "4 1 3 7 5"}));
  const Vector3d t(0.1, -0.05, 0.2), tu(0.0, 0.0, 30.0 * kPi / 180.0);
  const Vector3d own(0.3, 0.3, 0.3);  // the including file's own triangle
  const std::string path =
      dir.write("scene.cao", cao({own, own + Vector3d(0.1, 0, 0), own + Vector3d(0, 0.1, 0)}, {}, {}, {"3 0 1 2"}, {},
                                 {}, "load(\"parts/box.cao\", t=[0.1; -0.05; 0.2], tu=[0; 0; 30 deg])\n"));

  std::vector<Vector3d> expected = transformed(corners, rotation_about(tu), t);
  expected.insert(expected.end(), {own, own + Vector3d(0.1, 0, 0), own + Vector3d(0, 0.1, 0)});
  const Mesh mesh = icgp::load_cao_mesh(path);
  CHECK(mesh.triangle_count() == 13);
  CHECK(mesh_signed_volume(icgp::load_cao_mesh(dir.file("parts/box.cao"))) == Approx((hi - lo).prod()).epsilon(1e-6));
  check_vertices_are(mesh, expected, 1e-6);

  const Vector3d T_theta_u(-0.3, 0.1, 0.6), T_t(0.5, 0.4, -0.1);
  const Mesh moved = icgp::load_cao_mesh(path, Pose::from_rotation_vector(T_theta_u, T_t));
  check_vertices_are(moved, transformed(expected, rotation_about(T_theta_u), T_t), 1e-6);
}

TEST_CASE("unreadable models give a std::runtime_error naming the file and the problem") {
  TempDir dir("icgp-cao");
  SECTION("missing file") {
    const std::string missing = dir.file("does-not-exist.cao");
    CHECK_THAT(error_of([&] { icgp::load_cao_mesh(missing); }), Catch::Contains(missing));
  }
  SECTION("a coordinate that is not a number") {
    const std::string path = dir.write("bad-number.cao", "V1\n3\n0 0 0\n1 0 0\nfoo\n0\n0\n1\n3 0 1 2\n0\n0\n");
    CHECK_THAT(error_of([&] { icgp::load_cao_mesh(path); }), Catch::Contains(path));
  }
  SECTION("a face using a point that does not exist") {
    const std::string path = dir.write("bad-index.cao", cao({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}, {}, {"3 0 1 7"}));
    CHECK_THAT(error_of([&] { icgp::load_cao_mesh(path); }),
               Catch::Contains(path) && Catch::Contains(":13: face 0 (face from points) point 2: 7 (expected an index of the "
                                                        "points, 0 to 2)"));
  }
  SECTION("no V1 header") {
    const std::string path = dir.write("empty.cao", "\n");
    CHECK_THAT(error_of([&] { icgp::load_cao_mesh(path); }),
               Catch::Contains(path) && Catch::Contains(":1: version: '' (expected 'V1' or 'V2'"));
  }
  SECTION("an include that does not exist") {
    const std::string path = dir.write("broken-include.cao", "V1\nload(\"nowhere.cao\")\n" + cao({}).substr(3));
    CHECK_THAT(error_of([&] { icgp::load_cao_mesh(path); }), Catch::Contains(path));
  }
  SECTION("a circle whose points define no plane") {
    const std::string path =
        dir.write("flat-circle.cao", cao({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {}, {}, {}, {}, {"0.1 0 1 2 name=rim"}));
    CHECK_THAT(error_of([&] { icgp::load_cao_mesh(path); }),
               Catch::Contains(path) && Catch::Contains("circle 0 plane: points 0, 1 and 2 are collinear"));
  }
  SECTION("a self-intersecting face without any ear") {
    std::vector<Vector3d> crossed;
    for (const auto& [x, y] : std::vector<std::pair<int, int>>{{3, 4}, {0, 3}, {1, 3}, {3, 1}, {2, 4}, {2, 0}})
      crossed.emplace_back(0.01 * x, 0.01 * y, 0.0);
    const std::string path = dir.write("crossed.cao", cao(crossed, {}, {}, {face_of_all(crossed.size())}));
    CHECK_THAT(error_of([&] { icgp::load_cao_mesh(path); }),
               Catch::Contains(path) && Catch::Contains("face #1") && Catch::Contains("intersects itself"));
  }
  SECTION("a cylinder with a negative radius") {
    const std::string path = dir.write("inside-out.cao", cao({{0, 0, 0}, {0, 0, 1}}, {}, {}, {}, {"0 1 -0.1"}));
    CHECK_THAT(error_of([&] { icgp::load_cao_mesh(path); }),
               Catch::Contains(path) && Catch::Contains("cylinder 0 radius: '-0.1' (expected a decimal number > 0"));
  }
  SECTION("a cylinder without an axis, which ViSP would drop with a warning") {
    const std::string path = dir.write("no-axis.cao", cao({{0, 0, 0}}, {}, {}, {}, {"0 0 0.1"}));
    CHECK_THAT(error_of([&] { icgp::load_cao_mesh(path); }),
               Catch::Contains(path) && Catch::Contains("cylinder 0 axis: points 0 and 0 coincide"));
  }
}

TEST_CASE("tessellations below 3 segments are refused") {
  const std::string cube = (kModels / "cube" / "cube.cao").string();
  CHECK_THROWS_AS(icgp::load_cao_mesh(cube, Pose(), icgp::CaoTessellation{2, 48}), std::invalid_argument);
  CHECK_THROWS_AS(icgp::load_cao_mesh(cube, Pose(), icgp::CaoTessellation{48, 0}), std::invalid_argument);
}

TEST_CASE("load_any_mesh applies T * (scale * X) to .cao and assimp formats alike") {
  TempDir dir("icgp-cao");
  const Pose T = Pose::from_rotation_vector({0, 0, kPi / 2}, {0.1, 0.2, 0.3});
  const double scale = 2.0;

  const Mesh cube = icgp::load_any_mesh((kModels / "cube" / "cube.cao").string(), scale, T);
  const double side = scale * 0.042;
  check_bounds(cube, {0.1 - side, 0.2 - side, 0.3}, {0.1, 0.2, 0.3 + side}, 1e-6);

  const std::string obj = dir.write("triangle.obj", "v 0 0 0\nv 0.1 0 0\nv 0 0.05 0\nf 1 2 3\n");
  const Mesh triangle = icgp::load_any_mesh(obj, scale, T);
  CHECK(triangle.triangle_count() == 1);
  check_vertices_are(triangle, {{0.1, 0.2, 0.3}, {0.1, 0.2 + 0.2, 0.3}, {0.1 - 0.1, 0.2, 0.3}}, 1e-6);

  CHECK_THROWS_AS(icgp::load_any_mesh(obj, 0.0), std::invalid_argument);
}
