// SPDX-License-Identifier: GPL-2.0-or-later
// Private to model generation: the views of one generation, and the per-thread work of
// rendering one view and sampling it into every model.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "icgp/base/mesh.h"
#include "icgp/model/viewpoint_model.h"
#include "icgp/model/viewpoint_model_generator.h"
#include "icgp/render/renderer.h"
#include "inverse_depth_pyramid.h"
#include "mesh_face_locator.h"
#include "view_samplers.h"

namespace icgp {

/// Models that see the same views (equal n_divides, sphere_radius, image_size and
/// image_margin, and the same bodies rendered), with what every thread filling them
/// shares. The models are the caller's: copies sharing their arrays, so the threads write
/// straight into them, each view by one thread.
struct ViewJob {
  ViewJob(const Mesh& mesh, std::vector<ViewpointModel> models, const ModelGenerationOptions& options,
          bool with_associated_bodies);

  /// "region+depth model textured_box", for progress lines and errors.
  std::string label() const;
  int n_views() const { return static_cast<int>(directions.size()); }

  const Mesh mesh;
  std::vector<ViewpointModel> models;
  const ModelGenerationOptions options;
  const bool with_associated_bodies;  ///< render options.associated_bodies too
  const ViewpointModelParams params;  ///< the view parameters all models share
  const double body_radius;
  const std::vector<Eigen::Vector3f> directions;
  std::optional<MeshFaceLocator> faces;  ///< only depth models need face normals
};

/// One thread's renderer (with its own OpenGL context), samplers and buffers: renders a
/// view of the job and writes it into all of its models. Views land at their index and
/// depend on nothing but it, so which thread fills which view changes no byte.
class ViewFiller {
 public:
  /// Throws RenderError when no headless OpenGL context can be created.
  explicit ViewFiller(ViewJob& job);

  /// Throws StopRequested when a stop was requested (the view is then not written).
  void fill(int view);

 private:
  ViewJob& job_;
  Renderer renderer_;
  std::vector<std::unique_ptr<ViewSampler>> samplers_;
  bool need_offsets_ = false;
  float smallest_offset_px_ = 0.f;  ///< the smallest depth-offset radius a view is read at
  SilhouetteImages images_;
  InverseDepthPyramid pyramid_;
};

}  // namespace icgp
