// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>

#include "icgp/base/body.h"
#include "icgp/base/frame.h"
#include "icgp/modality/modality.h"
#include "icgp/modality/modality_params.h"

namespace icgp {

/// The focused render of every body that a cue reads about its own body in one frame:
/// modeled occlusions (ALGORITHMS.md §7) and region checking (§6). Empty (no render: the
/// tracker has no other body, or the cue asked for none): nothing is hidden and every
/// contour point counts as on the silhouette.
class RenderedScene {
 public:
  RenderedScene() = default;
  /// `render` shows the cue's body with id `body_id`.
  RenderedScene(const FocusedRender& render, std::uint8_t body_id) : render_(render), body_id_(body_id) {}

  bool empty() const { return render_.depth.empty(); }
  /// Modeled occlusion: a surface of another body within `radius` (metres) of the
  /// projection of `point` (the render's camera frame) is closer than
  /// Z − depth_offset − threshold.
  bool hidden(const Eigen::Vector3f& point, float depth_offset, double radius, double threshold) const;
  /// Region checking: the render shows the body just inside the contour point `point`
  /// (against its outward image `normal`) and, when `check_outside`, something else just
  /// outside it.
  bool on_silhouette(const Eigen::Vector3f& point, const Eigen::Vector2f& normal, bool check_outside) const;

 private:
  FocusedRender render_;
  std::uint8_t body_id_ = 0;
};

/// What one cue's scene render shows: the square around its body's bounding sphere in the
/// cue's camera, resampled to `size` pixels.
class SceneCrop {
 public:
  SceneCrop(const Body& body, std::string camera, int size);

  /// The request for the render of modeled occlusions and region checking in `stage` (the
  /// camera's image intrinsics and camera_T_reference): at the first correspondence
  /// iteration of a frame (the pose then moves by far less than an occlusion radius or a
  /// line's length), and only when another body of stage.scene may cover the body: its
  /// sphere's square overlaps the body's in this camera.
  std::optional<RenderRequest> request(const Stage& stage, const Intrinsics& intrinsics,
                                       const Pose& camera_T_reference) const;
  /// The render of this frame's `renders` that request() asked for, empty when it asked
  /// for none.
  RenderedScene find(const Renders& renders, const Intrinsics& intrinsics, const Pose& camera_T_reference) const;
  /// bounding_sphere of the body's mesh.
  const Sphere& sphere() const { return sphere_; }

 private:
  std::optional<RenderRequest> crop(const Intrinsics& intrinsics, const Pose& camera_T_reference) const;

  const Body* body_;
  std::string camera_;
  Sphere sphere_;
  int size_;
};

}  // namespace icgp
