// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/modality/dense_depth_sampling.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "icgp/geometry/rounding.h"

namespace icgp {
namespace {

/// The body is rendered again when it has moved by this share of a sampling step since the
/// kept surface was rendered: less moves each sample by less than a quarter pixel on the
/// surface. A box sliding along a face seen at a grazing angle is still rendered while it
/// slides (tests/unit/test_dense_depth.cpp).
constexpr double kRenewFraction = 0.25;

}  // namespace

DenseDepthSampling::DenseDepthSampling(const Body& body, std::string camera, const DenseDepthParams& params)
    : body_(&body), camera_(std::move(camera)), params_(params), sphere_(bounding_sphere(body.mesh)) {
  if (params_.step_x < 0 || params_.step_y < 0)
    throw std::invalid_argument("dense depth of '" + body.name + "': sampling step (" + std::to_string(params_.step_x) +
                                ", " + std::to_string(params_.step_y) +
                                ") must be pixels >= 1 along columns and rows, or 0 for automatic");
  if (params_.n_points_max < 1)
    throw std::invalid_argument("dense depth of '" + body.name + "': n_points_max (" +
                                std::to_string(params_.n_points_max) + ") must be at least 1");
}

DenseDepthSampling::Lattice DenseDepthSampling::lattice(const DepthImage& depth) const {
  const Intrinsics& k = depth.intrinsics;
  // The image pixels the body can cover: those of its sphere's square, or all of them when
  // the sphere reaches the camera's plane (its image is then unbounded).
  int col_lo = 0, row_lo = 0, col_hi = k.width - 1, row_hi = k.height - 1;
  const Eigen::Vector3d centre = depth.camera_T_reference * body_->reference_T_body * sphere_.centre;
  if (centre.z() > sphere_.radius) {
    // The square's edges are u_min - 0.5 and u_min - 0.5 + size (ImageSquare): it holds the
    // pixel centres from u_min - 0.5 up to, not including, u_min - 0.5 + size.
    const ImageSquare square = square_around_sphere(k, centre, sphere_.radius);
    col_lo = std::max(col_lo, static_cast<int>(std::ceil(square.u_min - 0.5)));
    row_lo = std::max(row_lo, static_cast<int>(std::ceil(square.v_min - 0.5)));
    col_hi = std::min(col_hi, static_cast<int>(std::ceil(square.u_min - 0.5 + square.size)) - 1);
    row_hi = std::min(row_hi, static_cast<int>(std::ceil(square.v_min - 0.5 + square.size)) - 1);
  }
  Lattice l;
  if (col_lo > col_hi || row_lo > row_hi) return l;
  // An automatic step spreads at most n_points_max samples over the pixels the body can
  // cover: every pixel of a far body, a bounded cost for a near one.
  const double n_pixels = static_cast<double>(col_hi - col_lo + 1) * (row_hi - row_lo + 1);
  const int automatic = std::max(1, static_cast<int>(std::ceil(std::sqrt(n_pixels / params_.n_points_max))));
  l.step_x = params_.step_x > 0 ? params_.step_x : automatic;
  l.step_y = params_.step_y > 0 ? params_.step_y : automatic;
  l.render_step = std::gcd(l.step_x, l.step_y);
  // Sampled columns and rows are multiples of their steps, as ViSP's are.
  l.col0 = lattice_ceil(static_cast<float>(col_lo), l.step_x);
  l.row0 = lattice_ceil(static_cast<float>(row_lo), l.step_y);
  if (l.col0 > col_hi || l.row0 > row_hi) return l;
  const int across = (col_hi - l.col0) / l.render_step + 1, down = (row_hi - l.row0) / l.render_step + 1;
  l.size = std::max(across, down);
  return l;
}

RenderRequest DenseDepthSampling::request_of(const Lattice& l, const DepthImage& depth) const {
  // Render pixel j's centre lies at image u = (j + 0.5)·render_step + u_min - 0.5
  // (Intrinsics::cropped), which is col0 + j·render_step for this u_min: the rendered ray of
  // a sample is its measured pixel's ray.
  const double half_step = 0.5 * l.render_step;
  ImageSquare square{l.col0 + 0.5 - half_step, l.row0 + 0.5 - half_step,
                     static_cast<double>(l.size) * l.render_step};
  return RenderRequest{camera_, depth.intrinsics, depth.camera_T_reference, square, l.size,
                       kRenderDepth | kRenderNormals | kRenderIds};
}

bool DenseDepthSampling::surface_stands(const Stage& stage, const Lattice& l, const DepthImage& depth) const {
  if (surface_.empty() || depth.intrinsics.width != rendered_width_ || depth.intrinsics.height != rendered_height_)
    return false;
  // Another body may have moved over this one whatever this one did.
  if (stage.scene)
    for (const BodyExtent& other : *stage.scene)
      if (other.name != body_->name) return false;
  // How far the body's sphere has moved in the camera since the render, its turn counted at
  // its radius, against the sampling step in metres at the body's depth.
  const Pose now = depth.camera_T_reference * body_->reference_T_body;
  const double turned = rotation_angle_between(now.rotation(), rendered_depth_T_body_.rotation());
  const double moved = (now * sphere_.centre - rendered_depth_T_body_ * sphere_.centre).norm() + turned * sphere_.radius;
  const double z = std::max((now * sphere_.centre).z(), 1e-3);
  return moved < kRenewFraction * std::min(l.step_x, l.step_y) * z / depth.intrinsics.fu;
}

std::optional<RenderRequest> DenseDepthSampling::request(const Stage& stage, const DepthImage& depth) const {
  if (stage.kind != Stage::kCorrespondences) return std::nullopt;
  const Lattice l = lattice(depth);
  if (l.size == 0 || surface_stands(stage, l, depth)) return std::nullopt;
  return request_of(l, depth);
}

void DenseDepthSampling::keep_surface(const FocusedRender& render, std::uint8_t id, const Lattice& l,
                                      const DepthImage& depth) {
  surface_.clear();
  rendered_depth_T_body_ = depth.camera_T_reference * body_->reference_T_body;
  rendered_width_ = depth.intrinsics.width;
  rendered_height_ = depth.intrinsics.height;
  const Posef body_T_depth = rendered_depth_T_body_.inverse().cast<float>();
  const Eigen::Matrix3f body_R_depth = body_T_depth.rotation();
  const Intrinsics& k = depth.intrinsics;
  const float ifu = static_cast<float>(1.0 / k.fu), ifv = static_cast<float>(1.0 / k.fv);
  const float pu = static_cast<float>(k.pu), pv = static_cast<float>(k.pv);
  // Every step_x / render_step-th render column and step_y / render_step-th row is a sample.
  const int skip_x = l.step_x / l.render_step, skip_y = l.step_y / l.render_step;
  for (int i = 0; i < l.size; i += skip_y) {
    const int row = l.row0 + i * l.render_step;
    if (row >= k.height) break;
    const std::uint8_t* ids = render.ids.ptr<std::uint8_t>(i);
    const float* rendered_z = render.depth.ptr<float>(i);
    const cv::Vec3f* normals = render.normals.ptr<cv::Vec3f>(i);
    for (int j = 0; j < l.size; j += skip_x) {
      const int col = l.col0 + j * l.render_step;
      if (col >= k.width) break;
      if (ids[j] != id) continue;
      const float zr = rendered_z[j];
      const Eigen::Vector3f surface((col - pu) * ifu * zr, (row - pv) * ifv * zr, zr);
      const cv::Vec3f& n = normals[j];
      surface_.push_back({row, col, body_T_depth * surface, body_R_depth * Eigen::Vector3f(n[0], n[1], n[2])});
    }
  }
}

DenseDepthSampling::Counts DenseDepthSampling::collect(const Renders& renders, const DepthImage& depth,
                                                       float considered_distance,
                                                       std::vector<DepthCorrespondence>& out) {
  out.clear();
  Counts counts;
  const Lattice l = lattice(depth);
  if (l.size == 0) return counts;
  if (const FocusedRender* render = renders.find(request_of(l, depth)))
    keep_surface(*render, renders.id(body_->name), l, depth);
  const Posef depth_T_body = (depth.camera_T_reference * body_->reference_T_body).cast<float>();
  const float gate = considered_distance * considered_distance;
  for (const SurfaceSample& s : surface_) {
    if (!depth.mask.usable(s.row, s.col)) continue;
    ++counts.n_on_body;
    const float z = depth.at(s.row, s.col);
    if (!(z > 0.f && z < std::numeric_limits<float>::infinity())) continue;
    counts.saw_depth = true;
    const Eigen::Vector3f measured = depth.point(s.row, s.col, z);
    if ((depth_T_body * s.body_point - measured).squaredNorm() >= gate) continue;
    out.push_back({s.body_point, s.body_normal, measured});
  }
  return counts;
}

}  // namespace icgp
