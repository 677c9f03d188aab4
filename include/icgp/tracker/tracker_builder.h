// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "icgp/base/mesh.h"
#include "icgp/render/scene_renderer.h"
#include "icgp/tracker/tracker.h"
#include "icgp/tracker/tracker_config.h"

namespace icgp {

/// One camera of a rig and the cues that read it. The colour cues (region, texture) test
/// their lines and keypoints for measured occlusion in `occlusion_depth_camera`'s depth
/// (empty: none).
struct CameraCues {
  std::string camera;
  bool region = false;
  bool texture = false;
  bool depth = false;
  std::string occlusion_depth_camera;
};

/// A tracker for one body with the configured modalities. Viewpoint models come from the
/// cache (config.cache_dir), generated with progress output on first use. The body starts
/// at the identity pose: set tracker.body(body_name).reference_T_body, then start().
std::unique_ptr<Tracker> build_tracker(const TrackerConfig& config, const Mesh& mesh, const std::string& body_name);
/// The same for a rig of cameras: each camera gets the cues it names (those of
/// config.modalities only), all fused in one Newton step per update. The viewpoint models
/// are the object's, shared by every camera. `renderer`: the one the tracker renders with
/// (null: its own).
std::unique_ptr<Tracker> build_tracker(const TrackerConfig& config, const Mesh& mesh, const std::string& body_name,
                                       const std::vector<CameraCues>& cameras,
                                       std::shared_ptr<SceneRenderer> renderer = nullptr);

}  // namespace icgp
