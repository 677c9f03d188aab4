// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "icgp/modality/modality.h"
#include "icgp/model/viewpoint_model.h"

namespace icgp {

struct TrackerConfig;
struct CameraCues;

/// ViSP's tracker types (vpMbGenericTracker's bits), as the cue registry and CameraCues use
/// them without ViSP: which cameras a cue reads.
namespace visp_type {
inline constexpr int kEdge = 1;         ///< EDGE_TRACKER
inline constexpr int kKlt = 2;          ///< KLT_TRACKER
inline constexpr int kDepthNormal = 4;  ///< DEPTH_NORMAL_TRACKER
inline constexpr int kDepthDense = 8;   ///< DEPTH_DENSE_TRACKER
inline constexpr int kDepth = kDepthNormal | kDepthDense;
}  // namespace visp_type

/// Which of vpMbIcgTracker's counters (getNbFeaturesEdge, getNbFeaturesKlt,
/// getNbFeaturesDepth*) count a cue's correspondences, and which list of
/// getFeaturesForDisplay shows its image features (Modality::append_image_features).
enum class VispFeatures { kNone, kEdge, kKlt, kDepth };

/// What a cue's factory is given to make the cue of one body (and one camera).
struct CueContext {
  Body& body;
  const TrackerConfig& config;
  /// The camera the cue reads; null for a cue that reads none (CueEntry::visp_types 0).
  const CameraCues* camera = nullptr;
  /// The viewpoint model of CueEntry::model; null for a cue that needs none.
  std::shared_ptr<const ViewpointModel> model;
  /// The model is one colour region of the body (TrackerConfig::regions), not the body.
  bool region_of_body = false;
  /// The cue is the only one selected for the body (depth alone samples densely).
  bool only_cue = false;
};

/// One cue of the registry: everything the tracker builder, the camera rigs and
/// vpMbIcgTracker need to know of it.
struct CueEntry {
  /// What TrackerConfig::modalities, YAML files and vpMbIcgTracker::setModalities select it
  /// by; its modalities' Modality::name() must return it.
  std::string name;
  /// The ViSP tracker types of the cameras it reads: a camera with any of these bits gets
  /// one cue per body. 0: each body gets one, reading no camera.
  int visp_types = 0;
  /// Whether it reads the images of its cameras (a camera of such a cue must deliver one).
  bool reads_image = false;
  /// Whether it reads their depth.
  bool reads_depth = false;
  /// The viewpoint model it needs (one cue per model and camera), generated or read from
  /// the cache with the configuration's parameters of that kind; none: one per camera.
  std::optional<ViewpointModel::Kind> model;
  VispFeatures visp_features = VispFeatures::kNone;
  /// Makes the cue. Parameters come from the configuration's section of the cue (the
  /// built-ins' TrackerConfig::region, depth, texture, flow, edge) or from the factory.
  std::function<std::unique_ptr<Modality>(const CueContext&)> make;
};

/// The cues a tracker can be built with: the built-in ones (cue::kRegion, kDepth,
/// kTexture, kFlow, kEdge, in that order) and those a program registers. The builder adds
/// a body's cues in registry order. Not thread-safe to register while others read it:
/// register at start-up.
class CueRegistry {
 public:
  /// The process's registry, with the built-in cues.
  static CueRegistry& instance();

  /// Adds `entry`. Throws std::invalid_argument for an empty or taken name, no factory, or
  /// a cue that reads images or depth but no camera type.
  void add(CueEntry entry);
  /// The cue called `name`; null for none.
  const CueEntry* find(const std::string& name) const;
  /// Whether `name` is one of the built-in cues.
  bool built_in(const std::string& name) const;
  /// The names, in registry order.
  std::vector<std::string> names() const;
  const std::vector<CueEntry>& entries() const { return entries_; }

 private:
  CueRegistry();
  std::vector<CueEntry> entries_;
  std::size_t n_built_in_ = 0;
};

/// "region, depth, texture, flow, edge" and the registered cues' names.
std::string registered_cue_names();
/// Whether `names` is a selection of registered cues: at least one, none twice.
bool valid_cue_list(const std::vector<std::string>& names);
/// `names` when they are a valid selection; throws std::invalid_argument naming the first
/// name that is no cue: "modality 'x' is not available (available: region, ...)", or an
/// empty or repeated selection.
std::vector<std::string> parse_cue_list(const std::vector<std::string>& names);
/// "a non-empty list of distinct names from region, depth, ...", completing "expected …"
/// in the messages of the files that select cues (valid until the next call).
const char* cue_list_expected();

}  // namespace icgp
