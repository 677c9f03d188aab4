// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "icgp/base/mesh.h"
#include "icgp/render/scene_renderer.h"
#include "icgp/tracker/tracker.h"
#include "icgp/tracker/tracker_config.h"

namespace icgp {

/// One camera of a rig and the cues that read it. The colour cues (region, texture, flow)
/// test their lines and points for measured occlusion in `occlusion_depth_camera`'s depth
/// (empty: none). `region` marks the camera of the contour cues: region and edge (ViSP's
/// EDGE_TRACKER); `texture` that of the point cues: texture and flow (ViSP's KLT_TRACKER),
/// as the configuration selects them.
struct CameraCues {
  std::string camera;
  bool region = false;
  bool texture = false;
  bool depth = false;
  std::string occlusion_depth_camera;
  /// The sampling step of this camera's dense depth (ViSP's setDepthDenseSamplingStep),
  /// over the configuration's depth.dense step; none: the configuration's.
  std::optional<SamplingStep> dense_depth_step;
};

/// Reads the mesh of a configured body (BodyConfig): file and metres per unit.
using MeshReader = std::function<Mesh(const std::string& path, double scale)>;
/// The core's MeshReader: load_mesh (the formats assimp reads).
Mesh read_mesh_file(const std::string& path, double scale);

/// The cameras the configuration's cue parameters name (region.color_camera,
/// texture.color_camera, depth.depth_camera) and the cues each one reads.
std::vector<CameraCues> configured_cameras(const TrackerConfig& config);

/// A tracker for the main body `body_name` and the configuration's other bodies
/// (config.bodies, meshes read by `read_mesh`), each tracked one with the configured
/// modalities. Viewpoint models come from the cache (config.cache_dir), generated with
/// progress output on first use. Bodies start at the identity pose and links at joint
/// values 0: set the free bodies' reference_T_body and the joint values, then start().
/// Errors name the body and the field (in_tree_order, validate(Joint&)).
/// Its cameras are configured_cameras(config).
std::unique_ptr<Tracker> build_tracker(const TrackerConfig& config, const Mesh& mesh, const std::string& body_name,
                                       const MeshReader& read_mesh = read_mesh_file);
/// The same for a rig of cameras: each camera gets the cues it names (those of
/// config.modalities only), all fused in one Newton step per update. The viewpoint models
/// are the object's, shared by every camera. `renderer`: the one the tracker renders with
/// (null: its own).
std::unique_ptr<Tracker> build_tracker(const TrackerConfig& config, const Mesh& mesh, const std::string& body_name,
                                       const std::vector<CameraCues>& cameras,
                                       std::shared_ptr<SceneRenderer> renderer = nullptr,
                                       const MeshReader& read_mesh = read_mesh_file);

}  // namespace icgp
