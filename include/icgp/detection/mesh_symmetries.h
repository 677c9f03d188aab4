// SPDX-License-Identifier: GPL-2.0-or-later
// The rotations that map a body's mesh onto itself, colours included.
#pragma once

#include <vector>

#include "icgp/base/mesh.h"
#include "icgp/base/pose.h"

namespace icgp {

/// The proper symmetries S of `mesh` other than the identity: rigid motions of the body
/// frame that map its surface onto itself, every point onto one of the same flat colour.
/// A body at T and at T·S shows the same image, so a detection cannot tell the two apart
/// (a two-colour box turned half a turn about its colour boundary's normal, say).
///
/// Found on a sampled surface: candidate turns of 1/2, 1/3, 1/4 and 1/6 about the surface's
/// principal axes and its main face normals, through its centroid, are kept when 99 % of
/// the turned samples land within two sample spacings of a sample of their colour; the
/// group they generate is returned. A textured mesh has none (its print is taken to
/// break any symmetry of its shape); a continuous symmetry (a plain cylinder) comes out as
/// its turns of 60 degrees.
std::vector<Pose> mesh_symmetries(const Mesh& mesh);

}  // namespace icgp
