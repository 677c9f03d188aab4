// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/render/model_edges.h"

#include <algorithm>
#include <cmath>

namespace icgp {

using Vec3 = Eigen::Vector3d;

ModelEdges::ModelEdges(const Mesh& mesh, double crease_angle_deg) : edges_(mesh_edges(mesh, crease_angle_deg)) {}

std::vector<ImageSegment> ModelEdges::project(const Intrinsics& k, const Pose& camera_T_body, const cv::Mat& depth,
                                              double step) const {
  const Vec3 camera_in_body = camera_T_body.inverse().translation();
  std::vector<ImageSegment> out;
  for (const MeshEdge& e : edges_) {
    const bool faces_1 = e.normal_1.dot(camera_in_body - e.a) > 0.0;
    const bool faces_2 = e.normal_2.dot(camera_in_body - e.a) > 0.0;
    const bool silhouette = faces_1 != faces_2;
    if (!e.crease && !silhouette) continue;
    visible_parts(k, camera_T_body, depth, e, step, out);
  }
  return out;
}

void ModelEdges::visible_parts(const Intrinsics& k, const Pose& camera_T_body, const cv::Mat& depth, const MeshEdge& edge,
                               double step, std::vector<ImageSegment>& out) const {
  const Vec3 a = camera_T_body * edge.a, b = camera_T_body * edge.b;
  if (a.z() <= 0.0 || b.z() <= 0.0) return;  // clipping is not worth it for an overlay
  const Eigen::Vector2d pa = k.project<double>(a), pb = k.project<double>(b);
  if (depth.empty()) {
    out.push_back({pa, pb});
    return;
  }
  // Sample along the edge; a sample is visible unless the body's own surface is clearly
  // in front of it anywhere in its 3x3 neighbourhood (the faces that meet at the edge are
  // at its depth, whatever covers it is nearer).
  const int n = std::max(1, static_cast<int>(std::ceil((pb - pa).norm() / step)));
  bool open = false;
  Eigen::Vector2d start, last;
  for (int i = 0; i <= n; ++i) {
    const double s = static_cast<double>(i) / n;
    const Vec3 X = (1.0 - s) * a + s * b;
    const Eigen::Vector2d x = k.project<double>(X);
    const int u = static_cast<int>(std::lround(x.x())), v = static_cast<int>(std::lround(x.y()));
    bool visible = u >= 0 && v >= 0 && u < depth.cols && v < depth.rows;
    const double tolerance = 0.001 + 0.005 * X.z();
    for (int dv = -1; visible && dv <= 1; ++dv)
      for (int du = -1; du <= 1; ++du) {
        const int uu = std::clamp(u + du, 0, depth.cols - 1), vv = std::clamp(v + dv, 0, depth.rows - 1);
        const float d = depth.at<float>(vv, uu);
        if (d > 0.f && d < X.z() - tolerance) visible = false;
      }
    if (visible && !open) start = x;
    if (!visible && open && (last - start).norm() > 0.0) out.push_back({start, last});
    open = visible;
    last = x;
  }
  if (open && (last - start).norm() > 0.0) out.push_back({start, last});
}

}  // namespace icgp
