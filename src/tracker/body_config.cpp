// SPDX-License-Identifier: GPL-2.0-or-later
#include "body_config_yaml.h"

#include <algorithm>
#include <stdexcept>

#include "icgp/geometry/tree_order.h"
#include "icgp/io/joint_yaml.h"

namespace icgp {
namespace {

const BodyConfig* find(const std::vector<BodyConfig>& bodies, const std::string& name) {
  for (const BodyConfig& body : bodies)
    if (body.name == name) return &body;
  return nullptr;
}

/// The bodies' tree order, parents outside the list taken as placed when `outside_roots`
/// names them.
TreeOrder tree_order(const std::vector<BodyConfig>& bodies, const std::vector<std::string>& outside_roots) {
  std::vector<std::string> names, parents;
  for (const BodyConfig& body : bodies) {
    names.push_back(body.name);
    parents.push_back(body.joint ? body.joint->parent : "");
  }
  return parents_first(names, parents, outside_roots);
}

/// The main body is named by the program, not the configuration: only cycles are refused.
void refuse_parent_cycles(const std::vector<BodyConfig>& bodies, const yaml::Location& list) {
  std::vector<std::string> outside;
  for (const BodyConfig& body : bodies)
    if (body.joint && !find(bodies, body.joint->parent)) outside.push_back(body.joint->parent);
  const TreeOrder tree = tree_order(bodies, outside);
  if (tree.problem)
    list.child(bodies[tree.problem->body].name).child("parent").fail("the parents form a cycle: " + tree.problem->chain);
}

/// A body's scale: a factor of its mesh's units.
const yaml::Interval kScale{0.0, 1e6, true};

}  // namespace

std::vector<BodyConfig> read_body_configs(const yaml::Value& list) {
  std::vector<BodyConfig> bodies;
  std::vector<std::string> keys = {"name", "mesh", "scale", "role"};
  keys.insert(keys.end(), joint_keys().begin(), joint_keys().end());
  for (const yaml::Value& entry : list.elements("a list of bodies")) {
    const yaml::Value name = yaml::Map(entry, keys).required("name");
    BodyConfig body;
    body.name = name.as(yaml::kNonEmptyString);
    if (find(bodies, body.name)) name.expected("a name no other body has");
    // The body's keys are named after it: "bodies.lid.limits_deg".
    const yaml::Map m(yaml::Value{entry.node, list.at.child(body.name)}, keys);
    body.mesh = m.required("mesh").as(yaml::kNonEmptyString);
    if (auto x = m.get("scale")) body.scale = x->number_in(kScale);
    if (auto x = m.get("role")) body.occluder = x->choice<bool>({{"tracked", false}, {"occluder", true}});
    body.joint = read_joint(m);
    if (body.occluder && body.joint) m.required("parent").at.fail("an occluder is placed by the caller, not by a joint");
    bodies.push_back(std::move(body));
  }
  refuse_parent_cycles(bodies, list.at);
  return bodies;
}

void check_body_configs(const std::vector<BodyConfig>& bodies, const yaml::Location& list) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const BodyConfig& body = bodies[i];
    if (body.name.empty()) list.element(i).child("name").fail("expected a non-empty string");
    if (find(bodies, body.name) != &body) list.element(i).child("name").fail("expected a name no other body has");
    const yaml::Location at = list.child(body.name);
    if (body.mesh.empty()) at.child("mesh").fail("expected a non-empty string");
    if (!kScale.contains(body.scale)) at.child("scale").fail("expected a number in " + kScale.text());
    if (!body.joint) continue;
    if (body.occluder) at.child("parent").fail("an occluder is placed by the caller, not by a joint");
    Joint joint = *body.joint;
    try {
      validate(joint, body.name);
    } catch (const std::invalid_argument& e) {
      list.fail(e.what());  // already names the body and the joint's field
    }
  }
  refuse_parent_cycles(bodies, list);
}

void write_body_configs(YAML::Emitter& out, const std::vector<BodyConfig>& bodies) {
  out << YAML::BeginSeq;
  for (const BodyConfig& body : bodies) {
    out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << body.name << YAML::Key << "mesh" << YAML::Value
        << body.mesh << YAML::Key << "scale" << YAML::Value << yaml::exact_number(body.scale) << YAML::Key << "role" << YAML::Value
        << (body.occluder ? "occluder" : "tracked");
    if (body.joint) write_joint(out, *body.joint);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

std::vector<const BodyConfig*> in_tree_order(const std::vector<BodyConfig>& bodies, const std::string& main_body) {
  std::vector<std::string> names = {main_body};
  for (const BodyConfig& body : bodies) {
    if (std::find(names.begin(), names.end(), body.name) != names.end())
      throw std::invalid_argument("body '" + body.name + "': name: another body has this name");
    names.push_back(body.name);
  }
  for (const BodyConfig& body : bodies) {
    const BodyConfig* parent = body.joint ? find(bodies, body.joint->parent) : nullptr;
    if (parent && parent->occluder)
      throw std::invalid_argument("body '" + body.name + "': parent: '" + parent->name +
                                  "' is an occluder, which is not tracked");
  }
  const TreeOrder tree = tree_order(bodies, {main_body});
  if (const std::optional<TreeOrderProblem>& problem = tree.problem) {
    const BodyConfig& body = bodies[problem->body];
    if (problem->kind == TreeOrderProblem::Kind::kUnknownParent)
      throw std::invalid_argument("body '" + body.name + "': parent: no body is named '" + body.joint->parent +
                                  "' (the bodies are " + yaml::join(names) + ")");
    throw std::invalid_argument("body '" + body.name + "': parent: the parents form a cycle: " + problem->chain);
  }
  std::vector<const BodyConfig*> ordered;
  for (const std::size_t i : tree.order) ordered.push_back(&bodies[i]);
  return ordered;
}

}  // namespace icgp
