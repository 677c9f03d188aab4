// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/tracker/cue_registry.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "icgp/io/yaml_reader.h"
#include "icgp/modality/cue_kind.h"
#include "icgp/modality/depth_modality.h"
#include "icgp/modality/edge_modality.h"
#include "icgp/modality/flow_modality.h"
#include "icgp/modality/region_modality.h"
#include "icgp/modality/texture_modality.h"
#include "icgp/tracker/tracker_builder.h"
#include "icgp/tracker/tracker_config.h"

namespace icgp {
namespace {

std::unique_ptr<Modality> make_region(const CueContext& c) {
  RegionParams params = c.config.region;
  params.color_camera = c.camera->camera;
  params.depth_camera = c.camera->occlusion_depth_camera;
  return std::make_unique<RegionModality>(
      c.body, c.model, params,
      c.region_of_body ? RegionModality::Extent::kRegionOfBody : RegionModality::Extent::kWholeBody);
}

std::unique_ptr<Modality> make_depth(const CueContext& c) {
  DepthParams params = c.config.depth;
  params.depth_camera = c.camera->camera;
  if (c.camera->dense_depth_step) {
    params.dense.step_x = c.camera->dense_depth_step->x;
    params.dense.step_y = c.camera->dense_depth_step->y;
  }
  // Depth alone must pin all six degrees of freedom by itself: the body's whole visible
  // surface does that better than the model's sparse points (docs/configuration.md).
  const DepthModality::Sampling sampling = c.only_cue && c.config.depth.dense.when_only_cue
                                               ? DepthModality::Sampling::kDense
                                               : DepthModality::Sampling::kModelPoints;
  return std::make_unique<DepthModality>(c.body, c.model, params, sampling);
}

std::unique_ptr<Modality> make_texture(const CueContext& c) {
  TextureParams params = c.config.texture;
  params.color_camera = c.camera->camera;
  params.depth_camera = c.camera->occlusion_depth_camera;
  return std::make_unique<TextureModality>(c.body, params);
}

std::unique_ptr<Modality> make_flow(const CueContext& c) {
  return std::make_unique<FlowModality>(c.body, c.config.flow, c.camera->camera, c.camera->occlusion_depth_camera);
}

std::unique_ptr<Modality> make_edge(const CueContext& c) {
  return std::make_unique<EdgeModality>(c.body, c.config.edge, c.camera->camera);
}

}  // namespace

CueRegistry::CueRegistry() {
  // The contour cues read EDGE_TRACKER's cameras, the point cues KLT_TRACKER's, depth the
  // depth types'. The colour cues also read a depth camera's measured occlusions. Their
  // parameters are TrackerConfig's typed sections, not CueEntry::parameters.
  add({cue::kRegion, visp_type::kEdge, true, false, ViewpointModel::Kind::kRegion, VispFeatures::kEdge, {}, make_region});
  add({cue::kDepth, visp_type::kDepth, false, true, ViewpointModel::Kind::kDepth, VispFeatures::kDepth, {}, make_depth});
  add({cue::kTexture, visp_type::kKlt, true, false, std::nullopt, VispFeatures::kKlt, {}, make_texture});
  add({cue::kFlow, visp_type::kKlt, true, false, std::nullopt, VispFeatures::kKlt, {}, make_flow});
  add({cue::kEdge, visp_type::kEdge, true, false, std::nullopt, VispFeatures::kEdge, {}, make_edge});
  n_built_in_ = entries_.size();
}

bool CueRegistry::built_in(const std::string& name) const {
  for (std::size_t i = 0; i < n_built_in_; ++i)
    if (entries_[i].name == name) return true;
  return false;
}

CueRegistry& CueRegistry::instance() {
  static CueRegistry registry;
  return registry;
}

namespace {

/// A cue's parameters become a section of the configuration: its name must be free there,
/// and each key must be one a file can set to its default.
void check_parameters(const CueEntry& entry) {
  if (entry.parameters.empty()) return;
  const std::string cue = "cue registry: cue '" + entry.name + "'";
  const std::vector<std::string>& keys = tracker_config_keys();
  if (std::find(keys.begin(), keys.end(), entry.name) != keys.end())
    throw std::invalid_argument(cue + " has parameters, so its name would be a section of the configuration, "
                                "where '" + entry.name + "' is a key already");
  std::vector<std::string> seen;
  for (const CueParameter& p : entry.parameters) {
    const std::string parameter = cue + ": parameter '" + p.key + "'";
    if (p.key.empty()) throw std::invalid_argument(cue + ": a parameter needs a key");
    if (std::find(seen.begin(), seen.end(), p.key) != seen.end()) throw std::invalid_argument(parameter + " is given twice");
    seen.push_back(p.key);
    if (!std::isfinite(p.min) || !std::isfinite(p.max) || p.min > p.max)
      throw std::invalid_argument(parameter + ": expected finite bounds min <= max");
    if (!p.accepts(p.default_value)) throw std::invalid_argument(parameter + ": its default is outside its range");
  }
}

}  // namespace

void CueRegistry::add(CueEntry entry) {
  if (entry.name.empty()) throw std::invalid_argument("cue registry: a cue needs a name");
  if (find(entry.name)) throw std::invalid_argument("cue registry: a cue named '" + entry.name + "' is registered already");
  if (!entry.make) throw std::invalid_argument("cue registry: cue '" + entry.name + "' has no factory");
  if ((entry.reads_image || entry.reads_depth) && entry.visp_types == 0)
    throw std::invalid_argument("cue registry: cue '" + entry.name +
                                "' reads images or depth but no camera type (visp_types)");
  check_parameters(entry);
  entries_.push_back(std::move(entry));
}

const CueEntry* CueRegistry::find(const std::string& name) const {
  for (const CueEntry& e : entries_)
    if (e.name == name) return &e;
  return nullptr;
}

std::vector<std::string> CueRegistry::names() const {
  std::vector<std::string> names;
  for (const CueEntry& e : entries_) names.push_back(e.name);
  return names;
}

std::string registered_cue_names() {
  std::string names;
  for (const std::string& name : CueRegistry::instance().names()) names += (names.empty() ? "" : ", ") + name;
  return names;
}

bool valid_cue_list(const std::vector<std::string>& names) {
  const std::set<std::string> distinct(names.begin(), names.end());
  const auto known = [](const std::string& name) { return CueRegistry::instance().find(name) != nullptr; };
  return !names.empty() && distinct.size() == names.size() && std::all_of(names.begin(), names.end(), known);
}

std::vector<std::string> parse_cue_list(const std::vector<std::string>& names) {
  for (const std::string& name : names)
    if (!CueRegistry::instance().find(name))
      throw std::invalid_argument("modality '" + name + "' is not available (available: " + registered_cue_names() + ")");
  if (!valid_cue_list(names)) throw std::invalid_argument(std::string("modalities: expected ") + cue_list_expected());
  return names;
}

const char* cue_list_expected() {
  // Rule<T>::expected is a C string; the text follows the registry as cues are added.
  static std::string text;
  text = "a non-empty list of distinct names from " + registered_cue_names();
  return text.c_str();
}

bool CueParameter::accepts(double value) const {
  return yaml::Interval{min, max}.contains(value) && (!integer || value == std::floor(value));
}

std::string CueParameter::expected() const {
  return (integer ? "an integer in " : "a number in ") + yaml::Interval{min, max}.text();
}

const CueParameter* CueEntry::parameter(const std::string& key) const {
  for (const CueParameter& p : parameters)
    if (p.key == key) return &p;
  return nullptr;
}

double cue_parameter(const TrackerConfig& config, const std::string& cue, const std::string& key) {
  const CueEntry* entry = CueRegistry::instance().find(cue);
  const CueParameter* parameter = entry ? entry->parameter(key) : nullptr;
  if (!parameter) throw std::invalid_argument("cue '" + cue + "' has no parameter '" + key + "'");
  const auto given = config.cue_parameters.find(cue);
  if (given != config.cue_parameters.end())
    if (const auto value = given->second.find(key); value != given->second.end()) return value->second;
  return parameter->default_value;
}

}  // namespace icgp
