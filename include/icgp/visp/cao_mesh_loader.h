// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <string>

#include "icgp/base/pose.h"
#include "icgp/base/mesh.h"

namespace icgp {

/// How finely the curved primitives of a .cao model are approximated by triangles.
struct CaoTessellation {
  static constexpr int kMaxSegments = 1024;
  int cylinder_segments = 48;  ///< facets around a cylinder's lateral surface (>= 3)
  int circle_segments = 48;    ///< triangles of a circle's disc (>= 3)
};

/// Reads a ViSP .cao model (or a VRML .wrl model, which ViSP reads through Coin3D and
/// calls back with the same faces and cylinders) with ViSP's own parser (vpMbTracker::loadModel, so load()
/// includes with their t= / tu= transforms behave exactly as in ViSP's trackers) and
/// triangulates what it describes into one MeshPart with the default grey material:
/// * faces (from points or from lines): planar polygons, possibly non-convex, ear-clipped
///   keeping the file's winding (ViSP models list corners counter-clockwise seen from
///   outside, so triangles face outwards);
/// * cylinders: the open lateral surface between the two axis points, no caps, as in ViSP;
/// * circles (`radius p1 p2 p3` in the file): a disc around the centre p1 in the plane of
///   p1, p2, p3, facing along (p2 - p1) x (p3 - p1);
/// * lone 3D lines are skipped: they have no surface.
/// Vertices are T * X for the file's points X (ViSP's optional model transform; for .wrl,
/// to which ViSP applies none, icgp applies it after ViSP's parse).
///
/// Throws std::invalid_argument for a tessellation below 3 segments, and std::runtime_error
/// naming the file when it is missing, cannot be parsed (the message includes what ViSP
/// reported), has a self-intersecting face that cannot be triangulated, a cylinder or circle
/// with a non-positive radius or a circle whose points define no plane, or no surface at all.
/// ViSP reports parse details on std::cerr; they are captured for the message during the
/// call, so other threads should not write to std::cerr meanwhile.
Mesh load_cao_mesh(const std::string& path, const Pose& T = Pose(), const CaoTessellation& tessellation = {});

/// Any mesh by its extension: .cao and .wrl through load_cao_mesh, everything else through the
/// assimp loader (icgp::load_mesh). Vertices are T * (scale * X) for the file's points X
/// whatever the format. Throws as the loader it uses, and std::invalid_argument for a
/// non-positive or non-finite scale.
Mesh load_any_mesh(const std::string& path, double scale = 1.0, const Pose& T = Pose());

}  // namespace icgp
