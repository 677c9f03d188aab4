// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/render/model_edges.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

namespace icgp {
namespace {

using Vec3 = Eigen::Vector3d;

/// Welds vertices that share a position (meshes repeat them per face for normals and
/// texture coordinates), so that neighbouring faces share edges.
class VertexWelder {
 public:
  explicit VertexWelder(double tolerance) : tolerance_(tolerance) {}
  int index(const Vec3& p) {
    const std::array<long long, 3> key{std::llround(p.x() / tolerance_), std::llround(p.y() / tolerance_),
                                       std::llround(p.z() / tolerance_)};
    const auto [it, inserted] = indices_.try_emplace(key, static_cast<int>(positions_.size()));
    if (inserted) positions_.push_back(p);
    return it->second;
  }
  const Vec3& position(int i) const { return positions_[i]; }

 private:
  double tolerance_;
  std::map<std::array<long long, 3>, int> indices_;
  std::vector<Vec3> positions_;
};

}  // namespace

ModelEdges::ModelEdges(const Mesh& mesh, double crease_angle_deg) {
  Eigen::Vector3f lo, hi;
  mesh.bounds(lo, hi);
  VertexWelder welder(1e-6 * std::max(1e-9, static_cast<double>((hi - lo).norm())));
  std::map<std::pair<int, int>, std::vector<Vec3>> normals_of_edge;
  for (const MeshPart& part : mesh.parts)
    for (const Eigen::Vector3i& t : part.triangles) {
      const int v[3] = {welder.index(part.vertices[t[0]].cast<double>()), welder.index(part.vertices[t[1]].cast<double>()),
                        welder.index(part.vertices[t[2]].cast<double>())};
      const Vec3 n = (welder.position(v[1]) - welder.position(v[0])).cross(welder.position(v[2]) - welder.position(v[0]));
      if (n.norm() <= 0.0) continue;  // degenerate: no face, no edge
      for (int i = 0; i < 3; ++i)
        normals_of_edge[std::minmax(v[i], v[(i + 1) % 3])].push_back(n.normalized());
    }
  const double cos_crease = std::cos(deg_to_rad(crease_angle_deg));
  for (const auto& [ends, normals] : normals_of_edge) {
    Edge e{welder.position(ends.first), welder.position(ends.second), normals.front(),
           normals.size() > 1 ? normals[1] : normals.front(), false};
    // Borders and edges shared by more than two faces always show.
    e.crease = normals.size() != 2 || e.normal_1.dot(e.normal_2) < cos_crease;
    edges_.push_back(e);
  }
}

std::vector<ImageSegment> ModelEdges::project(const Intrinsics& k, const Pose& camera_T_body, const cv::Mat& depth,
                                              double step) const {
  const Vec3 camera_in_body = camera_T_body.inverse().translation();
  std::vector<ImageSegment> out;
  for (const Edge& e : edges_) {
    const bool faces_1 = e.normal_1.dot(camera_in_body - e.a) > 0.0;
    const bool faces_2 = e.normal_2.dot(camera_in_body - e.a) > 0.0;
    const bool silhouette = faces_1 != faces_2;
    if (!e.crease && !silhouette) continue;
    visible_parts(k, camera_T_body, depth, e, step, out);
  }
  return out;
}

void ModelEdges::visible_parts(const Intrinsics& k, const Pose& camera_T_body, const cv::Mat& depth, const Edge& edge,
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
