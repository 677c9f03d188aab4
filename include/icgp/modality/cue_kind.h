// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <algorithm>
#include <string>
#include <vector>

namespace icgp {

/// The names of the built-in cues: what configuration files, scenarios and
/// vpMbIcgTracker::setModalities select them by, what their Modality::name() returns, and
/// their keys in the cue registry (icgp/tracker/cue_registry.h), where a user's own cues
/// join them. kFlow is ViSP's KLT tracker in ICG+'s step (FlowModality); kEdge ViSP's
/// moving edges on the model's creases (EdgeModality).
namespace cue {
inline constexpr const char* kRegion = "region";
inline constexpr const char* kDepth = "depth";
inline constexpr const char* kTexture = "texture";
inline constexpr const char* kFlow = "flow";
inline constexpr const char* kEdge = "edge";
}  // namespace cue

/// Whether `cues` selects the cue called `name`.
inline bool has_cue(const std::vector<std::string>& cues, const std::string& name) {
  return std::find(cues.begin(), cues.end(), name) != cues.end();
}

}  // namespace icgp
