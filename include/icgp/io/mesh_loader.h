// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <cstddef>
#include <string>

#include "icgp/base/mesh.h"

namespace icgp {

/// Mesh files larger than this are refused before assimp reads them.
constexpr std::size_t kMaxMeshFileBytes = std::size_t(1) << 30;

struct MeshLoadOptions {
  /// Factor applied to every vertex, e.g. 0.001 for a model authored in millimetres.
  double scale = 1.0;
};

/// Loads any triangle-mesh format assimp reads (.obj, .ply, .stl, .gltf, .glb, .dae, ...)
/// with node transforms applied, as one MeshPart per assimp mesh. Point and line
/// primitives are dropped. Each part keeps texture coordinates (channel 0, (0,0) at the
/// bottom-left of the image, not flipped), the material's diffuse colour and its diffuse
/// texture (a file relative to the model's folder or embedded in the model) as BGR.
/// Throws std::invalid_argument for a non-positive or non-finite scale or a mesh check_mesh
/// refuses (a NaN vertex, too many triangles...), and std::runtime_error, naming the file,
/// when it is missing, larger than kMaxMeshFileBytes, unreadable, has no triangles or
/// refers to a texture that cannot be read.
Mesh load_mesh(const std::string& path, const MeshLoadOptions& options = {});

}  // namespace icgp
