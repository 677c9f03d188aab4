// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/tracker/body_config.h"

#include <algorithm>
#include <stdexcept>

#include "icgp/io/joint_yaml.h"

namespace icgp {
namespace {

const BodyConfig* find(const std::vector<BodyConfig>& bodies, const std::string& name) {
  for (const BodyConfig& body : bodies)
    if (body.name == name) return &body;
  return nullptr;
}

/// The parents from `body` upwards until a body without parent, or the first repeated
/// name: "lid → box → lid" (empty when there is no cycle).
std::string cycle_from(const std::vector<BodyConfig>& bodies, const BodyConfig& body) {
  std::vector<std::string> chain = {body.name};
  for (const BodyConfig* at = &body; at->joint;) {
    const std::string& parent = at->joint->parent;
    const bool repeated = std::find(chain.begin(), chain.end(), parent) != chain.end();
    chain.push_back(parent);
    if (repeated) {
      std::string text;
      for (const std::string& name : chain) text += (text.empty() ? "" : " -> ") + name;
      return text;
    }
    at = find(bodies, parent);
    if (!at) break;
  }
  return "";
}

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
    if (auto x = m.get("scale")) body.scale = x->number_in({0.0, 1e6, true});
    if (auto x = m.get("role")) body.occluder = x->choice<bool>({{"tracked", false}, {"occluder", true}});
    body.joint = read_joint(m);
    if (body.occluder && body.joint) m.required("parent").at.fail("an occluder is placed by the caller, not by a joint");
    bodies.push_back(std::move(body));
  }
  for (const BodyConfig& body : bodies) {
    const std::string cycle = cycle_from(bodies, body);
    if (!cycle.empty()) list.at.child(body.name).child("parent").fail("the parents form a cycle: " + cycle);
  }
  return bodies;
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
    if (!body.joint) continue;
    const std::string& parent = body.joint->parent;
    const BodyConfig* parent_config = find(bodies, parent);
    if (parent != main_body && !parent_config)
      throw std::invalid_argument("body '" + body.name + "': parent: no body is named '" + parent +
                                  "' (the bodies are " + yaml::join(names) + ")");
    if (parent_config && parent_config->occluder)
      throw std::invalid_argument("body '" + body.name + "': parent: '" + parent +
                                  "' is an occluder, which is not tracked");
    const std::string cycle = cycle_from(bodies, body);
    if (!cycle.empty()) throw std::invalid_argument("body '" + body.name + "': parent: the parents form a cycle: " + cycle);
  }
  // Free bodies and occluders first, then links whose parent is placed, until all are.
  std::vector<const BodyConfig*> ordered;
  std::vector<std::string> placed = {main_body};
  while (ordered.size() < bodies.size())
    for (const BodyConfig& body : bodies) {
      const bool done = std::find(ordered.begin(), ordered.end(), &body) != ordered.end();
      if (done || (body.joint && std::find(placed.begin(), placed.end(), body.joint->parent) == placed.end())) continue;
      ordered.push_back(&body);
      placed.push_back(body.name);
    }
  return ordered;
}

}  // namespace icgp
