// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <cstdint>
#include <vector>

#include "icgp/base/mesh.h"
#include "icgp/model/viewpoint_model.h"
#include "icgp/model/viewpoint_model_generator.h"

namespace icgp {

/// Version of how viewpoint models are generated and stored. It is part of every key: bump it
/// whenever generation or the cache file format changes, and old cache files are regenerated.
constexpr std::uint32_t kViewpointModelVersion = 2;

/// Identity of a viewpoint model: 64-bit FNV-1a over the mesh geometry (every vertex and
/// triangle of every part, in order; not its file name or materials), every field of
/// `params`, the kind and kViewpointModelVersion. Equal keys mean interchangeable models.
std::uint64_t viewpoint_model_key(ViewpointModel::Kind kind, const Mesh& mesh, const ViewpointModelParams& params);

/// The key of a model generated with these associated bodies (ModelGenerationOptions):
/// for a region model with associated bodies, the key above followed by each body's kind,
/// same_region_fixed, pose and geometry, in order; otherwise (depth models, or none) exactly
/// the key above, as associated bodies do not change those models.
std::uint64_t viewpoint_model_key(ViewpointModel::Kind kind, const Mesh& mesh, const ViewpointModelParams& params,
                                  const std::vector<AssociatedBody>& associated_bodies);

}  // namespace icgp
