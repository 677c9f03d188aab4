// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <cmath>

namespace icgp {

/// The nearest integer (halves round up), inline: std::lround is a library call that
/// showed up as 15 % of tracking time in per-pixel loops.
inline int round_to_int(float x) {
  const float y = x + 0.5f;
  const int truncated = static_cast<int>(y);
  return truncated - (y < static_cast<float>(truncated));  // floor(y), also for y < 0
}

/// The smallest multiple of `step` (> 0) that is not below x: the first sample of a
/// sparse grid aligned with the image lattice.
inline int lattice_ceil(float x, int step) {
  const int c = static_cast<int>(std::ceil(x));
  const int multiples = c >= 0 ? (c + step - 1) / step : -(-c / step);
  return multiples * step;
}

}  // namespace icgp
