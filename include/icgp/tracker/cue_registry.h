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

/// A number a registered cue takes from its section of a tracker configuration: a file's
/// `<cue name>: {<key>: <value>}`, TrackerConfig::cue_parameters in code. Read, written and
/// checked with the configuration (load_tracker_config, to_yaml, validate); the cue's
/// factory reads it with cue_parameter().
struct CueParameter {
  std::string key;
  double default_value = 0.0;
  /// The numbers it may take, both included and finite: a file's value outside is refused
  /// naming the key and the range.
  double min = 0.0, max = 0.0;
  bool integer = false;  ///< whole numbers only

  /// Whether `value` is one it may take: within [min, max], whole if `integer`.
  bool accepts(double value) const;
  /// What it may take, completing "expected …": "a number in [1e-06, 1]".
  std::string expected() const;
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
  /// The keys of a registered cue's section of a configuration. The built-in cues have
  /// typed sections of their own (TrackerConfig::region, depth, texture, flow, edge).
  std::vector<CueParameter> parameters;
  /// The parameter of `key`; null for none.
  const CueParameter* parameter(const std::string& key) const;
  /// Makes the cue, with the parameters of its section of `CueContext::config`.
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

  /// Adds `entry`. Throws std::invalid_argument for an empty or taken name, no factory, a
  /// cue that reads images or depth but no camera type, or parameters whose section would
  /// take a key of the configuration, repeat a key, or whose default is outside its range.
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

/// The value of parameter `key` of registered cue `cue` in `config`: the configuration's
/// (TrackerConfig::cue_parameters) or the parameter's default. Throws std::invalid_argument
/// when the cue has no such parameter.
double cue_parameter(const TrackerConfig& config, const std::string& cue, const std::string& key);

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
