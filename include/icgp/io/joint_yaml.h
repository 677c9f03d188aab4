// SPDX-License-Identifier: GPL-2.0-or-later
// The joint of an entry of a `bodies:` list, as tracker configurations, make-sequence
// scenes and sequence.yaml files write it:
//
//   - name: lid
//     parent: box                    # the body it hangs from; no parent: a free body
//     joint: revolute                # revolute | prismatic | fixed | directions
//     axis: [1, 0, 0]                # revolute, prismatic: in the joint frame
//     origin: {t: [0, 0.05, 0.04], r_deg: [0, 0, 0]}      # parent_T_joint
//     link_origin: {t: [0, 0, 0], r_deg: [0, 0, 0]}       # joint_T_link
//     limits_deg: [0, 110]           # revolute; prismatic: limits (metres)
//     stiffness: 0                   # a spring towards 0 (soft constraint)
//     directions:                    # joint: directions, free directions in order
//       - {rotation: [0, 0, 1], limits_deg: [-30, 30], stiffness: 100}
//       - {translation: [1, 0, 0], limits: [-0.01, 0.01]}
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "icgp/geometry/joint.h"
#include "icgp/io/yaml_reader.h"

namespace icgp {

/// The keys of a body entry that describe its joint (parent, joint, axis, ...).
const std::vector<std::string>& joint_keys();

/// The joint of the body entry `body` (a map that may hold joint_keys()); nullopt when it
/// has no `parent`. Errors name the file and the key, e.g.
/// "scene.yaml: bodies.lid.limits_deg: expected min <= max, got [90, 0]".
std::optional<Joint> read_joint(const yaml::Map& body);

/// Writes `joint` as the keys read_joint reads, into the map `out` is writing.
void write_joint(YAML::Emitter& out, const Joint& joint);

/// Writes a pose as {t: [x, y, z], r_deg: [ux, uy, uz]}, the form yaml::pose reads.
void write_pose(YAML::Emitter& out, const Pose& pose);

}  // namespace icgp
