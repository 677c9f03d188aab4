// SPDX-License-Identifier: GPL-2.0-or-later
// Ranges of the numeric options of the icgp program. A refusal names the option, the value
// and the range in plain numbers, worded as the scenario files word theirs:
// "--width: expected an integer in [1, 8192], got 2000000000". Every option that sizes
// memory or work is bounded, so that a typo is refused at once instead of hanging.
#pragma once

#include <CLI/CLI.hpp>

#include "icgp/base/resource_limits.h"
#include "icgp/eval/make_sequence.h"
#include "icgp/io/yaml_reader.h"

namespace icgp::app {

/// Integers within [min, max] (1.5 and 10^20 refused too).
CLI::Validator integer_in(long long min, long long max);
/// Numbers within `range`.
CLI::Validator number_in(const yaml::Interval& range);

/// An image side, pixels: [1, kMaxImageSide].
CLI::Validator image_side();
/// Throws std::invalid_argument naming both options unless width x height is at most
/// kMaxImagePixels (each side is checked by image_side()).
void check_image_pixels(int width, int height, const char* width_option, const char* height_option);

// Ranges several commands share.
inline constexpr yaml::Interval kFocalPx = make_sequence_range::kFocal;  ///< focal length, pixels
inline constexpr yaml::Interval kMeshScale = make_sequence_range::kScale;  ///< metres per mesh unit
inline constexpr long long kMaxFramesRead = 1000000;  ///< --frames of a sequence read (first N frames)
/// --frames of a sequence rendered and written (make-sequence, bench --sweep's cells).
inline constexpr long long kMaxFramesWritten = make_sequence_range::kMaxFrames;
inline constexpr long long kMaxRounds = 100;          ///< timing rounds of bench and compare

}  // namespace icgp::app
