// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/io/joint_yaml.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace icgp {
namespace {

using yaml::Interval;
using yaml::Map;
using yaml::Value;

constexpr Interval kLimitDeg{-36000.0, 36000.0};  ///< a joint may turn a hundred times
constexpr Interval kLimitM{-100.0, 100.0};
constexpr Interval kStiffness{0.0, 1e12};

enum class JointType { kRevolute, kPrismatic, kFixed, kDirections };

/// [min, max] within `range`, min <= max; converted by `scale`.
void read_limits(const Value& v, const Interval& range, double scale, JointDirection& d) {
  const Eigen::Vector2d limits = yaml::numbers<2>(v, range);
  if (limits[0] > limits[1]) v.expected("min <= max");
  d.min = limits[0] * scale;
  d.max = limits[1] * scale;
}

Eigen::Vector3d read_axis(const Value& v) {
  const Eigen::Vector3d axis = yaml::numbers<3>(v, {-1000.0, 1000.0});
  if (axis.norm() < 1e-9) v.expected("a non-zero vector");
  return axis.normalized();
}

/// {rotation: axis | translation: axis, limits_deg | limits, stiffness}.
JointDirection read_direction(const Value& v) {
  const Map m(v, {"rotation", "translation", "limits_deg", "limits", "stiffness"});
  const std::optional<Value> rotation = m.get("rotation");
  const std::optional<Value> translation = m.get("translation");
  if (rotation.has_value() == translation.has_value()) v.expected("a map with either rotation or translation");
  JointDirection d;
  d.kind = rotation ? JointDirection::Kind::kRotation : JointDirection::Kind::kTranslation;
  d.axis = read_axis(rotation ? *rotation : *translation);
  if (rotation) {
    if (auto x = m.get("limits")) x->at.fail("a rotation's limits are limits_deg");
    if (auto x = m.get("limits_deg")) read_limits(*x, kLimitDeg, kPi / 180.0, d);
  } else {
    if (auto x = m.get("limits_deg")) x->at.fail("a translation's limits are limits (metres)");
    if (auto x = m.get("limits")) read_limits(*x, kLimitM, 1.0, d);
  }
  if (auto x = m.get("stiffness")) d.stiffness = x->number_in(kStiffness);
  return d;
}

}  // namespace

const std::vector<std::string>& joint_keys() {
  static const std::vector<std::string> keys = {"parent",     "joint",  "axis",      "origin",    "link_origin",
                                                "limits_deg", "limits", "stiffness", "directions"};
  return keys;
}

std::optional<Joint> read_joint(const Map& body) {
  const std::optional<Value> parent = body.get("parent");
  if (!parent) {
    for (const std::string& key : joint_keys())
      if (auto x = body.get(key)) x->at.fail("only a body with a parent has a joint");
    return std::nullopt;
  }
  Joint joint;
  joint.parent = parent->as(yaml::kNonEmptyString);
  if (auto x = body.get("origin")) joint.parent_T_joint = yaml::pose(*x);
  if (auto x = body.get("link_origin")) joint.joint_T_link = yaml::pose(*x);

  const JointType type = body.required("joint").choice<JointType>({{"revolute", JointType::kRevolute},
                                                                    {"prismatic", JointType::kPrismatic},
                                                                    {"fixed", JointType::kFixed},
                                                                    {"directions", JointType::kDirections}});
  auto refuse = [&](const std::string& key, const std::string& why) {
    if (auto x = body.get(key)) x->at.fail(why);
  };
  if (type == JointType::kDirections) {
    for (const std::string key : {"axis", "limits_deg", "limits", "stiffness"})
      refuse(key, "a joint of directions gives it for each direction");
    for (const Value& d : body.required("directions").elements("a list of directions"))
      joint.directions.push_back(read_direction(d));
    return joint;
  }
  refuse("directions", "only a joint of type directions lists directions");
  if (type == JointType::kFixed) {
    for (const std::string key : {"axis", "limits_deg", "limits", "stiffness"}) refuse(key, "a fixed joint has none");
    return joint;
  }
  JointDirection d;
  d.kind = type == JointType::kRevolute ? JointDirection::Kind::kRotation : JointDirection::Kind::kTranslation;
  if (auto x = body.get("axis")) d.axis = read_axis(*x);
  if (type == JointType::kRevolute) {
    refuse("limits", "a revolute joint's limits are limits_deg");
    if (auto x = body.get("limits_deg")) read_limits(*x, kLimitDeg, kPi / 180.0, d);
  } else {
    refuse("limits_deg", "a prismatic joint's limits are limits (metres)");
    if (auto x = body.get("limits")) read_limits(*x, kLimitM, 1.0, d);
  }
  if (auto x = body.get("stiffness")) d.stiffness = x->number_in(kStiffness);
  joint.directions.push_back(d);
  return joint;
}

namespace {

void write_vector(YAML::Emitter& out, const Eigen::Vector3d& v) {
  out << YAML::Flow << YAML::BeginSeq << yaml::exact_number(v.x()) << yaml::exact_number(v.y())
      << yaml::exact_number(v.z()) << YAML::EndSeq;
}

bool is_identity(const Pose& pose) { return pose.matrix().isIdentity(0.0); }



/// limits_deg / limits and stiffness of one direction, as far as they are set.
void write_direction_settings(YAML::Emitter& out, const JointDirection& d) {
  const bool rotation = d.kind == JointDirection::Kind::kRotation;
  const double scale = rotation ? 180.0 / kPi : 1.0;
  if (std::isfinite(d.min) || std::isfinite(d.max)) {
    // A file holds finite numbers: an open end is written as the farthest value it may hold.
    const Interval& range = rotation ? kLimitDeg : kLimitM;
    auto bounded = [&](double limit) { return std::clamp(limit * scale, range.min, range.max); };
    out << YAML::Key << (rotation ? "limits_deg" : "limits") << YAML::Value << YAML::Flow << YAML::BeginSeq
        << yaml::exact_number(bounded(d.min)) << yaml::exact_number(bounded(d.max)) << YAML::EndSeq;
  }
  if (d.stiffness != 0.0) out << YAML::Key << "stiffness" << YAML::Value << yaml::exact_number(d.stiffness);
}

}  // namespace

void write_pose(YAML::Emitter& out, const Pose& pose) {
  const Eigen::AngleAxisd rotation(pose.rotation());
  const Eigen::Vector3d r_deg = rotation.axis() * rotation.angle() * (180.0 / kPi);
  const Eigen::Vector3d& t = pose.translation();
  out << YAML::Flow << YAML::BeginMap << YAML::Key << "t" << YAML::Value;
  write_vector(out, t);
  out << YAML::Key << "r_deg" << YAML::Value;
  write_vector(out, r_deg);
  out << YAML::EndMap;
}

void write_joint(YAML::Emitter& out, const Joint& joint) {
  out << YAML::Key << "parent" << YAML::Value << joint.parent;
  if (!is_identity(joint.parent_T_joint)) {
    out << YAML::Key << "origin" << YAML::Value;
    write_pose(out, joint.parent_T_joint);
  }
  if (!is_identity(joint.joint_T_link)) {
    out << YAML::Key << "link_origin" << YAML::Value;
    write_pose(out, joint.joint_T_link);
  }
  out << YAML::Key << "joint" << YAML::Value;
  if (joint.directions.empty()) {
    out << "fixed";
  } else if (joint.directions.size() == 1) {
    const JointDirection& d = joint.directions.front();
    out << (d.kind == JointDirection::Kind::kRotation ? "revolute" : "prismatic");
    out << YAML::Key << "axis" << YAML::Value;
    write_vector(out, d.axis);
    write_direction_settings(out, d);
  } else {
    out << "directions" << YAML::Key << "directions" << YAML::Value << YAML::BeginSeq;
    for (const JointDirection& d : joint.directions) {
      out << YAML::Flow << YAML::BeginMap << YAML::Key
          << (d.kind == JointDirection::Kind::kRotation ? "rotation" : "translation") << YAML::Value;
      write_vector(out, d.axis);
      write_direction_settings(out, d);
      out << YAML::EndMap;
    }
    out << YAML::EndSeq;
  }
}

}  // namespace icgp
