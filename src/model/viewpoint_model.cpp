// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/model/viewpoint_model.h"

#include <sys/mman.h>

#include <cmath>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "icgp/model/icosphere.h"

namespace icgp {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("viewpoint model parameter " + what);
}

/// `size` bytes of zeros from the kernel, in huge pages where it offers them: a default model
/// is 68 MB, and zeroing it with memset page by page cost more than decoding its cache file.
std::shared_ptr<void> zeroed_block(std::size_t size) {
  void* block = ::mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (block == MAP_FAILED) throw std::bad_alloc();
  ::madvise(block, size, MADV_HUGEPAGE);  // a hint: without it, 4 KiB pages
  return std::shared_ptr<void>(block, [size](void* p) { ::munmap(p, size); });
}

}  // namespace

int ViewpointModelParams::n_depth_offsets() const {
  if (!(stride_depth_offset > 0.0) || !(max_radius_depth_offset >= 0.0)) return 0;
  // The tolerance keeps 0.05 / 0.002 at 25 radii despite its floating-point quotient.
  return static_cast<int>(std::floor(max_radius_depth_offset / stride_depth_offset + 1e-6));
}

int ViewpointModelParams::n_views() const { return 10 * (1 << (2 * n_divides)) + 2; }

void ViewpointModelParams::validate() const {
  require(n_divides >= 0 && n_divides <= 6, "n_divides must be from 0 to 6 (got " + std::to_string(n_divides) + ")");
  require(std::isfinite(sphere_radius) && sphere_radius > 0.0,
          "sphere_radius must be positive (got " + std::to_string(sphere_radius) + ")");
  require(image_size >= 16 && image_size <= kMaxImageSize, "image_size must be from 16 to " + std::to_string(kMaxImageSize) +
                                                                 " px (got " + std::to_string(image_size) + ")");
  require(image_margin >= 0 && 2LL * image_margin < image_size - 2LL,  // 64-bit: a cache header may hold any int
          "image_margin must be non-negative and leave room for the object (got " + std::to_string(image_margin) +
              " px of " + std::to_string(image_size) + ")");
  require(n_points >= 1 && n_points <= kMaxPoints,
          "n_points must be from 1 to " + std::to_string(kMaxPoints) + " (got " + std::to_string(n_points) + ")");
  require(std::isfinite(stride_depth_offset) && stride_depth_offset > 0.0,
          "stride_depth_offset must be positive (got " + std::to_string(stride_depth_offset) + ")");
  require(std::isfinite(max_radius_depth_offset) && max_radius_depth_offset >= 0.0,
          "max_radius_depth_offset must be non-negative (got " + std::to_string(max_radius_depth_offset) + ")");
  require(max_radius_depth_offset / stride_depth_offset <= kMaxDepthOffsets,
          "max_radius_depth_offset / stride_depth_offset must be at most " + std::to_string(kMaxDepthOffsets) +
              " depth offsets (got " + std::to_string(max_radius_depth_offset) + " / " +
              std::to_string(stride_depth_offset) + ")");
  require(sphere_radius <= 100.0, "sphere_radius must be at most 100 m (got " + std::to_string(sphere_radius) + ")");
  require(ViewpointModel::payload_size(*this) <= kMaxPayloadBytes,
          "n_divides " + std::to_string(n_divides) + ", n_points " + std::to_string(n_points) + " and " +
              std::to_string(n_depth_offsets()) + " depth offsets make a model of " +
              std::to_string(ViewpointModel::payload_size(*this) >> 20) + " MiB (expected at most " +
              std::to_string(kMaxPayloadBytes >> 20) + " MiB)");
  require(min_contour_length >= 0,
          "min_contour_length must be non-negative (got " + std::to_string(min_contour_length) + ")");
  require(normal_chord_offset >= 1,
          "normal_chord_offset must be positive (got " + std::to_string(normal_chord_offset) + ")");
}

bool operator==(const ViewpointModelParams& a, const ViewpointModelParams& b) {
  return a.n_divides == b.n_divides && a.sphere_radius == b.sphere_radius && a.image_size == b.image_size &&
         a.image_margin == b.image_margin && a.n_points == b.n_points &&
         a.stride_depth_offset == b.stride_depth_offset && a.max_radius_depth_offset == b.max_radius_depth_offset &&
         a.min_contour_length == b.min_contour_length && a.normal_chord_offset == b.normal_chord_offset &&
         a.seed == b.seed;
}

std::size_t ViewpointModel::payload_size(const ViewpointModelParams& params) {
  const std::size_t views = params.n_views(), slots = views * params.n_points;
  return views * (sizeof(ModelView) + sizeof(std::int32_t)) +
         slots * (sizeof(ModelPoint) + params.n_depth_offsets() * sizeof(float));
}

ViewpointModel::ViewpointModel(Kind kind, ViewpointModelParams params, std::uint64_t key)
    : kind_(kind), params_(params), key_(key) {
  const std::shared_ptr<void> block = zeroed_block(payload_size(params_));
  storage_ = block;
  point_into(static_cast<const unsigned char*>(block.get()));
  // Known before any view is rendered, so a model made in the background can pick views.
  const std::vector<Eigen::Vector3f> directions = icosphere_directions(params_.n_divides);
  for (int v = 0; v < n_views_; ++v) mutable_views()[v].direction = directions[v];
}

void ViewpointModel::point_into(const unsigned char* payload) {
  static_assert(sizeof(ModelView) == 4 * sizeof(float) && sizeof(ModelPoint) == 8 * sizeof(float),
                "views and points are plain floats: the payload is their bytes");
  n_views_ = params_.n_views();
  n_depth_offsets_ = params_.n_depth_offsets();
  const std::size_t slots = static_cast<std::size_t>(n_views_) * params_.n_points;
  payload_ = payload;
  views_ = reinterpret_cast<const ModelView*>(payload);
  counts_ = reinterpret_cast<const int*>(views_ + n_views_);
  points_ = reinterpret_cast<const ModelPoint*>(counts_ + n_views_);
  depth_offsets_ = reinterpret_cast<const float*>(points_ + slots);
}

int ViewpointModel::closest_view(const Eigen::Vector3f& direction) const {
  int best = 0;
  float best_dot = -2.f;
  for (int v = 0; v < n_views(); ++v) {
    const float d = views_[v].direction.dot(direction);
    if (d > best_dot) {
      best_dot = d;
      best = v;
    }
  }
  return best;
}

}  // namespace icgp
