// SPDX-License-Identifier: GPL-2.0-or-later
// The scene files of `icgp make-sequence --scene` (scenes/*.yaml): several bodies, each
// moving on its own or hanging from another by a joint driven along a trajectory.
//
//   bodies:
//     - name: box                       # unique, [A-Za-z0-9_.-] (it names the truth files)
//       mesh: textured_box              # a models/ folder, or a mesh file relative to the scene
//       scale: 1                        # metres per mesh unit
//       pose: {t: [0, 0, 0], r_deg: [0, 0, 0]}   # world_T_object at t = 0
//       velocity: [0, 0, 0]             # m/s, world frame
//       spin: [0, 0, 0]                 # rad/s, a rotation vector in the body's frame
//     - name: lid
//       mesh: hinged_box/lid.obj
//       parent: box                     # a link: the joint keys of io/joint_yaml.h
//       joint: revolute
//       axis: [1, 0, 0]
//       origin: {t: [0, 0.05, -0.03], r_deg: [0, 0, 0]}
//       limits_deg: [0, 110]
//       trajectory: {from_deg: 0, to_deg: 90, period: 6}   # revolute
//       # prismatic: {from: 0, to: 0.02, period: 2} (metres);
//       # directions: a list of those, one per direction
//
// A link has no pose, velocity or spin: its parent and joint place it. The camera orbits
// the world origin (SequenceWriter); the command line sets it.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "icgp/eval/sequence_writer.h"
#include "icgp/geometry/joint.h"
#include "icgp/io/yaml_reader.h"

namespace icgp {

/// One entry of a scene's `bodies:` list.
struct SceneBody {
  std::string name;
  std::string mesh_path;  ///< resolved: an existing file, absolute
  double scale = 1.0;
  Pose world_T_object;
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d spin = Eigen::Vector3d::Zero();
  std::optional<Joint> joint;
  std::vector<JointTrajectory> trajectory;  ///< one per joint direction
  yaml::Location mesh_at;                   ///< where the mesh is named, for load errors
};

/// The bodies of the scene file `path`, parents before their links. Models resolve against
/// `models_dir` (io/model_reference.h). Throws yaml::Error naming the file, the body and the
/// field: two bodies of one name, a parent that does not exist, a cycle of parents, joint
/// limits with min > max, a trajectory outside the limits, and any malformed value.
std::vector<SceneBody> read_sequence_scene(const std::string& path, const std::string& models_dir);

/// Loads each body's mesh (a mesh that cannot be read is a yaml::Error naming the scene
/// file, the body and its mesh) and adds the body to `writer`, as an object or a link.
void add_scene_bodies(SequenceWriter& writer, const std::vector<SceneBody>& bodies);

}  // namespace icgp
