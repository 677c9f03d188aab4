// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/model/viewpoint_model_generator.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "icgp/base/stop_request.h"
#include "icgp/model/icosphere.h"
#include "icgp/model/model_key.h"
#include "icgp/render/renderer.h"
#include "inverse_depth_pyramid.h"
#include "mesh_face_locator.h"
#include "view_samplers.h"

namespace icgp {
namespace {

constexpr std::uint8_t kMainBodyId = kMainRegionId;

bool same_views(const ViewpointModelParams& a, const ViewpointModelParams& b) {
  return a.n_divides == b.n_divides && a.sphere_radius == b.sphere_radius && a.image_size == b.image_size &&
         a.image_margin == b.image_margin;
}

/// Whether a model of this kind is rendered with the associated bodies (region models only).
bool with_associated(ViewpointModel::Kind kind, const ModelGenerationOptions& options) {
  return kind == ViewpointModel::Kind::kRegion && !options.associated_bodies.empty();
}

/// "region+depth model textured_box: 1024/2562 views, 12 s" on stderr every few seconds.
class Progress {
 public:
  Progress(std::string label, int n_views, bool enabled)
      : label_(std::move(label)), n_views_(n_views), enabled_(enabled), start_(Clock::now()), last_print_(start_) {}

  void view_done() {
    const int done = ++done_;
    if (!enabled_) return;
    const auto now = Clock::now();
    std::lock_guard<std::mutex> lock(mutex_);
    if (done < n_views_ && now - last_print_ < kInterval) return;
    last_print_ = now;
    std::ostringstream line;  // one write, so lines of concurrent generations do not interleave
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    line << label_ << ": " << done << "/" << n_views_ << " views, " << std::fixed << std::setprecision(1) << elapsed
         << " s";
    if (done < n_views_) line << ", about " << elapsed / done * (n_views_ - done) << " s left";
    line << "\n";
    std::cerr << line.str() << std::flush;
  }

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::seconds kInterval{3};
  const std::string label_;
  const int n_views_;
  const bool enabled_;
  const Clock::time_point start_;
  std::atomic<int> done_{0};
  std::mutex mutex_;
  Clock::time_point last_print_;
};

/// Generates the models that share views: every thread renders views with its own renderer
/// and fills them into all models. Results land at their view index, so they do not depend
/// on which thread did what.
class SharedViewsGeneration {
 public:
  SharedViewsGeneration(const Mesh& mesh, std::vector<ViewpointModel*> models, const ModelGenerationOptions& options,
                        bool with_associated_bodies)
      : mesh_(mesh),
        models_(std::move(models)),
        options_(options),
        with_associated_bodies_(with_associated_bodies),
        params_(models_.front()->params()),
        body_radius_(mesh.radius_about_origin()),
        directions_(icosphere_directions(params_.n_divides)) {
    // Only depth models need face normals.
    for (const ViewpointModel* m : models_)
      if (m->kind() == ViewpointModel::Kind::kDepth && !faces_) faces_.emplace(mesh);
  }

  void run() {
    const int hardware = static_cast<int>(std::thread::hardware_concurrency());
    const int wanted = options_.n_threads > 0 ? options_.n_threads : std::max(1, hardware);
    const int n_threads = std::min(wanted, static_cast<int>(directions_.size()));
    Progress progress(label(), static_cast<int>(directions_.size()), options_.print_progress);
    std::vector<std::thread> threads;
    for (int t = 0; t < n_threads; ++t) threads.emplace_back([this, &progress] { work(progress); });
    for (auto& t : threads) t.join();
    if (error_) std::rethrow_exception(error_);
  }

 private:
  std::string label() const {
    std::string kinds;
    for (const ViewpointModel* m : models_) kinds += (kinds.empty() ? "" : "+") + to_string(m->kind());
    std::string name = options_.name;
    if (name.empty()) name = std::filesystem::path(mesh_.source).stem().string();
    return kinds + " model " + (name.empty() ? std::string("mesh") : name);
  }

  void work(Progress& progress) {
    try {
      Renderer renderer;
      renderer.add_body(mesh_, kMainBodyId);
      if (with_associated_bodies_)
        for (const AssociatedBody& body : options_.associated_bodies)
          renderer.set_body_pose(renderer.add_body(body.mesh, region_render_id(body)), body.main_T_body);
      std::vector<std::unique_ptr<ViewSampler>> samplers;
      // Depth offsets of radius r are read r·f/Z pixels wide, Z at most sphere_radius + body radius.
      double smallest_offset_radius = std::numeric_limits<double>::infinity();
      for (const ViewpointModel* m : models_) {
        samplers.push_back(make_view_sampler(m->kind(), m->params()));
        if (m->n_depth_offsets() > 0)
          smallest_offset_radius = std::min(smallest_offset_radius, m->params().stride_depth_offset);
      }
      const bool need_offsets = std::isfinite(smallest_offset_radius);
      const float smallest_offset_px =
          static_cast<float>(smallest_offset_radius * view_camera(directions_[0], params_, body_radius_).intrinsics.fu /
                             (params_.sphere_radius + body_radius_));
      SilhouetteImages images;
      InverseDepthPyramid pyramid;
      for (int v = next_view_++; v < static_cast<int>(directions_.size()) && !failed_; v = next_view_++) {
        // A model is written whole or not at all, so stopping drops this generation only.
        if (stop_requested()) throw StopRequested("stopped on request while generating the " + label());
        RenderedView view;
        view.index = v;
        view.direction = directions_[v];
        view.camera = view_camera(directions_[v], params_, body_radius_);
        view.body_T_camera = view.camera.camera_T_body.inverse();
        renderer.render_silhouette(view.camera.intrinsics, view.camera.camera_T_body, images);
        if (need_offsets) pyramid.build(images.inverse_depth, images.footprint, smallest_offset_px);
        view.images = &images;
        view.pyramid = &pyramid;
        view.faces = faces_ ? &*faces_ : nullptr;
        view.body_id = kMainBodyId;
        view.with_associated_bodies = with_associated_bodies_;
        for (std::size_t i = 0; i < models_.size(); ++i) samplers[i]->sample(view, *models_[i]);
        progress.view_done();
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex_);
      if (!error_) error_ = std::current_exception();
      failed_ = true;
    }
  }

  const Mesh& mesh_;
  const std::vector<ViewpointModel*> models_;
  const ModelGenerationOptions& options_;
  const bool with_associated_bodies_;  ///< render options_.associated_bodies too
  const ViewpointModelParams params_;  ///< the view parameters all models share
  const double body_radius_;
  const std::vector<Eigen::Vector3f> directions_;
  std::optional<MeshFaceLocator> faces_;
  std::atomic<int> next_view_{0};
  std::atomic<bool> failed_{false};
  std::mutex error_mutex_;
  std::exception_ptr error_;
};

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
    std::vector<ViewpointModel*> group;
    for (std::size_t j = i; j < models.size(); ++j)
      if (!done[j] && same_views(models[i].params(), models[j].params()) &&
          with_associated(models[i].kind(), options) == with_associated(models[j].kind(), options)) {
        group.push_back(&models[j]);
        done[j] = true;
      }
    SharedViewsGeneration(mesh, std::move(group), options, with_associated(models[i].kind(), options)).run();
  }
  return models;
}

ViewpointModel generate_viewpoint_model(ViewpointModel::Kind kind, const Mesh& mesh, const ViewpointModelParams& params,
                                        const ModelGenerationOptions& options) {
  return std::move(generate_viewpoint_models(mesh, {{kind, params}}, options).front());
}

}  // namespace icgp
