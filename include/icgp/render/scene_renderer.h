// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <opencv2/core/mat.hpp>
#include <string>
#include <utility>
#include <vector>

#include "icgp/base/body.h"
#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"
#include "icgp/render/renderer.h"

namespace icgp {

/// A focused render a cue reads (Modality::render_requests): the crop `square` of one
/// camera's image, resampled to size x size pixels, showing every tracked body at its
/// current pose.
struct RenderRequest {
  std::string camera;
  Intrinsics intrinsics;    ///< the camera's full image
  Pose camera_T_reference;  ///< the camera in the frame's reference camera
  ImageSquare square;
  int size = 0;
  unsigned targets = kRenderDepth | kRenderIds;

  /// The same view, whatever the camera is called: cameras of one geometry (a depth camera
  /// registered to the colour camera) share one render.
  bool operator==(const RenderRequest& other) const;
};

/// The request for a focused render in camera `camera` (its image's intrinsics and
/// camera_T_reference) of a body at reference_T_body whose bounding sphere is `sphere`: the
/// square around the sphere's projection resampled to size x size pixels, with depth and
/// ids. None when the sphere is not wholly in front of the camera.
std::optional<RenderRequest> focused_render_request(const std::string& camera, const Intrinsics& intrinsics,
                                                    const Pose& camera_T_reference, const Pose& reference_T_body,
                                                    const Sphere& sphere, int size);

/// What a RenderRequest produced.
struct FocusedRender {
  Intrinsics intrinsics;  ///< of the crop: maps its pixels back into the camera's image
  cv::Mat depth;          ///< CV_32FC1 metric Z, 0 on background
  cv::Mat ids;            ///< CV_8UC1 SceneRenderer::id of the body seen, 0 on background
  cv::Mat normals;        ///< CV_32FC3 unit face normals in the camera frame, when the targets have kRenderNormals
  cv::Mat color;          ///< CV_8UC3 BGR shaded colour, when the request's targets have kRenderColor
};

/// The renders of one stage of a frame, looked up by the request that asked for them, and
/// the id each body has in their id images.
class Renders {
 public:
  void clear();
  void add(RenderRequest request, FocusedRender render);
  void set_id(const std::string& body, std::uint8_t id);
  /// Throws std::logic_error when nothing asked for `request` in this stage.
  const FocusedRender& at(const RenderRequest& request) const;
  /// The render of `request`, null when nothing asked for it in this stage.
  const FocusedRender* find(const RenderRequest& request) const;
  /// The id of `body` in the id images; throws std::logic_error for a body not rendered.
  std::uint8_t id(const std::string& body) const;

 private:
  std::vector<std::pair<RenderRequest, FocusedRender>> renders_;
  std::vector<std::pair<std::string, std::uint8_t>> ids_;
};

/// The tracker's one renderer: every body it tracks, uploaded once, rendered for the cues'
/// requests at the bodies' current poses, and for display. The GL context is made on the
/// first render, so that a tracker whose cues render nothing never needs one. Bodies are
/// known by name; each gets an id (1, 2, ... in the order first seen) for the id images.
class SceneRenderer {
 public:
  SceneRenderer();
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  /// Renders every request with all of `bodies` (and no other) visible at their
  /// reference_T_body, into `out` (cleared first).
  void render(const std::vector<const Body*>& bodies, const std::vector<RenderRequest>& requests, Renders& out);
  /// The depth (CV_32FC1, 0 on background) of the body named `name` alone, with mesh
  /// `mesh`, at camera_T_body, in the full image of `intrinsics`: hidden-line removal for
  /// display.
  cv::Mat depth_of(const std::string& name, const Mesh& mesh, const Intrinsics& intrinsics, const Pose& camera_T_body);
  /// The id of a body in the id images (0 when it has never been rendered).
  std::uint8_t id(const std::string& body) const;

 private:
  struct Uploaded {
    std::string name;
    Renderer::BodyHandle handle;
  };
  Renderer& renderer();
  /// Uploads the body the first time it is seen, and makes it visible.
  Renderer::BodyHandle show(const std::string& name, const Mesh& mesh);
  void hide_all();

  std::unique_ptr<Renderer> renderer_;
  std::vector<Uploaded> uploaded_;  ///< index + 1 is the body's id
};

}  // namespace icgp
