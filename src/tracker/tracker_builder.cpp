// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/tracker/tracker_builder.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "icgp/io/mesh_loader.h"
#include "icgp/model/model_cache.h"
#include "icgp/modality/cue_kind.h"
#include "icgp/modality/depth_stand_in.h"

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
    options.in_background = true;
    options.name = body_name + "-" + std::filesystem::path(config.regions[i]).stem().string();
    for (std::size_t j = 0; j < regions.size(); ++j)
      if (j != i) options.associated_bodies.push_back({regions[j], Pose(), AssociatedBody::Kind::kFixed});
    models.push_back(
        load_or_generate(ViewpointModel::Kind::kRegion, regions[i], config.region_model, config.cache_dir, options));
  }
  return models;
}

/// The registered cues of `config.modalities` that read a camera of the rig (or none),
/// in registry order.
std::vector<const CueEntry*> selected_cues(const TrackerConfig& config, const std::vector<CameraCues>& cameras) {
  std::vector<const CueEntry*> cues;
  for (const CueEntry& entry : CueRegistry::instance().entries()) {
    if (!has_cue(config.modalities, entry.name)) continue;
    const bool read = entry.visp_types == 0 ||
                      std::any_of(cameras.begin(), cameras.end(), [&](const CameraCues& c) { return c.reads(entry); });
    if (read) cues.push_back(&entry);
  }
  return cues;
}

/// The cameras whose depth images the depth cue among `cues` reads, when `cues` hold all
/// three of ICG+'s (region, depth, texture); none otherwise: the stand-ins then work in
/// every frame, since what they make up for is a cue of the three missing as much as depth.
std::vector<std::string> stand_in_depth_cameras(const std::vector<const CueEntry*>& cues,
                                                const std::vector<CameraCues>& cameras) {
  const auto selected = [&](const char* name) {
    return std::any_of(cues.begin(), cues.end(), [&](const CueEntry* c) { return c->name == name; });
  };
  std::vector<std::string> names;
  if (!selected(cue::kRegion) || !selected(cue::kTexture)) return names;
  for (const CueEntry* cue : cues)
    if (cue->name == cue::kDepth)
      for (const CameraCues& camera : cameras)
        if (camera.reads(*cue)) names.push_back(camera.camera);
  return names;
}

/// The configuration's parameters of a viewpoint model kind.
const ViewpointModelParams& model_params(const TrackerConfig& config, ViewpointModel::Kind kind) {
  return kind == ViewpointModel::Kind::kRegion ? config.region_model : config.depth_model;
}

/// Adds the cues of one tracked body, cue by cue in registry order; a cue with a viewpoint
/// model gets one modality per model and camera, the others one per camera (or one, when
/// they read none). The models come from the cache; `region_models` given: a multi-region
/// body's region models.
void add_cues(Tracker& tracker, Body& body, const TrackerConfig& config, const std::vector<CameraCues>& cameras,
              const std::vector<const CueEntry*>& cues, std::vector<ViewpointModel> region_models) {
  const bool multi_region = !region_models.empty();
  std::vector<ModelRequest> requests;
  // One model of each kind, whichever cues read it.
  for (const CueEntry* cue : cues) {
    if (!cue->model || (multi_region && *cue->model == ViewpointModel::Kind::kRegion)) continue;
    const auto same_kind = [&](const ModelRequest& r) { return r.kind == *cue->model; };
    if (std::none_of(requests.begin(), requests.end(), same_kind))
      requests.push_back({*cue->model, model_params(config, *cue->model)});
  }
  // A tracker starts on the views it needs while the rest are made (and then cached).
  ModelGenerationOptions options;
  options.in_background = true;
  options.name = body.name;
  std::vector<ViewpointModel> models = load_or_generate(body.mesh, requests, config.cache_dir, options);
  for (ViewpointModel& model : region_models) models.push_back(std::move(model));
  std::vector<std::shared_ptr<const ViewpointModel>> shared;
  for (ViewpointModel& model : models) shared.push_back(std::make_shared<const ViewpointModel>(std::move(model)));

  const std::vector<std::string> depth_cameras = stand_in_depth_cameras(cues, cameras);
  for (const CueEntry* cue : cues) {
    CueContext context{body, config};
    context.only_cue = cues.size() == 1;
    const bool stand_in = has_cue(config.depth_stand_ins, cue->name) && !depth_cameras.empty();
    const auto add = [&] {
      std::unique_ptr<Modality> made = cue->make(context);
      tracker.add_modality(stand_in ? std::make_unique<DepthStandIn>(std::move(made), depth_cameras) : std::move(made));
    };
    const auto add_per_camera = [&] {
      if (cue->visp_types == 0) {
        add();
        return;
      }
      for (const CameraCues& camera : cameras)
        if (camera.reads(*cue)) {
          context.camera = &camera;
          add();
        }
    };
    if (!cue->model) {
      add_per_camera();
      continue;
    }
    for (const auto& model : shared)
      if (model->kind() == *cue->model) {
        context.model = model;
        context.region_of_body = multi_region && model->kind() == ViewpointModel::Kind::kRegion;
        add_per_camera();
      }
  }
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

bool CameraCues::reads_image(const std::vector<std::string>& modalities) const {
  for (const std::string& name : modalities)
    if (const CueEntry* cue = CueRegistry::instance().find(name); cue && cue->reads_image && reads(*cue)) return true;
  return false;
}

bool CameraCues::reads_depth(const std::vector<std::string>& modalities) const {
  for (const std::string& name : modalities)
    if (const CueEntry* cue = CueRegistry::instance().find(name); cue && cue->reads_depth && reads(*cue)) return true;
  return false;
}

std::vector<CameraCues> configured_cameras(const TrackerConfig& config) {
  // The cameras the parameters name: the colour cues' camera, which looks for occlusions
  // in the region cue's depth camera (the texture cue's when region is off), and the depth
  // cue's camera.
  const bool region_on = has_cue(config.modalities, cue::kRegion);
  std::vector<CameraCues> cameras;
  auto camera = [&](const std::string& name) -> CameraCues& {
    for (CameraCues& c : cameras)
      if (c.camera == name) return c;
    return cameras.emplace_back(CameraCues{name});
  };
  camera(config.texture.color_camera).occlusion_depth_camera = config.texture.depth_camera;
  camera(config.region.color_camera).occlusion_depth_camera =
      region_on ? config.region.depth_camera : config.texture.depth_camera;
  camera(config.region.color_camera).types |= visp_type::kEdge;
  camera(config.texture.color_camera).types |= visp_type::kKlt;
  camera(config.depth.depth_camera).types |= visp_type::kDepthDense;
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
  const std::vector<const CueEntry*> cues = selected_cues(config, cameras);
  const bool region = std::any_of(cues.begin(), cues.end(), [](const CueEntry* c) { return c->name == cue::kRegion; });

  auto tracker = std::make_unique<Tracker>(config.tracker, std::move(renderer));
  Body& body = tracker->add_body({body_name, mesh, Pose()});
  add_cues(*tracker, body, config, cameras, cues,
           region && !config.regions.empty() ? multi_region_models(config, body_name) : std::vector<ViewpointModel>{});
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
