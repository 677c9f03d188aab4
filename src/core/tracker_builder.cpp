// SPDX-License-Identifier: GPL-2.0-or-later
#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "icgp/io/mesh_loader.h"
#include "icgp/model/model_cache.h"
#include "icgp/modality/depth_modality.h"
#include "icgp/modality/region_modality.h"
#include "icgp/modality/texture_modality.h"
#include "icgp/tracker/tracker_config.h"

namespace icgp {
namespace {

/// Region models of a multi-region object: region i's model is generated with every other
/// region as a fixed neighbour of the same body (ALGORITHMS.md §6).
std::vector<ViewpointModel> multi_region_models(const TrackerConfig& config, const std::string& body_name) {
  std::vector<Mesh> regions;
  for (const std::string& file : config.regions) regions.push_back(load_mesh(file));
  std::vector<ViewpointModel> models;
  for (std::size_t i = 0; i < regions.size(); ++i) {
    ModelGenerationOptions options;
    options.name = body_name + "-" + std::filesystem::path(config.regions[i]).stem().string();
    for (std::size_t j = 0; j < regions.size(); ++j)
      if (j != i) options.associated_bodies.push_back({regions[j], Pose(), AssociatedBody::Kind::kFixed});
    models.push_back(
        load_or_generate(ViewpointModel::Kind::kRegion, regions[i], config.region_model, config.cache_dir, options));
  }
  return models;
}

}  // namespace

std::unique_ptr<Tracker> build_tracker(const TrackerConfig& config, const Mesh& mesh, const std::string& body_name) {
  auto uses = [&](const std::string& name) {
    return std::find(config.modalities.begin(), config.modalities.end(), name) != config.modalities.end();
  };
  for (const std::string& name : config.modalities)
    if (name != "region" && name != "depth" && name != "texture")
      throw std::invalid_argument("modality '" + name + "' is not available (available: region, depth, texture)");

  const bool multi_region = uses("region") && !config.regions.empty();
  std::vector<ModelRequest> requests;
  if (uses("region") && !multi_region) requests.push_back({ViewpointModel::Kind::kRegion, config.region_model});
  if (uses("depth")) requests.push_back({ViewpointModel::Kind::kDepth, config.depth_model});
  ModelGenerationOptions options;
  options.name = body_name;
  std::vector<ViewpointModel> models = load_or_generate(mesh, requests, config.cache_dir, options);
  if (multi_region)
    for (ViewpointModel& model : multi_region_models(config, body_name)) models.push_back(std::move(model));

  auto tracker = std::make_unique<Tracker>(config.tracker);
  Body& body = tracker->add_body({body_name, mesh, Pose()});
  for (ViewpointModel& model : models) {
    auto shared = std::make_shared<const ViewpointModel>(std::move(model));
    if (shared->kind() == ViewpointModel::Kind::kRegion)
      tracker->add_modality(std::make_unique<RegionModality>(body, shared, config.region));
    else
      tracker->add_modality(std::make_unique<DepthModality>(body, shared, config.depth));
  }
  if (uses("texture")) tracker->add_modality(std::make_unique<TextureModality>(body, config.texture));
  return tracker;
}

}  // namespace icgp
