// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <string>

#include "icgp/base/mesh.h"

namespace icgp {

/// Writes `mesh` as a ViSP .cao model (format V1, "faces from points"), so that ViSP's
/// vpMbGenericTracker can track an object known only as a triangle mesh. Coplanar adjacent
/// triangles are merged into one polygon face, so the model's edges are the mesh's real
/// creases and outlines, not triangulation diagonals (ViSP's moving-edge tracker would look
/// for gradients along every listed edge). Corners are listed counter-clockwise seen from
/// outside, as ViSP expects. Throws std::runtime_error naming `path` when it cannot be
/// written, std::invalid_argument for an empty mesh.
void write_cao(const Mesh& mesh, const std::string& path);

}  // namespace icgp
