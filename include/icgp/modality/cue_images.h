// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <string>

#include "icgp/base/body.h"
#include "icgp/base/frame.h"

namespace icgp {

/// The image of colour camera `camera` in `frame` that the cue called `cue` of `body` reads:
/// CV_8UC3 (BGR) or CV_8UC1 (grey). Throws std::invalid_argument naming the cue, the body and
/// the camera when the frame has no such camera or its image is empty or of another type.
const ColorImage& cue_color_image(const Frame& frame, const std::string& camera, const std::string& cue,
                                  const Body& body);

}  // namespace icgp
