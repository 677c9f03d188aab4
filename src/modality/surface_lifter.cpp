// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/modality/surface_lifter.h"

#include <cmath>
#include <optional>

#include "icgp/geometry/rounding.h"

namespace icgp {
namespace {

/// A neighbour further off the fitted plane than this share of its distance (about 3°)
/// shows a crease, where the render gives no one normal.
constexpr float kMaxCreaseSlope = 0.05f;

/// The camera-frame normal of the render's surface at (row, col), from its depth at the
/// pixel's four neighbours; zero unless all of them show the body on one plane.
Eigen::Vector3f render_normal(const FocusedRender& render, std::uint8_t body_id, int row, int col) {
  if (row < 1 || col < 1 || row + 1 >= render.depth.rows || col + 1 >= render.depth.cols)
    return Eigen::Vector3f::Zero();
  const auto at = [&](int r, int c) -> std::optional<Eigen::Vector3f> {
    const float z = render.depth.at<float>(r, c);
    if (z <= 0.f || render.ids.at<std::uint8_t>(r, c) != body_id) return std::nullopt;
    return render.intrinsics.back_project<float>(static_cast<float>(c), static_cast<float>(r), z);
  };
  const auto centre = at(row, col), left = at(row, col - 1), right = at(row, col + 1), up = at(row - 1, col),
             down = at(row + 1, col);
  if (!centre || !left || !right || !up || !down) return Eigen::Vector3f::Zero();
  // Towards the camera: (right − left) × (down − up) points away from it in a frame of x
  // right and y down, so the order is reversed.
  const Eigen::Vector3f n = (*down - *up).cross(*right - *left);
  if (!(n.norm() > 0.f)) return Eigen::Vector3f::Zero();
  const Eigen::Vector3f unit = n.normalized();
  // On a crease the four neighbours lie on two faces: their plane is neither face's.
  for (const Eigen::Vector3f* p : {&*left, &*right, &*up, &*down})
    if (std::abs(unit.dot(*p - *centre)) > kMaxCreaseSlope * (*p - *centre).norm()) return Eigen::Vector3f::Zero();
  return unit;
}

}  // namespace

std::vector<SurfacePoint> SurfaceLifter::lift(const Intrinsics& k, const Pose& camera_T_body,
                                              const FocusedRender& render, std::uint8_t body_id,
                                              const std::vector<cv::Point2f>& points, const DepthImage* depth,
                                              const Pose& depth_T_camera) const {
  std::vector<SurfacePoint> lifted;
  if (points.empty()) return lifted;
  const Intrinsics& crop_k = render.intrinsics;
  const double su = crop_k.fu / k.fu, sv = crop_k.fv / k.fv;
  const Pose body_T_camera = camera_T_body.inverse();
  const Eigen::Matrix3f body_R_camera = body_T_camera.rotation().cast<float>();
  const Posef depth_T_body = (depth_T_camera * camera_T_body).cast<float>();
  // The object's own surface may rise towards the camera by about the radius around a
  // point (slopes up to 45°); steeper rises stay within the threshold.
  const float depth_offset = static_cast<float>(occlusion_.radius);
  lifted.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const cv::Point2f& x = points[i];
    const int col = round_to_int(static_cast<float>(crop_k.pu + (x.x - k.pu) * su));
    const int row = round_to_int(static_cast<float>(crop_k.pv + (x.y - k.pv) * sv));
    if (col < 0 || row < 0 || col >= render.depth.cols || row >= render.depth.rows) continue;
    const float z = render.depth.at<float>(row, col);
    // Another tracked body in front hides the point: it is not on this body's surface.
    if (z <= 0.f || render.ids.at<std::uint8_t>(row, col) != body_id) continue;
    const Eigen::Vector3d camera_X = k.back_project<double>(x.x, x.y, z);
    const Eigen::Vector3f body_X = (body_T_camera * camera_X).cast<float>();
    if (depth && occlusion_.occluded(*depth, depth_T_body * body_X, depth_offset)) continue;
    lifted.push_back({static_cast<int>(i), body_X, body_R_camera * render_normal(render, body_id, row, col)});
  }
  return lifted;
}

}  // namespace icgp
