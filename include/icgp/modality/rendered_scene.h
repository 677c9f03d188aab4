// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <cstdint>

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

}  // namespace icgp
