// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp bench --visp-types`: every tracker type a ViSP program may ask for, with
// vpMbGenericTracker and vpMbIcgTracker on the same frames through the same ViSP-API code.
#pragma once

#include <string>
#include <vector>

#include "icgp/eval/sequence.h"

namespace icgp::app {

struct VispTypesBenchOptions {
  std::vector<std::string> sequences;  ///< each with ground truth for one object; empty: teabox-blender
  int frames = 0;                      ///< per sequence; 0: all
  int rounds = 1;
  std::string summary;  ///< JSON of the rows; empty: none
  SequenceOptions sequence_options;
};

/// Prints, per sequence, tracker types and image kind (grey, colour), both classes' mean and
/// max errors and median ms, and whether vpMbIcgTracker is at least as accurate (every error)
/// at twice the speed or more. Both start at the first frame's ground truth and load the
/// sequence's ViSP XML files (written for the mesh when the sequence has none), as a ViSP
/// program does.
void run_visp_types_bench(const VispTypesBenchOptions& options);

}  // namespace icgp::app
