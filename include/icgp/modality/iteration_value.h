// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "icgp/model/viewpoint_model.h"

namespace icgp {

/// Entry `iteration` of an iteration-indexed parameter list, its last entry afterwards
/// (ALGORITHMS.md §2). Lists are validated non-empty when the configuration is read.
template <typename T>
T iteration_value(const std::vector<T>& values, int iteration) {
  return values[std::min<std::size_t>(static_cast<std::size_t>(iteration), values.size() - 1)];
}

/// Index of the model's depth offset whose radius is closest to `radius`.
inline int depth_offset_index(const ViewpointModel& model, double radius) {
  const int k = static_cast<int>(std::lround(radius / model.params().stride_depth_offset)) - 1;
  return std::clamp(k, 0, model.n_depth_offsets() - 1);
}

}  // namespace icgp
