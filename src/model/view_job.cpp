// SPDX-License-Identifier: GPL-2.0-or-later
#include "view_job.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "icgp/base/stop_request.h"
#include "icgp/model/icosphere.h"
#include "stored_model.h"

namespace icgp {
namespace {

constexpr std::uint8_t kMainBodyId = kMainRegionId;

}  // namespace

ViewJob::ViewJob(const Mesh& mesh_, std::vector<ViewpointModel> models_, const ModelGenerationOptions& options_,
                 bool with_associated_bodies_)
    : mesh(mesh_),
      models(std::move(models_)),
      options(options_),
      with_associated_bodies(with_associated_bodies_),
      params(models.front().params()),
      body_radius(mesh.radius_about_origin()),
      directions(icosphere_directions(params.n_divides)) {
  for (const ViewpointModel& m : models)
    if (m.kind() == ViewpointModel::Kind::kDepth && !faces) faces.emplace(mesh);
}

std::string ViewJob::label() const {
  std::string kinds;
  for (const ViewpointModel& m : models) kinds += (kinds.empty() ? "" : "+") + to_string(m.kind());
  std::string name = options.name;
  if (name.empty()) name = std::filesystem::path(mesh.source).stem().string();
  return kinds + " model " + (name.empty() ? std::string("mesh") : name);
}

ViewFiller::ViewFiller(ViewJob& job) : job_(job) {
  renderer_.add_body(job.mesh, kMainBodyId);
  if (job.with_associated_bodies)
    for (const AssociatedBody& body : job.options.associated_bodies)
      renderer_.set_body_pose(renderer_.add_body(body.mesh, region_render_id(body)), body.main_T_body);
  // Depth offsets of radius r are read r·f/Z pixels wide, Z at most sphere_radius + body radius.
  double smallest_offset_radius = std::numeric_limits<double>::infinity();
  for (const ViewpointModel& m : job.models) {
    samplers_.push_back(make_view_sampler(m.kind(), m.params()));
    if (m.n_depth_offsets() > 0) smallest_offset_radius = std::min(smallest_offset_radius, m.params().stride_depth_offset);
  }
  need_offsets_ = std::isfinite(smallest_offset_radius);
  smallest_offset_px_ = static_cast<float>(
      smallest_offset_radius * view_camera(job.directions[0], job.params, job.body_radius).intrinsics.fu /
      (job.params.sphere_radius + job.body_radius));
}

void ViewFiller::fill(int v) {
  // A model is written whole or not at all, so stopping drops this generation only.
  if (stop_requested()) throw StopRequested("stopped on request while generating the " + job_.label());
  RenderedView view;
  view.index = v;
  view.direction = job_.directions[v];
  view.camera = view_camera(job_.directions[v], job_.params, job_.body_radius);
  view.body_T_camera = view.camera.camera_T_body.inverse();
  renderer_.render_silhouette(view.camera.intrinsics, view.camera.camera_T_body, images_);
  if (need_offsets_) pyramid_.build(images_.inverse_depth, images_.footprint, smallest_offset_px_);
  view.images = &images_;
  view.pyramid = &pyramid_;
  view.faces = job_.faces ? &*job_.faces : nullptr;
  view.body_id = kMainBodyId;
  view.with_associated_bodies = job_.with_associated_bodies;
  for (std::size_t i = 0; i < job_.models.size(); ++i) {
    samplers_[i]->sample(view, job_.models[i]);
    quantise_view(job_.models[i], v);  // to what its cache file keeps
  }
}

}  // namespace icgp
