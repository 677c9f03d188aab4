// SPDX-License-Identifier: GPL-2.0-or-later
// The `bodies:` list of a tracker configuration: joints read as written, and every bad
// input refused with the file, the body and the field named.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "icgp/tracker/tracker_builder.h"
#include "icgp/tracker/tracker_config.h"
#include "test_meshes.h"
#include "test_temp_dir.h"

using namespace icgp;
using Catch::Contains;
using icgp::test::TempDir;

namespace {

std::string with_bodies(const std::string& bodies) { return "modalities: [texture]\nbodies:\n" + bodies; }

}  // namespace

TEST_CASE("bodies: a joint is read as written, with relative meshes beside the file") {
  TempDir dir("icgp-bodies");
  const std::string file = dir.write("config.yaml", with_bodies(R"(
  - name: lid
    mesh: parts/lid.obj
    parent: box
    joint: revolute
    axis: [0, 0, 2]
    origin: {t: [0, 0.05, 0.04], r_deg: [0, 0, 90]}
    limits_deg: [0, 90]
    stiffness: 5
  - name: drawer
    mesh: /abs/drawer.obj
    scale: 0.001
    parent: box
    joint: directions
    directions:
      - {translation: [1, 0, 0], limits: [0, 0.2]}
      - {rotation: [0, 1, 0], limits_deg: [-10, 10], stiffness: 100}
  - name: hand
    mesh: hand.obj
    role: occluder
)"));
  const TrackerConfig config = load_tracker_config(file);
  REQUIRE(config.bodies.size() == 3);
  const BodyConfig& lid = config.bodies[0];
  CHECK(lid.mesh == (dir.path() / "parts/lid.obj").string());
  REQUIRE(lid.joint);
  CHECK(lid.joint->parent == "box");
  REQUIRE(lid.joint->directions.size() == 1);
  const JointDirection& hinge = lid.joint->directions[0];
  CHECK(hinge.kind == JointDirection::Kind::kRotation);
  CHECK(hinge.axis == Eigen::Vector3d::UnitZ());  // normalised
  CHECK(hinge.max == Approx(kPi / 2));
  CHECK(hinge.stiffness == 5.0);
  CHECK(lid.joint->parent_T_joint.translation().isApprox(Eigen::Vector3d(0, 0.05, 0.04)));
  CHECK(lid.joint->parent_T_joint.rotation().isApprox(
      Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix()));
  const BodyConfig& drawer = config.bodies[1];
  CHECK(drawer.scale == 0.001);
  REQUIRE(drawer.joint->directions.size() == 2);
  CHECK(drawer.joint->directions[0].kind == JointDirection::Kind::kTranslation);
  CHECK(drawer.joint->directions[0].max == 0.2);
  CHECK(drawer.joint->directions[1].min == Approx(-10 * kPi / 180));
  CHECK(config.bodies[2].occluder);
  CHECK_FALSE(config.bodies[2].joint);
  // Written and read back, the list is the same.
  const TrackerConfig back = load_tracker_config(dir.write("back.yaml", to_yaml(config)));
  CHECK(to_yaml(back) == to_yaml(config));
}

TEST_CASE("bodies: a joint open at one end is written as the farthest limit a file may hold") {
  TempDir dir("icgp-bodies");
  TrackerConfig config;
  config.bodies = {BodyConfig{"lid", "lid.obj", 1.0, false,
                              Joint::revolute("box", Pose(), Eigen::Vector3d::UnitX(), 0.0,
                                              std::numeric_limits<double>::infinity())}};
  const TrackerConfig back = load_tracker_config(dir.write("open.yaml", to_yaml(config)));
  REQUIRE(back.bodies.size() == 1);
  const JointDirection& d = back.bodies[0].joint->directions.at(0);
  CHECK(d.min == 0.0);
  CHECK(d.max == Approx(36000.0 * kPi / 180.0));
}

TEST_CASE("bodies: bad lists name the file, the body and the field") {
  TempDir dir("icgp-bodies");
  struct Case {
    const char* bodies;
    const char* message;
  };
  const Case cases[] = {
      {"  - {name: lid, mesh: a.obj, parent: box, joint: revolute, limits_deg: [90, 0]}\n",
       "bodies.lid.limits_deg: expected min <= max, got [90, 0]"},
      {"  - {name: lid, mesh: a.obj}\n  - {name: lid, mesh: b.obj}\n",
       "bodies[1].name: expected a name no other body has, got 'lid'"},
      {"  - {name: a, mesh: a.obj, parent: b, joint: fixed}\n  - {name: b, mesh: b.obj, parent: a, joint: fixed}\n",
       "bodies.a.parent: the parents form a cycle: a -> b -> a"},
      {"  - {name: a, mesh: a.obj, parent: a, joint: revolute}\n", "bodies.a.parent: the parents form a cycle: a -> a"},
      {"  - {name: lid, mesh: a.obj, parent: box, joint: hinge}\n",
       "bodies.lid.joint: expected one of revolute, prismatic, fixed, directions, got 'hinge'"},
      {"  - {name: lid, mesh: a.obj, parent: box}\n", "bodies.lid.joint: required"},
      {"  - {name: lid, mesh: a.obj, joint: revolute}\n", "bodies.lid.joint: only a body with a parent has a joint"},
      {"  - {name: lid, mesh: a.obj, parent: box, joint: prismatic, limits_deg: [0, 1]}\n",
       "bodies.lid.limits_deg: a prismatic joint's limits are limits (metres)"},
      {"  - {name: hand, mesh: h.obj, role: occluder, parent: box, joint: fixed}\n",
       "bodies.hand.parent: an occluder is placed by the caller, not by a joint"},
      {"  - {name: lid, mesh: a.obj, parent: box, joint: revolute, axis: [0, 0, 0]}\n",
       "bodies.lid.axis: expected a non-zero vector"},
  };
  for (const Case& c : cases) {
    INFO(c.bodies);
    const std::string file = dir.write("bad.yaml", with_bodies(c.bodies));
    CHECK_THROWS_WITH(load_tracker_config(file), Contains(file + ": " + c.message));
  }
}

TEST_CASE("bodies: building refuses unknown parents, taken names and unreadable meshes, naming the body") {
  TrackerConfig config;
  config.modalities = {cue::kTexture};  // no viewpoint model to generate
  const Mesh box = test::make_box(0.1f, 0.1f, 0.1f);
  auto body = [](std::string name, std::string mesh, std::optional<Joint> joint = std::nullopt, bool occluder = false) {
    return BodyConfig{std::move(name), std::move(mesh), 1.0, occluder, std::move(joint)};
  };
  const Joint hinge = Joint::revolute("bsae", Pose(), Eigen::Vector3d::UnitX(), 0.0, 1.0);

  config.bodies = {body("lid", "lid.obj", hinge)};
  CHECK_THROWS_WITH(build_tracker(config, box, "base"),
                    Contains("body 'lid': parent: no body is named 'bsae' (the bodies are base, lid)"));
  config.bodies = {body("base", "other.obj")};
  CHECK_THROWS_WITH(build_tracker(config, box, "base"), Contains("body 'base': name: another body has this name"));
  config.bodies = {body("hand", "/no/such/hand.obj", std::nullopt, true)};
  CHECK_THROWS_WITH(build_tracker(config, box, "base"),
                    Contains("body 'hand': mesh: ") && Contains("/no/such/hand.obj"));
  config.bodies = {body("hand", "hand.obj", std::nullopt, true),
                   body("lid", "lid.obj", Joint::revolute("hand", Pose(), Eigen::Vector3d::UnitX(), 0.0, 1.0))};
  CHECK_THROWS_WITH(build_tracker(config, box, "base"), Contains("body 'lid': parent: 'hand' is an occluder"));
}

TEST_CASE("bodies: a built tracker has the links, joints and occluders of the list") {
  TrackerConfig config;
  config.modalities = {cue::kTexture};
  const Mesh box = test::make_box(0.1f, 0.1f, 0.1f);
  const MeshReader boxes = [&](const std::string&, double) { return box; };
  // The lid is listed before its parent: the builder orders the tree.
  config.bodies = {BodyConfig{"knob", "knob.obj", 1.0, false,
                              Joint::prismatic("lid", Pose(), Eigen::Vector3d::UnitZ(), 0.01, 0.1)},
                   BodyConfig{"lid", "lid.obj", 1.0, false,
                              Joint::revolute("base", Pose(), Eigen::Vector3d::UnitX(), 0.0, 1.0)},
                   BodyConfig{"hand", "hand.obj", 1.0, true, std::nullopt}};
  std::unique_ptr<Tracker> tracker = build_tracker(config, box, "base", {CameraCues{"Camera1", visp_type::kKlt, ""}},
                                                   nullptr, boxes);
  std::vector<std::string> names;
  for (Body* body : tracker->bodies()) names.push_back(body->name);
  CHECK(names == std::vector<std::string>{"base", "lid", "knob"});
  CHECK(tracker->joint_values("lid") == std::vector<double>{0.0});
  CHECK(tracker->joint_values("knob") == std::vector<double>{0.01});  // 0 clamped into [0.01, 0.1]
  CHECK(tracker->modalities("lid").size() == 1);
  CHECK(tracker->modalities("hand").empty());  // the occluder: rendered, not tracked
}
