// SPDX-License-Identifier: GPL-2.0-or-later
// Private to model generation and the cache: how a model is stored in a cache file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "icgp/model/viewpoint_model.h"

namespace icgp {

/// A model's cache payload: views (ModelView, as in memory), point counts (int32), then per
/// point slot 20 bytes, then per slot n_depth_offsets bytes:
///   * position: 3 floats;
///   * normal: octahedral coordinates as two signed 16-bit numbers (about 0.005° apart);
///   * foreground and background distances: IEEE half floats (0.05 % apart; infinity kept);
///   * depth offsets: one byte each, on a logarithmic scale from 0.1 mm to 200 m (each step
///     5.9 % above the last), rounded up, so an offset is never smaller than measured.
/// 45 bytes per point with the default 25 offsets, where floats take 132: the default
/// region and depth models of an object take 46 MB instead of 135 MB.
///
/// The generator stores exactly these values in memory too (quantise_view), so a model
/// loaded from its file equals the model that was generated, byte for byte.
std::size_t stored_payload_size(const ViewpointModelParams& params);

/// Rounds view v of `model` (a generator's) to the values its cache file keeps.
void quantise_view(ViewpointModel& model, int v);

/// The stored payload of a model (stored_payload_size bytes).
std::string stored_payload(const ViewpointModel& model);

/// A model of `params` with the values of a stored payload (stored_payload_size bytes).
ViewpointModel model_from_stored(ViewpointModel::Kind kind, const ViewpointModelParams& params, std::uint64_t key,
                                 const unsigned char* payload);

}  // namespace icgp
