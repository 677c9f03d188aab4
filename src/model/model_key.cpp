// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/model/model_key.h"

#include <type_traits>

namespace icgp {
namespace {

/// FNV-1a, fed value by value so that struct padding never enters the hash.
class Fnv1a {
 public:
  void bytes(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) hash_ = (hash_ ^ p[i]) * 0x100000001b3ull;
  }
  template <typename T>
  void value(const T& v) {
    static_assert(std::is_arithmetic_v<T>, "hash plain numbers only");
    bytes(&v, sizeof v);
  }
  std::uint64_t hash() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

void hash_geometry(Fnv1a& h, const Mesh& mesh) {
  h.value(static_cast<std::uint64_t>(mesh.parts.size()));
  for (const auto& part : mesh.parts) {
    // Counts separate the parts, so moving a vertex from one part to the next changes the key.
    h.value(static_cast<std::uint64_t>(part.vertices.size()));
    for (const auto& v : part.vertices) h.bytes(v.data(), 3 * sizeof(float));
    h.value(static_cast<std::uint64_t>(part.triangles.size()));
    for (const auto& t : part.triangles) h.bytes(t.data(), 3 * sizeof(int));
  }
}

Fnv1a single_body_hash(ViewpointModel::Kind kind, const Mesh& mesh, const ViewpointModelParams& params) {
  Fnv1a h;
  h.value(kViewpointModelVersion);
  h.value(static_cast<std::uint32_t>(kind));
  h.value(params.n_divides);
  h.value(params.sphere_radius);
  h.value(params.image_size);
  h.value(params.image_margin);
  h.value(params.n_points);
  h.value(params.stride_depth_offset);
  h.value(params.max_radius_depth_offset);
  h.value(params.min_contour_length);
  h.value(params.normal_chord_offset);
  h.value(params.seed);
  hash_geometry(h, mesh);
  return h;
}

}  // namespace

std::uint64_t viewpoint_model_key(ViewpointModel::Kind kind, const Mesh& mesh, const ViewpointModelParams& params) {
  return single_body_hash(kind, mesh, params).hash();
}

std::uint64_t viewpoint_model_key(ViewpointModel::Kind kind, const Mesh& mesh, const ViewpointModelParams& params,
                                  const std::vector<AssociatedBody>& associated_bodies) {
  Fnv1a h = single_body_hash(kind, mesh, params);
  if (kind != ViewpointModel::Kind::kRegion || associated_bodies.empty()) return h.hash();
  h.value(static_cast<std::uint64_t>(associated_bodies.size()));
  for (const AssociatedBody& body : associated_bodies) {
    h.value(static_cast<std::uint32_t>(body.kind));
    h.value(static_cast<std::uint8_t>(body.same_region_fixed ? 1 : 0));
    const Eigen::Matrix3d& R = body.main_T_body.rotation();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) h.value(R(i, j));
    for (int i = 0; i < 3; ++i) h.value(body.main_T_body.translation()[i]);
    hash_geometry(h, body.mesh);
  }
  return h.hash();
}

}  // namespace icgp
