// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/model/viewpoint_model_generator.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "background_views.h"
#include "generation_progress.h"
#include "icgp/model/model_key.h"
#include "view_job.h"
#include "view_samplers.h"

namespace icgp {
namespace {

bool same_views(const ViewpointModelParams& a, const ViewpointModelParams& b) {
  return a.n_divides == b.n_divides && a.sphere_radius == b.sphere_radius && a.image_size == b.image_size &&
         a.image_margin == b.image_margin;
}

/// Whether a model of this kind is rendered with the associated bodies (region models only).
bool with_associated(ViewpointModel::Kind kind, const ModelGenerationOptions& options) {
  return kind == ViewpointModel::Kind::kRegion && !options.associated_bodies.empty();
}

int hardware_threads() { return std::max(1, static_cast<int>(std::thread::hardware_concurrency())); }

/// Fills every view of a job before returning: each thread takes the next view.
void generate_in_foreground(ViewJob& job) {
  const int wanted = job.options.n_threads > 0 ? job.options.n_threads : hardware_threads();
  const int n_threads = std::min(wanted, job.n_views());
  GenerationProgress progress(job.label(), job.n_views(), job.options.print_progress);
  std::atomic<int> next_view{0};
  std::atomic<bool> failed{false};
  std::mutex error_mutex;
  std::exception_ptr error;
  auto work = [&] {
    try {
      ViewFiller filler(job);
      for (int v = next_view++; v < job.n_views() && !failed; v = next_view++) {
        filler.fill(v);
        progress.view_done();
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      failed = true;
    }
  };
  std::vector<std::thread> threads;
  for (int t = 0; t < n_threads; ++t) threads.emplace_back(work);
  for (auto& t : threads) t.join();
  if (error) std::rethrow_exception(error);
}

/// Starts the background generation of a job's models; `group` maps them to their requests.
std::shared_ptr<ViewSupply> generate_in_background(std::unique_ptr<ViewJob> job, std::vector<std::size_t> group) {
  // One core stays with the program that uses the models.
  const int n_threads = job->options.n_threads > 0 ? job->options.n_threads : std::max(1, hardware_threads() - 1);
  auto on_complete = [group = std::move(group)](const ViewJob& done) {
    if (!done.options.on_complete) return;
    for (std::size_t m = 0; m < group.size(); ++m) done.options.on_complete(group[m], done.models[m]);
  };
  return std::make_shared<BackgroundViews>(std::move(job), n_threads, std::move(on_complete));
}

}  // namespace

std::string to_string(ViewpointModel::Kind kind) { return kind == ViewpointModel::Kind::kRegion ? "region" : "depth"; }

ViewCamera view_camera(const Eigen::Vector3f& direction, const ViewpointModelParams& params, double body_radius) {
  const double R = params.sphere_radius, r = body_radius;
  if (!(r > 0.0)) throw std::invalid_argument("viewpoint model: the mesh has no extent about its origin");
  if (!(R > r))
    throw std::invalid_argument("viewpoint model: sphere_radius " + std::to_string(R) +
                                " m must exceed the mesh's radius about its origin, " + std::to_string(r) + " m");
  // The sphere's outline spans f·r/sqrt(R² − r²) pixels from the image centre: make that the
  // half image (pixel edges at ±size/2 around the centre) minus the margin.
  const double half_extent = params.image_size / 2.0 - params.image_margin;
  ViewCamera camera;
  camera.intrinsics =
      Intrinsics::centred(params.image_size, params.image_size, half_extent * std::sqrt(R * R - r * r) / r);
  const Eigen::Vector3d d = direction.cast<double>().normalized();
  const Eigen::Vector3d up = std::abs(d.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
  camera.camera_T_body = look_at<double>(R * d, Eigen::Vector3d::Zero(), up);
  return camera;
}

std::vector<ViewpointModel> generate_viewpoint_models(const Mesh& mesh, const std::vector<ModelRequest>& requests,
                                                      const ModelGenerationOptions& options) {
  std::vector<ViewpointModel> models;
  models.reserve(requests.size());
  for (const ModelRequest& r : requests) {
    r.params.validate();
    view_camera(Eigen::Vector3f::UnitZ(), r.params, mesh.radius_about_origin());  // throws for a bad sphere
    models.emplace_back(r.kind, r.params, viewpoint_model_key(r.kind, mesh, r.params, options.associated_bodies));
  }
  for (const AssociatedBody& body : options.associated_bodies)
    region_render_id(body);  // throws for an unknown kind
  std::vector<bool> done(models.size(), false);
  for (std::size_t i = 0; i < models.size(); ++i) {
    if (done[i]) continue;
    std::vector<std::size_t> group;
    for (std::size_t j = i; j < models.size(); ++j)
      if (!done[j] && same_views(models[i].params(), models[j].params()) &&
          with_associated(models[i].kind(), options) == with_associated(models[j].kind(), options)) {
        group.push_back(j);
        done[j] = true;
      }
    // The job's models are copies sharing the arrays of those returned.
    std::vector<ViewpointModel> job_models;
    for (const std::size_t j : group) job_models.push_back(models[j]);
    auto job = std::make_unique<ViewJob>(mesh, std::move(job_models), options,
                                         with_associated(models[i].kind(), options));
    if (!options.in_background) {
      generate_in_foreground(*job);
      continue;
    }
    const std::shared_ptr<ViewSupply> supply = generate_in_background(std::move(job), group);
    for (const std::size_t j : group) models[j].set_supply(supply);
  }
  return models;
}

ViewpointModel generate_viewpoint_model(ViewpointModel::Kind kind, const Mesh& mesh, const ViewpointModelParams& params,
                                        const ModelGenerationOptions& options) {
  return std::move(generate_viewpoint_models(mesh, {{kind, params}}, options).front());
}

}  // namespace icgp
