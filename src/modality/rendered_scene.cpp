// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/modality/rendered_scene.h"

#include <optional>

#include "icgp/geometry/rounding.h"
#include "icgp/modality/measured_occlusion.h"

namespace icgp {

bool RenderedScene::hidden(const Eigen::Vector3f& point, float depth_offset, double radius, double threshold) const {
  if (empty()) return false;
  const cv::Mat& depth = render_.depth;
  const cv::Mat& ids = render_.ids;
  // The cue's own body never hides its points: its self-occlusions are the viewpoint
  // model's business, and its surface around a point is near the point's depth anyway.
  auto other_body_depth = [&](int row, int col) {
    return ids.ptr<std::uint8_t>(row)[col] == body_id_ ? 0.f : depth.ptr<float>(row)[col];
  };
  return closer_depth_nearby(render_.intrinsics, depth.rows, depth.cols, other_body_depth, point, depth_offset, radius,
                             threshold);
}

bool RenderedScene::on_silhouette(const Eigen::Vector3f& point, const Eigen::Vector2f& normal,
                                  bool check_outside) const {
  if (empty() || point.z() <= 0.f) return true;
  // 1.5 render pixels either side: beyond the rasteriser's half-pixel edge, within the
  // thinnest part a region model keeps (min_continuous_distance).
  constexpr float kSide = 1.5f;
  const Eigen::Vector2f centre = render_.intrinsics.project<float>(point);
  auto id_at = [&](const Eigen::Vector2f& x) -> std::optional<std::uint8_t> {
    const int col = round_to_int(x.x()), row = round_to_int(x.y());
    if (col < 0 || row < 0 || col >= render_.ids.cols || row >= render_.ids.rows) return std::nullopt;
    return render_.ids.ptr<std::uint8_t>(row)[col];
  };
  const std::optional<std::uint8_t> inside = id_at(centre - kSide * normal);
  if (inside && *inside != body_id_) return false;
  if (!check_outside) return true;
  const std::optional<std::uint8_t> outside = id_at(centre + kSide * normal);
  return !outside || *outside != body_id_;
}

}  // namespace icgp
