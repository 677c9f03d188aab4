// SPDX-License-Identifier: GPL-2.0-or-later
// Private to model generation: turning one rendered view into the points of a model view.
#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core/types.hpp>
#include <vector>

#include "icgp/model/viewpoint_model.h"
#include "icgp/model/viewpoint_model_generator.h"
#include "icgp/render/renderer.h"
#include "inverse_depth_pyramid.h"
#include "mesh_face_locator.h"

namespace icgp {

/// Ids of a region render with associated bodies (ModelGenerationOptions::associated_bodies):
/// the main body, then one id per kind of associated body.
enum RegionRenderId : std::uint8_t {
  kMainRegionId = 1,
  kFixedBodyId = 2,               ///< AssociatedBody::Kind::kFixed
  kFixedSameRegionBodyId = 3,     ///< kSameRegion, same_region_fixed
  kMovableSameRegionBodyId = 4,   ///< kSameRegion, not same_region_fixed
  kMovableBodyId = 5,             ///< AssociatedBody::Kind::kMovable
};

/// The id an associated body is rendered with.
std::uint8_t region_render_id(const AssociatedBody& body);

/// One rendered view of the main body, as the samplers read it.
struct RenderedView {
  int index = 0;  ///< view number: seeds the sampling, places the results
  Eigen::Vector3f direction;
  ViewCamera camera;
  Pose body_T_camera;
  const SilhouetteImages* images = nullptr;
  InverseDepthPyramid* pyramid = nullptr;  ///< of images->inverse_depth
  const MeshFaceLocator* faces = nullptr;  ///< of the main body, for normals
  std::uint8_t body_id = 0;                ///< of the main body in images->ids
  /// The render also holds associated bodies, with the ids of RegionRenderId (body_id is
  /// then kMainRegionId); false: only the main body, ids are its silhouette mask.
  bool with_associated_bodies = false;
};

/// Fills one view of a model from a rendered view. Keeps its working buffers across views,
/// so one sampler per thread and model.
class ViewSampler {
 public:
  virtual ~ViewSampler() = default;
  /// Writes view `view.index` of `model`, whose arrays are sized for all its views.
  virtual void sample(const RenderedView& view, ViewpointModel& model) = 0;
};

/// The sampler for a model of this kind and these parameters.
std::unique_ptr<ViewSampler> make_view_sampler(ViewpointModel::Kind kind, const ViewpointModelParams& params);

}  // namespace icgp
