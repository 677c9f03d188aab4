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

}  // namespace

std::uint64_t viewpoint_model_key(ViewpointModel::Kind kind, const Mesh& mesh, const ViewpointModelParams& params) {
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
  h.value(static_cast<std::uint64_t>(mesh.parts.size()));
  for (const auto& part : mesh.parts) {
    // Counts separate the parts, so moving a vertex from one part to the next changes the key.
    h.value(static_cast<std::uint64_t>(part.vertices.size()));
    for (const auto& v : part.vertices) h.bytes(v.data(), 3 * sizeof(float));
    h.value(static_cast<std::uint64_t>(part.triangles.size()));
    for (const auto& t : part.triangles) h.bytes(t.data(), 3 * sizeof(int));
  }
  return h.hash();
}

}  // namespace icgp
