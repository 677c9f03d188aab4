// SPDX-License-Identifier: GPL-2.0-or-later
// mesh_symmetries against the known rotation groups of boxes, a cube and the two-colour box;
// round_axes and their turns against a labelled can (round) and shapes that are not round.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include "icgp/detection/mesh_symmetries.h"
#include "icgp/io/mesh_loader.h"

using namespace icgp;

namespace {

/// Whether every symmetry maps every vertex of `mesh` onto a vertex of the same part's colour.
bool maps_vertices_onto_vertices(const Mesh& mesh, const Pose& symmetry) {
  for (const MeshPart& part : mesh.parts)
    for (const Eigen::Vector3f& v : part.vertices) {
      const Eigen::Vector3d moved = symmetry * v.cast<double>();
      bool found = false;
      for (const MeshPart& other : mesh.parts) {
        if ((other.material.diffuse_rgb - part.material.diffuse_rgb).norm() > 1e-3f) continue;
        for (const Eigen::Vector3f& w : other.vertices) found = found || (w.cast<double>() - moved).norm() < 1e-3;
      }
      if (!found) return false;
    }
  return true;
}

}  // namespace

TEST_CASE("mesh symmetries: a box of three different sides has its three half turns") {
  const Mesh box = box_mesh(Eigen::Vector3d(0.1, 0.08, 0.06), Eigen::Vector3f(0.5f, 0.5f, 0.5f));
  const std::vector<Pose> symmetries = mesh_symmetries(box);
  REQUIRE(symmetries.size() == 3);
  for (const Pose& s : symmetries) {
    CHECK(Eigen::AngleAxisd(s.rotation()).angle() == Approx(kPi).margin(1e-6));
    CHECK(s.translation().norm() < 1e-9);
    CHECK(maps_vertices_onto_vertices(box, s));
  }
}

TEST_CASE("mesh symmetries: a cube has the 23 turns of its rotation group") {
  const Mesh cube = box_mesh(Eigen::Vector3d(0.05, 0.05, 0.05), Eigen::Vector3f(0.2f, 0.6f, 0.2f));
  const std::vector<Pose> symmetries = mesh_symmetries(cube);
  CHECK(symmetries.size() == 23);
  for (const Pose& s : symmetries) CHECK(maps_vertices_onto_vertices(cube, s));
}

TEST_CASE("mesh symmetries: the two-colour box keeps only the half turn about its colour boundary's normal") {
  const Mesh two_region = load_mesh(ICGP_MODELS_DIR "/two_region/object.obj");
  const std::vector<Pose> symmetries = mesh_symmetries(two_region);
  REQUIRE(symmetries.size() == 1);
  const Eigen::AngleAxisd turn(symmetries[0].rotation());
  CHECK(turn.angle() == Approx(kPi).margin(1e-6));
  CHECK(std::abs(turn.axis().y()) == Approx(1.0).margin(1e-6));
  CHECK(maps_vertices_onto_vertices(two_region, symmetries[0]));
}

TEST_CASE("mesh symmetries: a handle off every axis, a texture or no area leaves none") {
  Mesh mug_like = box_mesh(Eigen::Vector3d(0.08, 0.1, 0.08), Eigen::Vector3f(0.9f, 0.9f, 0.9f));
  Mesh handle = box_mesh(Eigen::Vector3d(0.03, 0.04, 0.01), Eigen::Vector3f(0.9f, 0.9f, 0.9f));
  handle.transform(Posef(Eigen::Matrix3f::Identity(), Eigen::Vector3f(0.055f, 0.02f, 0.f)));
  mug_like.append(handle);
  CHECK(mesh_symmetries(mug_like).empty());
  CHECK(mesh_symmetries(load_mesh(ICGP_MODELS_DIR "/textured_box/textured_box.obj")).empty());
  // No area to sample (every triangle on a line): nothing to claim.
  Mesh line;
  line.parts.push_back({{Eigen::Vector3f(0, 0, 0), Eigen::Vector3f(0.1f, 0, 0), Eigen::Vector3f(0.2f, 0, 0)}, {}, {Eigen::Vector3i(0, 1, 2)}, {}});
  CHECK(mesh_symmetries(line).empty());
}

TEST_CASE("mesh symmetries: the closed mug, its handle centred on the x axis, turns half about that axis") {
  const Mesh mug = load_mesh(ICGP_MODELS_DIR "/textureless_mug/textureless_mug.obj");
  const std::vector<Pose> symmetries = mesh_symmetries(mug);
  REQUIRE(symmetries.size() == 1);
  const Eigen::AngleAxisd turn(symmetries[0].rotation());
  CHECK(turn.angle() == Approx(kPi).margin(1e-6));
  CHECK(std::abs(turn.axis().x()) == Approx(1.0).margin(1e-6));
  CHECK(symmetries[0].translation().norm() < 1e-6);
}

TEST_CASE("round axis turns: the labelled can's shape is round about its axis, whatever its label says") {
  const Mesh can = load_mesh(ICGP_MODELS_DIR "/labelled_can/object.obj");
  // Its label breaks every symmetry of its look, not of its shape.
  CHECK(mesh_symmetries(can).empty());
  CHECK_FALSE(mesh_symmetries(can, Keeping::kShape).empty());
  const std::vector<Pose> turns = turns_about(round_axes(can), deg_to_rad(15.0));
  REQUIRE(turns.size() == 23);
  for (std::size_t k = 0; k < turns.size(); ++k) {
    const Eigen::AngleAxisd turn(turns[k].rotation());
    CHECK(std::abs(turn.axis().y()) == Approx(1.0).margin(1e-6));
    // 15, 30, ... 345 degrees (as 15..180 about +y or -y).
    const double degrees = turn.angle() * 180.0 / kPi;
    CHECK(std::remainder(degrees, 15.0) == Approx(0.0).margin(1e-6));
    CHECK(turns[k].translation().norm() < 1e-3);  // about the can's centroid, on its axis
  }
}

TEST_CASE("round axis turns: a box, a cube and a mug with its handle have no round axis") {
  const Eigen::Vector3f grey(0.5f, 0.5f, 0.5f);
  CHECK(round_axes(box_mesh(Eigen::Vector3d(0.1, 0.08, 0.06), grey)).empty());
  CHECK(round_axes(box_mesh(Eigen::Vector3d(0.05, 0.05, 0.05), grey)).empty());
  CHECK(round_axes(load_mesh(ICGP_MODELS_DIR "/textureless_mug/textureless_mug.obj")).empty());
}

TEST_CASE("round axis turns: turned_towards takes the turn about the axis that is nearest to another pose") {
  const BodyAxis axis{Eigen::Vector3d(0.01, 0.02, -0.03), Eigen::Vector3d(0.0, 1.0, 0.0)};
  const Pose pose = Pose::from_rotation_vector(Eigen::Vector3d(0.4, -0.2, 0.9), Eigen::Vector3d(0.1, -0.05, 0.6));
  const auto turned_by = [&](double degrees) {
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(deg_to_rad(degrees), axis.direction).toRotationMatrix();
    return pose * Pose(turn, axis.point - turn * axis.point);
  };
  for (const double degrees : {37.0, -120.0, 179.0}) {
    INFO(degrees << " degrees about the axis");
    // Exactly a turn about the axis: found exactly, the axis's points staying where they were.
    const Pose target = turned_by(degrees);
    const Pose found = turned_towards(pose, axis, target);
    CHECK(rotation_angle_between(found.rotation(), target.rotation()) < 1e-9);
    CHECK((found.translation() - target.translation()).norm() < 1e-9);
    CHECK((found * axis.point - pose * axis.point).norm() < 1e-12);
    // With a swing of 5 degrees about another axis on top: the turn still found, and only
    // the swing left between them.
    const Pose swung = target * Pose(Eigen::AngleAxisd(deg_to_rad(5.0), Eigen::Vector3d::UnitX()).toRotationMatrix(),
                                     Eigen::Vector3d::Zero());
    const Pose nearest = turned_towards(pose, axis, swung);
    CHECK(rotation_angle_between(nearest.rotation(), swung.rotation()) * 180.0 / kPi == Approx(5.0).margin(1e-6));
    CHECK(rotation_angle_between(nearest.rotation(), target.rotation()) < 1e-9);
  }
}
