// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "icgp/geometry/intrinsics.h"
#include "icgp/geometry/pose.h"
#include "icgp/io/mesh.h"
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

/// How a generation runs; none of it changes the models.
struct ModelGenerationOptions {
  int n_threads = 0;           ///< 0: std::thread::hardware_concurrency(); each thread renders with its own context
  bool print_progress = true;  ///< a line on stderr every few seconds and at the end
  std::string name;            ///< names the mesh in progress lines; empty: its file stem
  // Multi-region (ALGORITHMS.md §6) adds the associated bodies here (mesh, pose relative to
  // the main body, kind fixed / same_region / movable): they change the region renders and
  // the contour-pixel rules, and must then enter the cache key.
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
/// Both: body-frame points, and depth offsets (the largest amount the rendered surface
/// within radius r_k of a point comes closer to the camera than the point), conservative:
/// see InverseDepthPyramid for the approximation.
///
/// Throws std::invalid_argument for invalid parameters or a mesh without extent, RenderError
/// when no headless OpenGL context can be created.
std::vector<ViewpointModel> generate_viewpoint_models(const Mesh& mesh, const std::vector<ModelRequest>& requests,
                                                      const ModelGenerationOptions& options = {});

/// One model: generate_viewpoint_models with a single request.
ViewpointModel generate_viewpoint_model(ViewpointModel::Kind kind, const Mesh& mesh, const ViewpointModelParams& params,
                                        const ModelGenerationOptions& options = {});

/// "region" or "depth".
std::string to_string(ViewpointModel::Kind kind);

}  // namespace icgp
