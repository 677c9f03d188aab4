// SPDX-License-Identifier: GPL-2.0-or-later
// Private to model generation: nearest-surface queries over discs of a rendered view.
#pragma once

#include <opencv2/core/mat.hpp>
#include <vector>

namespace icgp {

/// Max-pyramid of an inverse-depth image (SilhouetteImages::inverse_depth): level l holds
/// the maximum, i.e. the nearest surface, over aligned 2^l x 2^l pixel blocks. It answers
/// "how near does the surface come within r pixels of (u, v)" with a few hundred reads
/// whatever r, where scanning the disc would read up to a million pixels at 2000 px.
///
/// A disc of radius r is read at the level whose blocks are at most r/4 pixels wide (single
/// pixels below 8 px), as all blocks of that level that meet the disc. So the answer is
/// never below the exact maximum over the pixel centres in the disc, and never above the
/// maximum over the disc of radius r + sqrt(2)·r/4 + 1 px: an overreach of at most 36 %.
class InverseDepthPyramid {
 public:
  /// Builds the pyramid of `inverse_depth`, which must outlive the queries and be zero
  /// outside `footprint` (SilhouetteImages). Queries will not use radii below
  /// `smallest_radius` pixels, so finer levels than those radii read are not built.
  void build(const cv::Mat& inverse_depth, const cv::Rect& footprint, float smallest_radius);

  /// maxima[k] = the maximum over the disc of radius (k+1)·radius_step around (u, v), for
  /// k < n. Growing discs at one level only read the blocks the previous disc did not.
  void max_in_discs(float u, float v, float radius_step, int n, float* maxima);

 private:
  int level_for(float radius) const;

  std::vector<cv::Mat> levels_;   ///< levels_[0] shares the input's pixels; empty below finest_
  std::vector<cv::Rect> filled_;  ///< per level, the blocks computed last (all others are 0)
  int finest_ = 0;                ///< finest level built besides level 0
  std::vector<float> row_buffer_;
  /// Per block row of the current level: the columns read so far (first > last: none).
  std::vector<int> read_first_, read_last_;
};

}  // namespace icgp
