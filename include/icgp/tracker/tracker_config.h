// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "icgp/modality/cue_kind.h"
#include "icgp/modality/modality_params.h"
#include "icgp/model/viewpoint_model.h"
#include "icgp/tracker/body_config.h"
#include "icgp/tracker/detection_params.h"
#include "icgp/tracker/tracker.h"

namespace icgp {

/// Everything that configures a tracker, with the reference defaults; a YAML file sets any
/// subset of it (see docs/configuration.md).
struct TrackerConfig {
  std::string preset = "default";  ///< the preset the configuration started from
  TrackerParams tracker;
  /// The cues by name (the cue registry's: cue::kRegion, ... or a registered cue's); ICG+'s
  /// three by default. Texture abstains on objects without texture (too few keyframe
  /// points, ModalityQuality::abstained) and depth where no depth is measured.
  std::vector<std::string> modalities = {cue::kRegion, cue::kDepth, cue::kTexture};
  /// Cues of `modalities` that stand in for ICG+'s: with all three of region, depth and
  /// texture selected, they work only in frames in which no camera delivers depth to the
  /// depth cue (DepthStandIn); with one of the three missing, in every frame. None in icgp's
  /// defaults; vpMbIcgTracker's are flow and edge.
  std::vector<std::string> depth_stand_ins;
  ViewpointModelParams region_model;
  ViewpointModelParams depth_model;
  RegionParams region;
  DepthParams depth;
  TextureParams texture;
  /// The flow cue's parameters (`modalities` names it "flow"; it reads the texture cue's cameras).
  FlowParams flow;
  /// The edge cue's parameters (`modalities` names it "edge"; it reads the region cue's cameras).
  EdgeParams edge;
  /// Multi-region tracking (paper §III-D): one mesh file per colour region of the object,
  /// all in the object's frame; each gets its own region model and modality with its own
  /// colour statistics. Empty: one region modality on the whole object. Relative paths in a
  /// file are relative to that file's folder.
  std::vector<std::string> regions;
  /// Further bodies beside the main one: free bodies, links of kinematic trees (with the
  /// main body or another as the root) and occluders. Each tracked one gets the cues of
  /// `modalities` with these parameters. Relative mesh paths in a file are relative to its folder.
  std::vector<BodyConfig> bodies;
  /// Detection without a given pose and recovery after a loss (docs/detection.md).
  DetectionParams detection;
  /// The parameters of cues a program registered (CueEntry::parameters) that a file or the
  /// program set: cue name -> key -> value. A key not set takes its default (cue_parameter).
  std::map<std::string, std::map<std::string, double>> cue_parameters;
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

/// The keys a configuration file has besides the sections of registered cues: a cue with
/// parameters cannot be named after one.
const std::vector<std::string>& tracker_config_keys();

/// Reads a YAML configuration over `base` (the defaults unless given). Unknown keys and
/// values of the wrong type or range throw std::runtime_error naming the file and the key.
TrackerConfig load_tracker_config(const std::string& path, const TrackerConfig& base = {});
/// Reads a configuration given as YAML text (the keys of a file) over `base`; a `preset`
/// key starts again from that preset. Errors name `source` as they name a file
/// ("<source>: <key>: expected …"); relative mesh paths are resolved against `folder`.
TrackerConfig read_tracker_config(const std::string& yaml_text, const std::string& source, const std::string& folder,
                                  const TrackerConfig& base = {});
/// The configuration as YAML (every key, so `icgp config` can print the defaults).
std::string to_yaml(const TrackerConfig& config);
/// Applies a file's checks (ranges and resource bounds) to a configuration made in code;
/// throws yaml::Error "<source>: <key>: expected …, got …" for the first value out of range.
void validate(const TrackerConfig& config, const std::string& source);

}  // namespace icgp
