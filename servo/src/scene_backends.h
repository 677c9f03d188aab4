// SPDX-License-Identifier: GPL-2.0-or-later
// The two SceneBackends, which make_scene_backend chooses between.
#pragma once

#include <cstdint>
#include <memory>

#include "icgp/servo/scene_backend.h"

namespace icgp::servo {

/// Pose of a camera moved back along the straight line from `from` towards `to`, where it
/// was `fraction` of the way (translation interpolated, rotation along the geodesic): where
/// an exposure of that fraction of a step began.
vpHomogeneousMatrix pose_along_motion(const vpHomogeneousMatrix& from, const vpHomogeneousMatrix& to, double fraction);

/// icgp's OpenGL renderer (EGL, headless), physically based shading (PhysicalLighting):
/// GGX highlights, the lamps' soft shadows, antialiased edges.
std::unique_ptr<SceneBackend> make_opengl_backend();

/// Blender's Cycles path tracer in a Blender process of its own (servo/blender/cycles_server.py).
std::unique_ptr<SceneBackend> make_cycles_backend(const CyclesSpec& cycles, std::uint64_t seed);

}  // namespace icgp::servo
