// SPDX-License-Identifier: GPL-2.0-or-later
// The <camera> block of ViSP's tracker XML files, read by ViSP's own parser: what the ViSP
// sequence layouts of icgp::Sequence need, which the core library cannot read itself.
#pragma once

#include <string>

#include "icgp/base/intrinsics.h"
#include "icgp/eval/sequence.h"

namespace icgp {

/// px, py, u0, v0 of the <camera> block of a ViSP tracker XML file as fu, fv, pu, pv (image
/// size left 0), read by vpMbtXmlGenericParser as vpMbGenericTracker::loadConfigFile reads
/// them. What ViSP's parser prints stays quiet. Throws std::runtime_error naming the file
/// and what is wrong: no such file, unreadable, not XML ViSP can parse, no <camera> block or
/// one without <px>, <py>, <u0> or <v0>, px or py not a finite positive number, u0 or v0
/// not finite.
Intrinsics read_visp_camera_xml(const std::string& path);

/// SequenceOptions whose read_camera_xml is read_visp_camera_xml: what a program linking
/// icgp::visp passes to Sequence::open to read every layout.
SequenceOptions visp_sequence_options();

}  // namespace icgp
