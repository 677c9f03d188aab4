// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/tracker/tracker_builder.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "icgp/io/mesh_loader.h"
#include "icgp/model/model_cache.h"
#include "icgp/modality/cue_kind.h"
#include "icgp/modality/depth_modality.h"
#include "icgp/modality/edge_modality.h"
#include "icgp/modality/flow_modality.h"
#include "icgp/modality/region_modality.h"
#include "icgp/modality/texture_modality.h"

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

/// Which cues the configuration and the rig ask for.
struct CueSelection {
  bool region, depth, texture, flow, edge;
  bool depth_alone() const { return depth && !region && !texture && !flow && !edge; }
};

/// Adds the cues of one tracked body: its region model(s) and depth model from the cache
/// (`region_models` given: a multi-region body's), then its texture, flow and edge cues per camera.
void add_cues(Tracker& tracker, Body& body, const TrackerConfig& config, const std::vector<CameraCues>& cameras,
              const CueSelection& cues, std::vector<ViewpointModel> region_models) {
  std::vector<ModelRequest> requests;
  const bool multi_region = !region_models.empty();
  if (cues.region && !multi_region) requests.push_back({ViewpointModel::Kind::kRegion, config.region_model});
  if (cues.depth) requests.push_back({ViewpointModel::Kind::kDepth, config.depth_model});
  ModelGenerationOptions options;
  options.name = body.name;
  std::vector<ViewpointModel> models = load_or_generate(body.mesh, requests, config.cache_dir, options);
  for (ViewpointModel& model : region_models) models.push_back(std::move(model));

  std::vector<std::shared_ptr<const ViewpointModel>> shared;
  for (ViewpointModel& model : models) shared.push_back(std::make_shared<const ViewpointModel>(std::move(model)));
  const RegionModality::Extent extent =
      multi_region ? RegionModality::Extent::kRegionOfBody : RegionModality::Extent::kWholeBody;
  // Depth alone must pin all six degrees of freedom by itself: the body's whole visible
  // surface does that better than the model's sparse points (docs/configuration.md).
  const DepthModality::Sampling depth_sampling = cues.depth_alone() && config.depth.dense.when_only_cue
                                                     ? DepthModality::Sampling::kDense
                                                     : DepthModality::Sampling::kModelPoints;
  // Model by model, then camera by camera: one camera per cue gives the modality order of
  // a single-camera tracker.
  for (const auto& model : shared) {
    for (const CameraCues& camera : cameras) {
      if (model->kind() == ViewpointModel::Kind::kRegion && cues.region && camera.region) {
        RegionParams params = config.region;
        params.color_camera = camera.camera;
        params.depth_camera = camera.occlusion_depth_camera;
        tracker.add_modality(std::make_unique<RegionModality>(body, model, params, extent));
      } else if (model->kind() == ViewpointModel::Kind::kDepth && cues.depth && camera.depth) {
        DepthParams params = config.depth;
        params.depth_camera = camera.camera;
        if (camera.dense_depth_step) {
          params.dense.step_x = camera.dense_depth_step->x;
          params.dense.step_y = camera.dense_depth_step->y;
        }
        tracker.add_modality(std::make_unique<DepthModality>(body, model, params, depth_sampling));
      }
    }
  }
  if (cues.texture)
    for (const CameraCues& camera : cameras) {
      if (!camera.texture) continue;
      TextureParams params = config.texture;
      params.color_camera = camera.camera;
      params.depth_camera = camera.occlusion_depth_camera;
      tracker.add_modality(std::make_unique<TextureModality>(body, params));
    }
  if (cues.flow)
    for (const CameraCues& camera : cameras)
      if (camera.texture)
        tracker.add_modality(
            std::make_unique<FlowModality>(body, config.flow, camera.camera, camera.occlusion_depth_camera));
  if (cues.edge)
    for (const CameraCues& camera : cameras)
      if (camera.region) tracker.add_modality(std::make_unique<EdgeModality>(body, config.edge, camera.camera));
}

/// The mesh of a configured body, with the body named in any error.
Mesh read_body_mesh(const BodyConfig& body, const MeshReader& read_mesh) {
  try {
    return read_mesh(body.mesh, body.scale);
  } catch (const std::exception& e) {
    throw std::runtime_error("body '" + body.name + "': mesh: " + e.what());
  }
}

}  // namespace

std::vector<CameraCues> configured_cameras(const TrackerConfig& config) {
  // The cameras the parameters name: the colour cues' camera, which looks for occlusions
  // in the region cue's depth camera (the texture cue's when region is off), and the depth
  // cue's camera.
  const bool region_on = has_cue(config.modalities, CueKind::kRegion);
  std::vector<CameraCues> cameras;
  auto camera = [&](const std::string& name) -> CameraCues& {
    for (CameraCues& c : cameras)
      if (c.camera == name) return c;
    return cameras.emplace_back(CameraCues{name});
  };
  camera(config.texture.color_camera).occlusion_depth_camera = config.texture.depth_camera;
  camera(config.region.color_camera).occlusion_depth_camera =
      region_on ? config.region.depth_camera : config.texture.depth_camera;
  camera(config.region.color_camera).region = true;  // and the edge cue's
  camera(config.texture.color_camera).texture = true;
  camera(config.depth.depth_camera).depth = true;
  return cameras;
}

std::unique_ptr<Tracker> build_tracker(const TrackerConfig& config, const Mesh& mesh, const std::string& body_name,
                                       const MeshReader& read_mesh) {
  return build_tracker(config, mesh, body_name, configured_cameras(config), nullptr, read_mesh);
}

Mesh read_mesh_file(const std::string& path, double scale) {
  MeshLoadOptions options;
  options.scale = scale;
  return load_mesh(path, options);
}

std::unique_ptr<Tracker> build_tracker(const TrackerConfig& config, const Mesh& mesh, const std::string& body_name,
                                       const std::vector<CameraCues>& cameras,
                                       std::shared_ptr<SceneRenderer> renderer, const MeshReader& read_mesh) {
  validate(config, "tracker configuration");
  const std::vector<const BodyConfig*> others = in_tree_order(config.bodies, body_name);
  auto any_camera = [&](bool CameraCues::*cue) {
    return std::any_of(cameras.begin(), cameras.end(), [cue](const CameraCues& c) { return c.*cue; });
  };
  const CueSelection cues{has_cue(config.modalities, CueKind::kRegion) && any_camera(&CameraCues::region),
                          has_cue(config.modalities, CueKind::kDepth) && any_camera(&CameraCues::depth),
                          has_cue(config.modalities, CueKind::kTexture) && any_camera(&CameraCues::texture),
                          has_cue(config.modalities, CueKind::kFlow) && any_camera(&CameraCues::texture),
                          has_cue(config.modalities, CueKind::kEdge) && any_camera(&CameraCues::region)};

  auto tracker = std::make_unique<Tracker>(config.tracker, std::move(renderer));
  Body& body = tracker->add_body({body_name, mesh, Pose()});
  add_cues(*tracker, body, config, cameras, cues,
           cues.region && !config.regions.empty() ? multi_region_models(config, body_name) : std::vector<ViewpointModel>{});
  for (const BodyConfig* other : others) {
    Body added{other->name, read_body_mesh(*other, read_mesh), Pose()};
    if (other->occluder) {
      tracker->add_occluder(std::move(added));
      continue;
    }
    Body& tracked = other->joint ? tracker->add_link(std::move(added), *other->joint) : tracker->add_body(std::move(added));
    add_cues(*tracker, tracked, config, cameras, cues, {});
  }
  return tracker;
}

}  // namespace icgp
