// SPDX-License-Identifier: GPL-2.0-or-later
// The rotations that map a body's mesh onto itself (colours included, or its shape alone).
#pragma once

#include <vector>

#include "icgp/base/mesh.h"
#include "icgp/base/pose.h"

namespace icgp {

/// What a symmetry keeps: the body's look (its shape, texture and part colours), or its shape alone.
enum class Keeping { kAppearance, kShape };

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
/// its turns of 60 degrees. With Keeping::kShape, textures and colours are ignored.
std::vector<Pose> mesh_symmetries(const Mesh& mesh, Keeping keeping = Keeping::kAppearance);

/// An axis of the body frame: through `point`, along the unit `direction`.
struct BodyAxis {
  Eigen::Vector3d point;
  Eigen::Vector3d direction;
};

/// Every axis the shape of `mesh` is round about (its turns of a quarter and of a sixth
/// both map it onto itself: a cylinder, a cone), through its centroid; textures and colours
/// ignored. Empty when the shape has none.
std::vector<BodyAxis> round_axes(const Mesh& mesh);

/// Turns in steps of about `step` radians about each of `axes` (round_axes: contour and
/// depth cannot tell these turns of a labelled can apart, a detector compares them by
/// appearance).
std::vector<Pose> turns_about(const std::vector<BodyAxis>& axes, double step);

/// `reference_T_body` turned about `axis` (of the body frame) to the turn nearest in
/// rotation to `nearest`: of the poses a shape round about the axis fits equally, the one
/// that continues `nearest`.
Pose turned_towards(const Pose& reference_T_body, const BodyAxis& axis, const Pose& nearest);

}  // namespace icgp
