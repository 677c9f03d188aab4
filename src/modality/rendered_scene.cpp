// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/modality/rendered_scene.h"

#include <optional>

#include "icgp/geometry/rounding.h"
#include "icgp/modality/measured_occlusion.h"

namespace icgp {

namespace {

bool overlap(const ImageSquare& a, const ImageSquare& b) {
  return a.u_min < b.u_min + b.size && b.u_min < a.u_min + a.size && a.v_min < b.v_min + b.size &&
         b.v_min < a.v_min + a.size;
}

}  // namespace

SceneCrop::SceneCrop(const Body& body, std::string camera, int size)
    : body_(&body), camera_(std::move(camera)), sphere_(bounding_sphere(body.mesh)), size_(size) {}

std::optional<RenderRequest> SceneCrop::crop(const Intrinsics& intrinsics, const Pose& camera_T_reference) const {
  return focused_render_request(camera_, intrinsics, camera_T_reference, body_->reference_T_body, sphere_, size_);
}

std::optional<RenderRequest> SceneCrop::request(const Stage& stage, const Intrinsics& intrinsics,
                                                const Pose& camera_T_reference) const {
  if (stage.kind != Stage::kCorrespondences || stage.corr_iter != 0 || !stage.scene) return std::nullopt;
  std::optional<RenderRequest> request = crop(intrinsics, camera_T_reference);
  if (!request) return std::nullopt;
  for (const BodyExtent& other : *stage.scene) {
    if (other.name == body_->name) continue;
    const Eigen::Vector3d centre = camera_T_reference * other.centre;
    // A sphere that reaches the camera's plane may cover any part of the image.
    if (!(centre.z() > other.radius) ||
        overlap(request->square, square_around_sphere(intrinsics, centre, other.radius)))
      return request;
  }
  return std::nullopt;
}

RenderedScene SceneCrop::find(const Renders& renders, const Intrinsics& intrinsics,
                              const Pose& camera_T_reference) const {
  const std::optional<RenderRequest> request = crop(intrinsics, camera_T_reference);
  if (!request) return {};
  const FocusedRender* render = renders.find(*request);
  return render ? RenderedScene(*render, renders.id(body_->name)) : RenderedScene();
}

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
