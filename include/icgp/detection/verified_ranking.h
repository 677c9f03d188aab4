// SPDX-License-Identifier: GPL-2.0-or-later
// How the detector orders the poses it verified: by their fit, and among those that fit
// nearly as well as the best, by how much their render looks like the image.
#pragma once

#include <cstddef>
#include <vector>

namespace icgp {

/// A verified pose's two scores.
struct VerifiedScores {
  double quality = 0.0;     ///< the refining cues' fit
  double appearance = 0.0;  ///< its render's correlation with the image (0 without appearance)
};

struct VerifiedRanking {
  /// Poses this far below the best fit still compete on look (infinite: all do).
  double quality_margin = 0.0;
  /// Of those, the ones that look within this of the best-looking one look alike, and their
  /// fit ranks them (0: the look alone ranks).
  double alike_appearance = 0.0;
};

/// Indices of `scores`, best first: the contenders (within `quality_margin` of the best
/// fit) before the rest; among the contenders those that look alike, best fit first, then
/// the others by look; the rest by fit. Ties keep their order.
std::vector<std::size_t> rank_verified(const std::vector<VerifiedScores>& scores, const VerifiedRanking& ranking);

}  // namespace icgp
