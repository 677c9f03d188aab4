// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <vector>

namespace icgp {

/// Unit vertices of an icosahedron whose triangles are split into four n_divides times
/// (10 * 4^n_divides + 2 of them, nearly evenly spread), in a fixed order: the 12 icosahedron
/// corners first, then each subdivision's new edge midpoints. From n_divides = 1 on they
/// include the six axis directions ±x, ±y, ±z. Throws std::invalid_argument below 0.
std::vector<Eigen::Vector3f> icosphere_directions(int n_divides);

}  // namespace icgp
