// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <algorithm>
#include <array>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace icgp {

/// The built-in cues. Their names ("region", "depth", "texture", "flow", "edge") are what configuration
/// files, scenarios and vpMbIcgTracker::setModalities select them by, and what the built-in
/// modalities' Modality::name() returns (a cue written elsewhere may name itself freely).
/// kFlow is ViSP's KLT tracker in ICG+'s step (FlowModality); it reads the texture cue's cameras.
/// kEdge is ViSP's moving edges on the model's creases (EdgeModality); it reads the region
/// cue's cameras.
enum class CueKind { kRegion, kDepth, kTexture, kFlow, kEdge };

inline constexpr std::array<CueKind, 5> kCueKinds = {CueKind::kRegion, CueKind::kDepth, CueKind::kTexture,
                                                     CueKind::kFlow, CueKind::kEdge};

inline const std::string& to_string(CueKind kind) {
  static const std::array<std::string, 5> names = {"region", "depth", "texture", "flow", "edge"};
  return names[static_cast<std::size_t>(kind)];
}

/// The cue called `name`; nullopt for any other name.
inline std::optional<CueKind> parse_cue_kind(const std::string& name) {
  for (const CueKind kind : kCueKinds)
    if (to_string(kind) == name) return kind;
  return std::nullopt;
}

/// "region, depth, texture, flow, edge".
inline std::string cue_kind_names() {
  std::string names;
  for (const CueKind kind : kCueKinds) names += (names.empty() ? "" : ", ") + to_string(kind);
  return names;
}

/// Whether `cues` selects `kind`.
inline bool has_cue(const std::vector<CueKind>& cues, CueKind kind) {
  return std::find(cues.begin(), cues.end(), kind) != cues.end();
}

/// Whether `names` is a selection of cues: at least one, every one a cue's name, none twice.
inline bool valid_cue_list(const std::vector<std::string>& names) {
  const std::set<std::string> distinct(names.begin(), names.end());
  const auto known = [](const std::string& name) { return parse_cue_kind(name).has_value(); };
  return !names.empty() && distinct.size() == names.size() && std::all_of(names.begin(), names.end(), known);
}

/// The cues `names` names, in order. Throws std::invalid_argument for the first name that
/// is none: "modality 'x' is not available (available: region, depth, texture, flow, edge)".
inline std::vector<CueKind> parse_cue_list(const std::vector<std::string>& names) {
  std::vector<CueKind> cues;
  for (const std::string& name : names) {
    const std::optional<CueKind> kind = parse_cue_kind(name);
    if (!kind) throw std::invalid_argument("modality '" + name + "' is not available (available: " + cue_kind_names() + ")");
    cues.push_back(*kind);
  }
  return cues;
}

/// The names of `cues`, in order.
inline std::vector<std::string> cue_names(const std::vector<CueKind>& cues) {
  std::vector<std::string> names;
  for (const CueKind kind : cues) names.push_back(to_string(kind));
  return names;
}

/// What valid_cue_list accepts, completing "expected …" in the messages of the files that
/// select cues: "a non-empty list of distinct names from region, depth, texture, flow, edge".
inline const char* cue_list_expected() {
  static const std::string text = "a non-empty list of distinct names from " + cue_kind_names();
  return text.c_str();
}

}  // namespace icgp
