// SPDX-License-Identifier: GPL-2.0-or-later
#include "stored_model.h"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace icgp {
namespace {

struct StoredPoint {
  float position[3];
  std::int16_t normal[2];
  std::uint16_t foreground_distance, background_distance;
};
static_assert(sizeof(StoredPoint) == 20, "a stored point is 20 bytes, without padding");

constexpr float kOctScale = 32767.f;

/// sign with sign(0) = +1, as the octahedral fold needs.
float sign_of(float x) { return x >= 0.f ? 1.f : -1.f; }

/// The octahedral fold of the lower hemisphere onto the square's corners.
Eigen::Vector2f folded(const Eigen::Vector2f& p) {
  return {(1.f - std::abs(p.y())) * sign_of(p.x()), (1.f - std::abs(p.x())) * sign_of(p.y())};
}

void encode_normal(const Eigen::Vector3f& n, std::int16_t out[2]) {
  Eigen::Vector2f p = n.head<2>() / n.cwiseAbs().sum();
  if (n.z() < 0.f) p = folded(p);
  for (int i = 0; i < 2; ++i)
    out[i] = static_cast<std::int16_t>(std::lround(std::clamp(p[i], -1.f, 1.f) * kOctScale));
}

Eigen::Vector3f decode_normal(const std::int16_t in[2]) {
  Eigen::Vector2f p(in[0] / kOctScale, in[1] / kOctScale);
  const float z = 1.f - std::abs(p.x()) - std::abs(p.y());
  if (z < 0.f) p = folded(p);
  // + 0: no negative zeros, which would encode to the code of +0 and not come back the same.
  return (Eigen::Vector3f(p.x(), p.y(), z).normalized().array() + 0.f).matrix();
}

std::uint16_t encode_half(float x) { return Eigen::numext::bit_cast<std::uint16_t>(Eigen::half(x)); }
float decode_half(std::uint16_t bits) { return static_cast<float>(Eigen::numext::bit_cast<Eigen::half>(bits)); }

/// The 256 depth offsets a byte stands for: 0, then 0.1 mm · (e^(c·L/255) − 1) up to 200 m.
const std::array<float, 256>& offset_table() {
  static const std::array<float, 256> table = [] {
    constexpr double kSmallest = 1e-4, kLargest = 200.0;  // metres: 2 x the largest sphere_radius
    const double log_range = std::log1p(kLargest / kSmallest);
    std::array<float, 256> t{};
    for (int c = 0; c < 256; ++c) t[c] = static_cast<float>(kSmallest * std::expm1(c * log_range / 255.0));
    return t;
  }();
  return table;
}

/// The smallest code whose offset is not below `offset`.
std::uint8_t encode_offset(float offset) {
  const std::array<float, 256>& t = offset_table();
  const auto it = std::lower_bound(t.begin(), t.end(), offset);
  return static_cast<std::uint8_t>(it == t.end() ? 255 : it - t.begin());
}

StoredPoint encode_point(const ModelPoint& p) {
  StoredPoint s;
  std::memcpy(s.position, p.position.data(), sizeof s.position);
  encode_normal(p.normal, s.normal);
  s.foreground_distance = encode_half(p.foreground_distance);
  s.background_distance = encode_half(p.background_distance);
  return s;
}

ModelPoint decode_point(const StoredPoint& s) {
  ModelPoint p;
  p.position = Eigen::Vector3f(s.position[0], s.position[1], s.position[2]);
  p.normal = decode_normal(s.normal);
  p.foreground_distance = decode_half(s.foreground_distance);
  p.background_distance = decode_half(s.background_distance);
  return p;
}

/// Where the parts of a stored payload start.
struct StoredLayout {
  explicit StoredLayout(const ViewpointModelParams& params)
      : n_views(params.n_views()),
        n_points(params.n_points),
        n_offsets(params.n_depth_offsets()),
        views(0),
        counts(views + n_views * sizeof(ModelView)),
        points(counts + n_views * sizeof(std::int32_t)),
        offsets(points + n_views * n_points * sizeof(StoredPoint)),
        size(offsets + n_views * n_points * n_offsets) {}
  const std::size_t n_views, n_points, n_offsets;
  const std::size_t views, counts, points, offsets, size;
};

}  // namespace

std::size_t stored_payload_size(const ViewpointModelParams& params) { return StoredLayout(params).size; }

void quantise_view(ViewpointModel& model, int v) {
  const int n_offsets = model.n_depth_offsets();
  ModelPoint* points = model.mutable_points() + static_cast<std::size_t>(v) * model.n_points();
  for (int p = 0; p < model.view_point_count(v); ++p) {
    points[p] = decode_point(encode_point(points[p]));
    float* offsets = model.mutable_depth_offsets() + (static_cast<std::size_t>(v) * model.n_points() + p) * n_offsets;
    for (int k = 0; k < n_offsets; ++k) offsets[k] = offset_table()[encode_offset(offsets[k])];
  }
}

std::string stored_payload(const ViewpointModel& model) {
  const StoredLayout layout(model.params());
  std::string out(layout.size, '\0');  // slots past a view's count stay zero
  unsigned char* bytes = reinterpret_cast<unsigned char*>(out.data());
  std::memcpy(bytes + layout.views, &model.view(0), layout.n_views * sizeof(ModelView));
  for (std::size_t v = 0; v < layout.n_views; ++v) {
    const std::int32_t count = model.view_point_count(static_cast<int>(v));
    std::memcpy(bytes + layout.counts + v * sizeof count, &count, sizeof count);
    for (int p = 0; p < count; ++p) {
      const std::size_t slot = v * layout.n_points + p;
      const StoredPoint s = encode_point(model.points(static_cast<int>(v))[p]);
      std::memcpy(bytes + layout.points + slot * sizeof s, &s, sizeof s);
      const float* offsets = model.depth_offsets(static_cast<int>(v), p);
      for (std::size_t k = 0; k < layout.n_offsets; ++k)
        bytes[layout.offsets + slot * layout.n_offsets + k] = encode_offset(offsets[k]);
    }
  }
  return out;
}

ViewpointModel model_from_stored(ViewpointModel::Kind kind, const ViewpointModelParams& params, std::uint64_t key,
                                 const unsigned char* payload) {
  const StoredLayout layout(params);
  ViewpointModel model(kind, params, key);
  std::memcpy(model.mutable_views(), payload + layout.views, layout.n_views * sizeof(ModelView));
  std::memcpy(model.mutable_counts(), payload + layout.counts, layout.n_views * sizeof(std::int32_t));
  const std::array<float, 256>& offset_of = offset_table();
  for (std::size_t v = 0; v < layout.n_views; ++v) {
    // A count out of range is the caller's to report (check_contents): read none of it.
    const int count = std::clamp(model.view_point_count(static_cast<int>(v)), 0, static_cast<int>(layout.n_points));
    for (int p = 0; p < count; ++p) {
      const std::size_t slot = v * layout.n_points + p;
      StoredPoint s;
      std::memcpy(&s, payload + layout.points + slot * sizeof s, sizeof s);
      model.mutable_points()[slot] = decode_point(s);
      const unsigned char* codes = payload + layout.offsets + slot * layout.n_offsets;
      float* offsets = model.mutable_depth_offsets() + slot * layout.n_offsets;
      for (std::size_t k = 0; k < layout.n_offsets; ++k) offsets[k] = offset_of[codes[k]];
    }
  }
  return model;
}

}  // namespace icgp
