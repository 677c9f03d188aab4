// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>

namespace icgp {

/// How a sparse viewpoint model is generated (ALGORITHMS.md §3). Every field is part of
/// the cache key: changing any of them regenerates the model.
struct ViewpointModelParams {
  // Resource bounds (validate()): beyond them a model would take unbounded memory or time.
  static constexpr int kMaxImageSize = 8192;
  static constexpr int kMaxPoints = 5000;
  static constexpr int kMaxDepthOffsets = 1000;
  static constexpr std::size_t kMaxPayloadBytes = std::size_t(4) << 30;

  int n_divides = 4;                      ///< icosphere subdivisions: 4 -> 2562 views
  double sphere_radius = 0.8;             ///< metres, camera distance to the body origin
  int image_size = 2000;                  ///< square render size in pixels
  int image_margin = 20;                  ///< pixels between the bounding sphere and the border
  int n_points = 200;                     ///< points per view
  double stride_depth_offset = 0.002;     ///< metres between depth-offset radii
  double max_radius_depth_offset = 0.05;  ///< metres, largest depth-offset radius
  int min_contour_length = 15;            ///< region: contours shorter than this (px) are dropped
  int normal_chord_offset = 3;            ///< region: contour pixels ±k apart give the normal
  std::uint64_t seed = 7;                 ///< point sampling; fixed for deterministic models

  int n_depth_offsets() const;  ///< radii (k+1) * stride_depth_offset up to max_radius_depth_offset
  int n_views() const;          ///< 10 * 4^n_divides + 2
  /// Throws std::invalid_argument naming the first field out of range, or the fields whose
  /// product makes a model larger than kMaxPayloadBytes.
  void validate() const;
};

bool operator==(const ViewpointModelParams& a, const ViewpointModelParams& b);
inline bool operator!=(const ViewpointModelParams& a, const ViewpointModelParams& b) { return !(a == b); }

/// One sampled model point of a view, in the body frame. Plain floats: the cache stores it
/// byte for byte.
struct ModelPoint {
  Eigen::Vector3f position;
  Eigen::Vector3f normal;         ///< region: contour normal (outwards); depth: surface normal
  float foreground_distance = 0;  ///< region: metres inside the silhouette along -normal
  float background_distance = 0;  ///< region: metres outside along +normal (inf: to the border)
};

/// The points seen from one viewpoint.
struct ModelView {
  Eigen::Vector3f direction;  ///< unit vector body origin -> camera, body frame
  float measure = 0;          ///< region: contour length (m); depth: visible surface area (m²)
};

/// Where the views of a model still being made come from (generate_viewpoint_models with
/// ModelGenerationOptions::in_background): background threads, and on demand the view a
/// tracker needs now.
class ViewSupply {
 public:
  virtual ~ViewSupply() = default;
  /// Returns once view v is in the model; rethrows the generation's error.
  virtual void require(int v) = 0;
  /// Returns once every view is in the model; rethrows the generation's error.
  virtual void require_all() = 0;
  virtual bool complete() const = 0;
};

/// A sparse viewpoint model: for each of n_views directions, n_points sampled points with
/// their depth offsets (for occlusion tests). Made by generate_viewpoint_models
/// (viewpoint_model_generator.h), usually through the disk cache (model_cache.h).
///
/// All arrays live in one block. A cache file keeps them in 45 bytes a point instead of 132
/// (src/model/stored_model.h), and the generator rounds its values to what the file keeps,
/// so a loaded model equals the generated one. Models are immutable once made; copies share
/// the block.
///
/// A model generated in the background (ModelGenerationOptions::in_background) has every
/// view's direction from the start, and a view's points, counts, measure and depth offsets
/// once require_view() returned for it: select a view with closest_view(), require it, then
/// read it. Complete models (loaded, or generated in the foreground) need no require.
class ViewpointModel {
 public:
  enum class Kind : std::uint32_t { kRegion = 1, kDepth = 2 };

  ViewpointModel() = default;
  /// A model of all views of `params`, for the generator to fill: the views' directions
  /// (icosphere_directions), every other array zero.
  ViewpointModel(Kind kind, ViewpointModelParams params, std::uint64_t key);

  Kind kind() const { return kind_; }
  const ViewpointModelParams& params() const { return params_; }
  /// Hash of the mesh geometry and every generation parameter.
  std::uint64_t key() const { return key_; }

  int n_views() const { return n_views_; }
  int n_points() const { return params_.n_points; }
  int n_depth_offsets() const { return n_depth_offsets_; }

  /// Index of the view whose direction is closest to `direction` (body frame, unit).
  int closest_view(const Eigen::Vector3f& direction) const;
  /// Returns once view v can be read (at once unless the model is being generated in the
  /// background, which then makes v next). Throws what the generation threw.
  void require_view(int v) const {
    if (supply_) supply_->require(v);
  }
  /// Returns once every view can be read.
  void require_all_views() const {
    if (supply_) supply_->require_all();
  }
  /// Every view can be read.
  bool complete() const { return !supply_ || supply_->complete(); }
  const ModelView& view(int v) const { return views_[v]; }
  /// The points of view v: n_points() slots of which the first view_point_count(v) are
  /// valid (the rest are zero). They are in random order, so any prefix of them is itself a
  /// uniform sample of the view's contour or surface.
  const ModelPoint* points(int v) const { return points_ + static_cast<std::size_t>(v) * n_points(); }
  int view_point_count(int v) const { return counts_[v]; }
  /// Depth offsets of point p of view v: entry k is for radius (k+1) * stride_depth_offset.
  const float* depth_offsets(int v, int p) const {
    return depth_offsets_ + (static_cast<std::size_t>(v) * n_points() + p) * n_depth_offsets();
  }

  /// The block of all arrays: views (ModelView), point counts (int32 per view), points
  /// (n_points slots per view), depth offsets (n_depth_offsets floats per slot).
  const unsigned char* payload() const { return payload_; }
  std::size_t payload_size() const { return payload_size(params_); }
  static std::size_t payload_size(const ViewpointModelParams& params);

  // For the generator and the cache reader, on models they made (null on a default-constructed one).
  ModelView* mutable_views() { return writable(views_); }
  int* mutable_counts() { return writable(counts_); }
  ModelPoint* mutable_points() { return writable(points_); }
  float* mutable_depth_offsets() { return writable(depth_offsets_); }
  /// For the generator: the views of this model (and of its copies made from now on) come
  /// from `supply` until it is complete.
  void set_supply(std::shared_ptr<ViewSupply> supply) { supply_ = std::move(supply); }
  /// Where the views come from until the model is complete (null: every view is made).
  const std::shared_ptr<ViewSupply>& supply() const { return supply_; }

 private:
  void point_into(const unsigned char* payload);
  template <typename T>
  T* writable(const T* p) {
    return storage_ ? const_cast<T*>(p) : nullptr;
  }

  Kind kind_ = Kind::kRegion;
  ViewpointModelParams params_;
  std::uint64_t key_ = 0;
  int n_views_ = 0;
  int n_depth_offsets_ = 0;
  std::shared_ptr<const void> storage_;  ///< the block of all arrays (null: a default-constructed model)
  const unsigned char* payload_ = nullptr;
  const ModelView* views_ = nullptr;
  const int* counts_ = nullptr;         ///< valid points per view (<= n_points)
  const ModelPoint* points_ = nullptr;  ///< n_views * n_points, row per view
  const float* depth_offsets_ = nullptr;
  std::shared_ptr<ViewSupply> supply_;  ///< null: every view is made
};

}  // namespace icgp
