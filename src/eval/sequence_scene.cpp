// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/eval/sequence_scene.h"

#include <algorithm>
#include <exception>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "icgp/geometry/tree_order.h"
#include "icgp/io/joint_yaml.h"
#include "icgp/io/mesh_loader.h"
#include "icgp/io/model_reference.h"

namespace icgp {
namespace {

using yaml::Interval;
using yaml::Location;
using yaml::Map;
using yaml::Value;

constexpr Interval kScale{0.0, 1000.0, true};  ///< metres per mesh unit
constexpr Interval kRate{-100.0, 100.0};       ///< m/s of a velocity, rad/s of a spin
constexpr Interval kPeriod{0.0, 1e6, true};    ///< seconds
constexpr Interval kTrajectoryDeg{-36000.0, 36000.0};
constexpr Interval kTrajectoryM{-100.0, 100.0};

const std::vector<std::string>& body_keys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> k = {"name", "mesh", "scale", "pose", "velocity", "spin", "trajectory"};
    k.insert(k.end(), joint_keys().begin(), joint_keys().end());
    return k;
  }();
  return keys;
}

/// {from_deg, to_deg, period} of a rotation, {from, to, period} of a translation, within
/// the direction's limits.
JointTrajectory read_trajectory(const Value& v, const JointDirection& d) {
  const bool rotation = d.kind == JointDirection::Kind::kRotation;
  const std::string from_key = rotation ? "from_deg" : "from", to_key = rotation ? "to_deg" : "to";
  const Map m(v, {from_key, to_key, "period"});
  const Interval& range = rotation ? kTrajectoryDeg : kTrajectoryM;
  const double unit = rotation ? kPi / 180.0 : 1.0;  // as read_joint converts limits_deg
  JointTrajectory trajectory;
  trajectory.from = m.required(from_key).number_in(range) * unit;
  trajectory.to = m.required(to_key).number_in(range) * unit;
  trajectory.period = m.required("period").number_in(kPeriod);
  if (std::min(trajectory.from, trajectory.to) < d.min || std::max(trajectory.from, trajectory.to) > d.max) {
    const auto shown = [&](double value) { return yaml::plain_number(value / unit); };
    v.at.fail("from " + shown(trajectory.from) + " to " + shown(trajectory.to) + (rotation ? " deg" : " m") +
              " leaves the joint's limits [" + shown(d.min) + ", " + shown(d.max) + "]");
  }
  return trajectory;
}

/// One trajectory per direction: a map for a one-direction joint, a list otherwise.
std::vector<JointTrajectory> read_trajectories(const Map& body, const Joint& joint) {
  if (joint.size() == 0) {
    if (auto x = body.get("trajectory")) x->at.fail("a fixed joint has no trajectory");
    return {};
  }
  const Value v = body.required("trajectory");
  std::vector<JointTrajectory> trajectories;
  if (!v.node.IsSequence()) {
    if (joint.size() != 1) v.expected("a list of " + std::to_string(joint.size()) + " trajectories, one per direction");
    trajectories.push_back(read_trajectory(v, joint.directions[0]));
    return trajectories;
  }
  const std::vector<Value> elements = v.elements("a list of trajectories");
  if (static_cast<int>(elements.size()) != joint.size())
    v.expected("a list of " + std::to_string(joint.size()) + " trajectories, one per direction");
  for (int k = 0; k < joint.size(); ++k) trajectories.push_back(read_trajectory(elements[k], joint.directions[k]));
  return trajectories;
}

SceneBody read_body(const Value& entry, const Location& list, const std::string& scene_dir,
                    const std::string& models_dir) {
  SceneBody body;
  body.name = Map(entry, body_keys()).required("name").as(yaml::kNonEmptyString);
  // Errors below name the body rather than its index: "bodies.lid.limits_deg: …".
  const Value named{entry.node, list.child(body.name)};
  const Map m(named, body_keys());
  const Value mesh = m.required("mesh");
  // Absolute: sequence.yaml records it, and reads it relative to the sequence's folder.
  body.mesh_path = std::filesystem::absolute(model_file(mesh, scene_dir, models_dir)).lexically_normal().string();
  body.mesh_at = mesh.at;
  if (auto x = m.get("scale")) body.scale = x->number_in(kScale);
  body.joint = read_joint(m);
  if (body.joint) {
    for (const char* key : {"pose", "velocity", "spin"})
      if (auto x = m.get(key)) x->at.fail("a link is placed by its parent and joint");
    try {
      validate(*body.joint, body.name);
    } catch (const std::invalid_argument& e) {
      named.at.fail(e.what());
    }
    body.trajectory = read_trajectories(m, *body.joint);
    return body;
  }
  if (auto x = m.get("trajectory")) x->at.fail("only a link (a body with a parent) has a trajectory");
  if (auto x = m.get("pose")) body.world_T_object = yaml::pose(*x);
  if (auto x = m.get("velocity")) body.velocity = yaml::numbers<3>(*x, kRate);
  if (auto x = m.get("spin")) body.spin = yaml::numbers<3>(*x, kRate);
  return body;
}

/// The bodies with every parent before its links. Fails on a parent that is not a body
/// and on a cycle of parents, naming the link and its `parent`.
std::vector<SceneBody> parents_first(std::vector<SceneBody> bodies, const Location& list) {
  std::vector<std::string> names, parents;
  for (const SceneBody& body : bodies) {
    names.push_back(body.name);
    parents.push_back(body.joint ? body.joint->parent : "");
  }
  const TreeOrder tree = icgp::parents_first(names, parents);
  if (const std::optional<TreeOrderProblem>& problem = tree.problem) {
    const Location parent = list.child(names[problem->body]).child("parent");
    if (problem->kind == TreeOrderProblem::Kind::kUnknownParent)
      parent.fail("no body is named '" + parents[problem->body] + "'");
    parent.fail("the parents form a cycle: " + problem->chain);
  }
  std::vector<SceneBody> ordered;
  for (const std::size_t i : tree.order) ordered.push_back(std::move(bodies[i]));
  return ordered;
}

}  // namespace

std::vector<SceneBody> read_sequence_scene(const std::string& path, const std::string& models_dir) {
  const Value root = yaml::load_file(path, {"scene file"});
  const Map scene(root, {"bodies"});
  const Value list = scene.required("bodies");
  const std::string scene_dir = std::filesystem::path(path).parent_path().string();
  std::vector<SceneBody> bodies;
  for (const Value& entry : list.elements("a list of bodies")) {
    SceneBody body = read_body(entry, list.at, scene_dir, models_dir);
    if (std::any_of(bodies.begin(), bodies.end(), [&](const SceneBody& b) { return b.name == body.name; }))
      list.at.child(body.name).child("name").fail("two bodies are named '" + body.name + "'");
    bodies.push_back(std::move(body));
  }
  if (bodies.empty()) list.expected("a list of at least one body");
  return parents_first(std::move(bodies), list.at);
}

void add_scene_bodies(SequenceWriter& writer, const std::vector<SceneBody>& bodies) {
  for (const SceneBody& body : bodies) {
    Mesh mesh;
    try {
      mesh = load_mesh(body.mesh_path, {body.scale});
    } catch (const std::exception& e) {
      body.mesh_at.fail(std::string("cannot read the mesh: ") + e.what());
    }
    if (body.joint)
      writer.add_link(body.name, mesh, *body.joint, body.trajectory, body.mesh_path);
    else
      writer.add_object(body.name, mesh, body.world_T_object, body.mesh_path, body.spin, body.velocity);
  }
}

}  // namespace icgp
