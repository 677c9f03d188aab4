// SPDX-License-Identifier: GPL-2.0-or-later
#include <algorithm>
#include <stdexcept>

#include "icgp/model/model_cache.h"
#include "icgp/modality/depth_modality.h"
#include "icgp/modality/region_modality.h"
#include "icgp/modality/texture_modality.h"
#include "icgp/tracker/tracker_config.h"

namespace icgp {

std::unique_ptr<Tracker> build_tracker(const TrackerConfig& config, const Mesh& mesh, const std::string& body_name) {
  auto uses = [&](const std::string& name) {
    return std::find(config.modalities.begin(), config.modalities.end(), name) != config.modalities.end();
  };
  for (const std::string& name : config.modalities)
    if (name != "region" && name != "depth" && name != "texture")
      throw std::invalid_argument("modality '" + name + "' is not available (available: region, depth, texture)");

  std::vector<ModelRequest> requests;
  if (uses("region")) requests.push_back({ViewpointModel::Kind::kRegion, config.region_model});
  if (uses("depth")) requests.push_back({ViewpointModel::Kind::kDepth, config.depth_model});
  ModelGenerationOptions options;
  options.name = body_name;
  std::vector<ViewpointModel> models = load_or_generate(mesh, requests, config.cache_dir, options);

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
