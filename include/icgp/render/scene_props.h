// SPDX-License-Identifier: GPL-2.0-or-later
// The props both simulators put behind the objects (the sequence writer and the servo
// simulator): a clutter texture and a tiled plane to carry it.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "icgp/base/mesh.h"

namespace icgp {

/// The clutter texture behind objects when none is given: random filled rectangles, discs
/// and thick lines on a random base colour (512 x 512, BGR), the same for the same seed.
cv::Mat procedural_clutter_texture(std::uint64_t seed);
/// A square plane of side 2 * half_extent at `z` facing +z, centred on (centre, z), made of
/// tiles of `tile` metres that each map the whole texture, so that the texture repeats
/// without relying on the renderer's wrap mode.
Mesh tiled_plane(const cv::Mat& texture, double half_extent, double tile,
                 const Eigen::Vector2d& centre = Eigen::Vector2d::Zero(), double z = 0.0);

}  // namespace icgp
