// SPDX-License-Identifier: GPL-2.0-or-later
// Bounds on the inputs that size memory: one value each, shared by the scenario files and
// every command of the icgp program, so that a file and an option accept the same images.
// They are far beyond real cameras; their job is to refuse a typo (an extra zero, a
// negative number read as huge) with a message before anything is allocated.
#pragma once

namespace icgp {

/// The longest image side, pixels (twice the width of 4K UHD).
inline constexpr int kMaxImageSide = 8192;
/// The most pixels in one camera image: 8192 x 4096 = 32 Mpx, so 8K UHD (7680 x 4320)
/// fits. One RGB-D frame that size takes 32 Mpx x (3 + 4) bytes = 235 MB.
inline constexpr long long kMaxImagePixels = 8192LL * 4096LL;

}  // namespace icgp
