// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "icgp/base/mesh.h"
#include "icgp/render/scene_renderer.h"
#include "icgp/tracker/cue_registry.h"
#include "icgp/tracker/tracker.h"
#include "icgp/tracker/tracker_config.h"

namespace icgp {

/// One camera of a rig and the cues that read it: those of the selected modalities whose
/// ViSP tracker types (CueEntry::visp_types) the camera has. The colour cues test their
/// lines and points for measured occlusion in `occlusion_depth_camera`'s depth (empty:
/// none).
struct CameraCues {
  std::string camera;
  int types = 0;  ///< ViSP tracker types (visp_type::kEdge, ...)
  std::string occlusion_depth_camera;
  /// The sampling step of this camera's dense depth (ViSP's setDepthDenseSamplingStep),
  /// over the configuration's depth.dense step; none: the configuration's.
  std::optional<SamplingStep> dense_depth_step;

  /// Whether `cue` reads this camera.
  bool reads(const CueEntry& cue) const { return (types & cue.visp_types) != 0; }
  /// Whether a cue of `modalities` reads this camera's image / its depth.
  bool reads_image(const std::vector<std::string>& modalities) const;
  bool reads_depth(const std::vector<std::string>& modalities) const;
};

/// Reads the mesh of a configured body (BodyConfig): file and metres per unit.
using MeshReader = std::function<Mesh(const std::string& path, double scale)>;
/// The core's MeshReader: load_mesh (the formats assimp reads).
Mesh read_mesh_file(const std::string& path, double scale);

/// The cameras the configuration's cue parameters name and the cues each one reads:
/// region.color_camera the contour cues' (EDGE_TRACKER), texture.color_camera the point
/// cues' (KLT_TRACKER), depth.depth_camera the depth cue's (DEPTH_DENSE_TRACKER).
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
