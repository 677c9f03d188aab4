// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "icgp/modality/modality_params.h"
#include "icgp/model/viewpoint_model.h"
#include "icgp/tracker/tracker.h"

namespace icgp {

/// Everything that configures a tracker, with the reference defaults; a YAML file sets any
/// subset of it (see docs/configuration.md).
struct TrackerConfig {
  std::string preset = "default";  ///< the preset the configuration started from
  TrackerParams tracker;
  /// ICG+'s three cues. Texture abstains on objects without texture (too few keyframe
  /// points, ModalityQuality::abstained) and depth where no depth is measured.
  std::vector<std::string> modalities = {"region", "depth", "texture"};
  ViewpointModelParams region_model;
  ViewpointModelParams depth_model;
  RegionParams region;
  DepthParams depth;
  TextureParams texture;
  /// Multi-region tracking (paper §III-D): one mesh file per colour region of the object,
  /// all in the object's frame; each gets its own region model and modality with its own
  /// colour statistics. Empty: one region modality on the whole object. Relative paths in a
  /// file are relative to that file's folder.
  std::vector<std::string> regions;
  std::string cache_dir;  ///< empty: $ICGP_CACHE_DIR, else $XDG_CACHE_HOME/icgp, else ~/.cache/icgp
};

/// Named starting points of a configuration; a YAML file's `preset:` key picks one and its
/// other keys are read over it.
///  * "default": icgp's defaults, the reference parameters of ALGORITHMS.md with every
///    cue's noise estimated online from its residuals (the `noise` keys).
///  * "icg_reference": the reference parameters with fixed noise schedules, the discrete
///    contour posterior and OpenCV's ORB: the ICG/ICG+ papers' behaviour.
/// Throws std::invalid_argument naming an unknown preset and the known ones.
TrackerConfig tracker_config_preset(const std::string& name);
/// The preset names tracker_config_preset() knows, "default" first.
const std::vector<std::string>& tracker_config_presets();

/// Reads a YAML configuration over the defaults. Unknown keys and values of the wrong type
/// or range throw std::runtime_error naming the file and the key.
TrackerConfig load_tracker_config(const std::string& path);
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
/// Throws std::invalid_argument for an unknown or unavailable modality name.
std::unique_ptr<Tracker> build_tracker(const TrackerConfig& config, const Mesh& mesh, const std::string& body_name);
/// The same for a rig of cameras: each camera gets the cues it names (those of
/// config.modalities only), all fused in one Newton step per update. The viewpoint models
/// are the object's, shared by every camera. `renderer`: the one the tracker renders with
/// (null: its own).
std::unique_ptr<Tracker> build_tracker(const TrackerConfig& config, const Mesh& mesh, const std::string& body_name,
                                       const std::vector<CameraCues>& cameras,
                                       std::shared_ptr<SceneRenderer> renderer = nullptr);

/// The configuration as YAML (every key, so `icgp config` can print the defaults).
std::string to_yaml(const TrackerConfig& config);

}  // namespace icgp
