// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/servo/true_object.h"

#include <cmath>

#include "icgp/base/splitmix64.h"
#include "icgp/visp/cao_mesh_loader.h"

namespace icgp::servo {
namespace {

/// The seed's stream of vertex noise (icgp::seeded_stream purposes are per use).
constexpr std::uint64_t kVertexNoiseStream = 18;
/// Vertices closer than this are one point of the surface (a box's corner repeated per face
/// for its texture coordinates): they move together.
constexpr double kSamePointMetres = 1e-6;

/// A displacement of standard deviation `sigma` per axis that depends only on where the
/// vertex is (and the seed).
Eigen::Vector3f displacement(const Eigen::Vector3f& vertex, double sigma, std::uint64_t seed) {
  std::uint64_t key = 0;
  for (int axis = 0; axis < 3; ++axis)
    key = key * 0x100000001B3ull ^ static_cast<std::uint64_t>(std::llround(vertex[axis] / kSamePointMetres));
  SplitMix64 random = seeded_stream(seed, kVertexNoiseStream, key);
  return Eigen::Vector3f(static_cast<float>(sigma * random.normal()), static_cast<float>(sigma * random.normal()),
                         static_cast<float>(sigma * random.normal()));
}

}  // namespace

Mesh true_object_mesh(const ObjectSpec& object, std::uint64_t seed) {
  Mesh mesh = load_any_mesh(object.true_model.empty() ? object.model : object.true_model, 1.0 + object.scale_error);
  if (object.vertex_noise > 0.0)
    for (MeshPart& part : mesh.parts)
      for (Eigen::Vector3f& v : part.vertices) v += displacement(v, object.vertex_noise, seed);
  return mesh;
}

}  // namespace icgp::servo
