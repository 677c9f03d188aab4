// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/eval/sequence_layout.h"

#include <stdexcept>

#include "built_in_layouts.h"

namespace icgp {
namespace {

/// The built-in layouts in probing order. One list here rather than each file registering
/// itself through a static object: the linker drops such objects from a static library
/// when nothing else refers to their file.
std::vector<SequenceLayoutEntry> built_in() { return {icgp_layout(), visp_blender_layout(), visp_realsense_layout()}; }

}  // namespace

SequenceLayouts::SequenceLayouts() {
  for (SequenceLayoutEntry& entry : built_in()) add(std::move(entry));
}

SequenceLayouts& SequenceLayouts::instance() {
  static SequenceLayouts layouts;
  return layouts;
}

void SequenceLayouts::add(SequenceLayoutEntry entry) {
  if (entry.name.empty()) throw std::invalid_argument("sequence layouts: a layout needs a name");
  for (const SequenceLayoutEntry& e : entries_)
    if (e.name == entry.name)
      throw std::invalid_argument("sequence layouts: a layout named '" + entry.name + "' is registered already");
  if (!entry.probe || !entry.open)
    throw std::invalid_argument("sequence layouts: layout '" + entry.name + "' needs a probe and an open function");
  entries_.push_back(std::move(entry));
}

}  // namespace icgp
