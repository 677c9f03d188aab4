// SPDX-License-Identifier: GPL-2.0-or-later
// The built-in sequence layouts, registered by SequenceLayouts (sequence_layout.cpp).
#pragma once

#include "icgp/eval/sequence.h"

namespace icgp {

SequenceLayoutEntry icgp_layout();            ///< icgp_layout.cpp
SequenceLayoutEntry visp_blender_layout();    ///< visp_blender_layout.cpp
SequenceLayoutEntry visp_realsense_layout();  ///< visp_realsense_layout.cpp

}  // namespace icgp
