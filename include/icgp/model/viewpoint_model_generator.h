// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"
#include "icgp/base/mesh.h"
#include "icgp/model/viewpoint_model.h"

namespace icgp {

/// The camera that renders one view of a model (ALGORITHMS.md §3): at direction·sphere_radius,
/// looking at the body origin, image_size² pixels, with the focal length that makes the
/// body's origin-centred bounding sphere fill the image up to image_margin pixels.
struct ViewCamera {
  Intrinsics intrinsics;
  Pose camera_T_body;
};

/// Throws std::invalid_argument when body_radius is not positive or the camera would be
/// inside the bounding sphere (sphere_radius <= body_radius).
ViewCamera view_camera(const Eigen::Vector3f& direction, const ViewpointModelParams& params, double body_radius);

/// A body rendered next to the main one when generating its REGION model (multi-region,
/// ALGORITHMS.md §6, paper §III-D): another region of the same object, external geometry,
/// or a moving part. Only region models see associated bodies; depth models ignore them.
struct AssociatedBody {
  enum class Kind : std::uint32_t {
    kFixed = 1,       ///< rigidly attached, different appearance (another region, fixed surroundings)
    kSameRegion = 2,  ///< similar appearance to the main region (rigid or not: see same_region_fixed)
    kMovable = 3,     ///< a part that moves relative to the main body, different appearance
  };
  Mesh mesh;         ///< in its own frame
  Pose main_T_body;  ///< its pose in the main body's frame
  Kind kind = Kind::kFixed;
  /// kSameRegion only: rigidly attached to the main body, so foreground walks may cross it.
  bool same_region_fixed = true;
};

/// How a generation runs. None of it changes the models except associated_bodies, which
/// changes region models and therefore enters their keys (viewpoint_model_key).
struct ModelGenerationOptions {
  /// 0: std::thread::hardware_concurrency() (in_background: one less, at least one); each
  /// thread renders with its own context.
  int n_threads = 0;
  bool print_progress = true;  ///< a line on stderr every few seconds and at the end
  std::string name;            ///< names the mesh in progress lines; empty: its file stem
  /// Multi-region (ALGORITHMS.md §6): bodies rendered with the main body for region models
  /// (with distinct ids by kind), changing the contour-pixel rules and the distance walks.
  /// Empty: the single-body generation, unchanged.
  std::vector<AssociatedBody> associated_bodies;
  /// Return at once, with models whose views are made by background threads and on demand
  /// (ViewpointModel::require_view): a tracker starts on the few views it needs instead of
  /// waiting for all of them. The complete models are byte-identical to a foreground
  /// generation's. Destroying the last copy of a model finishes its generation first, on
  /// every core (unless a stop was requested), so that on_complete runs.
  bool in_background = false;
  /// in_background: called with each request's index and model once the model is complete,
  /// on a generation thread (e.g. to cache it).
  std::function<void(std::size_t request, const ViewpointModel& model)> on_complete;
};

/// One model to generate.
struct ModelRequest {
  ViewpointModel::Kind kind = ViewpointModel::Kind::kRegion;
  ViewpointModelParams params;
};

/// Generates the sparse viewpoint models of a mesh (ALGORITHMS.md §3), one per request, in
/// request order, each carrying its viewpoint_model_key. Requests that see the same views
/// (equal n_divides, sphere_radius, image_size and image_margin) share one render per view,
/// which is most of the cost. Deterministic: the same inputs give byte-identical models
/// whatever the number of threads.
///
/// Region model, per view: closed contours of the body's silhouette of at least
/// min_contour_length pixels; n_points pixels drawn uniformly without replacement from their
/// valid pixels (not on the image border); outward normal perpendicular to the chord
/// between the contour pixels ±normal_chord_offset positions away; the point back-projected
/// at the pixel's depth, moved half a pixel step out onto the silhouette's edge; foreground
/// distance to the first pixel off the silhouette inwards, background distance to the first
/// silhouette pixel outwards (+infinity at the image border), both in metres at the point's
/// depth; view measure: length of the valid contour in metres.
/// Depth model, per view: n_points pixels drawn uniformly from the silhouette, the point
/// back-projected from the rendered depth, the normal of the face the rasteriser drew there
/// (the renderer's normal image, without reading it back); view measure: visible surface
/// area in m² (see visible_surface_area in view_samplers.cpp for how).
/// Region model with associated bodies (options.associated_bodies non-empty): the main
/// body and every associated body are rendered together into an id image (ids by kind), the
/// contours are those of the pixels showing the main body, and a contour pixel is valid only
/// if it also passes the neighbour rules (see RegionViewSampler in view_samplers.cpp):
///   * "next to" a body: one of the pixel's 4-neighbours off the main mask shows it (when all
///     4-neighbours are in the mask, the diagonal neighbours off it are looked at instead);
///   * next to a same-region body (fixed or not): rejected;
///   * covered by a movable body: a movable body shows next to the pixel and is not clearly
///     behind it (its depth there < point depth + 10 px · pixel_to_metre): rejected;
///   * next to fixed bodies: valid only if their mean depth over those neighbours is not
///     smaller than point depth − 10 px · pixel_to_metre (rejects shadows of elevated edges);
///   pixel_to_metre = point depth / f.
/// The foreground walk continues across the main body and fixed same-region bodies; the
/// background walk, once off them, stops at the first pixel of the main body or any
/// same-region body. Depth offsets see every rendered body.
/// Both: body-frame points, and depth offsets (the largest amount the rendered surface
/// within radius r_k of a point comes closer to the camera than the point), conservative:
/// see InverseDepthPyramid for the approximation.
///
/// Throws std::invalid_argument for invalid parameters or a mesh without extent, RenderError
/// when no headless OpenGL context can be created (in_background: require_view throws it).
std::vector<ViewpointModel> generate_viewpoint_models(const Mesh& mesh, const std::vector<ModelRequest>& requests,
                                                      const ModelGenerationOptions& options = {});

/// One model: generate_viewpoint_models with a single request.
ViewpointModel generate_viewpoint_model(ViewpointModel::Kind kind, const Mesh& mesh, const ViewpointModelParams& params,
                                        const ModelGenerationOptions& options = {});

/// "region" or "depth".
std::string to_string(ViewpointModel::Kind kind);

}  // namespace icgp
