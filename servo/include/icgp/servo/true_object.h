// SPDX-License-Identifier: GPL-2.0-or-later
// The object the simulated scene shows, which need not be the model the tracker loads.
#pragma once

#include <cstdint>

#include "icgp/base/mesh.h"
#include "icgp/servo/scenario.h"

namespace icgp::servo {

/// The mesh of the object as the scene shows it (ObjectSpec: true_model, scale_error,
/// vertex_noise), its noise drawn from `seed`. Without them, the model itself.
Mesh true_object_mesh(const ObjectSpec& object, std::uint64_t seed);

}  // namespace icgp::servo
