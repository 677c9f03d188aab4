// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "icgp/geometry/joint.h"

namespace icgp {

/// A body of a configuration's `bodies:` list, beside the tracker's main body (the one the
/// caller names and gives a mesh: a sequence's object, vpMbIcgTracker's cMo). In a file:
///
///   bodies:
///     - name: lid
///       mesh: lid.obj        # relative to the file's folder
///       scale: 1             # metres per mesh unit
///       role: tracked        # tracked (default) | occluder
///       parent: box          # and the other joint keys of icgp/io/joint_yaml.h
///       joint: revolute
///       axis: [1, 0, 0]
///       limits_deg: [0, 110]
struct BodyConfig {
  std::string name;
  std::string mesh;
  double scale = 1.0;
  /// Rendered so that it hides what lies behind it (modeled occlusions), never tracked: its
  /// pose is set by the caller each frame.
  bool occluder = false;
  /// A link of the tree of joint->parent (the main body or another tracked body); none: a
  /// free body.
  std::optional<Joint> joint;
};

/// `bodies` ordered so that every parent comes before its links, checked against the main
/// body's name: throws std::invalid_argument naming the body and the field for a name used
/// twice (the main body's too), a parent that is no tracked body, or a cycle of parents.
std::vector<const BodyConfig*> in_tree_order(const std::vector<BodyConfig>& bodies, const std::string& main_body);

}  // namespace icgp
