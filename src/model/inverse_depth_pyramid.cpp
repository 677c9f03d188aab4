// SPDX-License-Identifier: GPL-2.0-or-later
#include "inverse_depth_pyramid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace icgp {
namespace {

// Blocks at most radius / 4 wide: about 9 to 17 block rows per disc, and an overreach of
// at most a third of the radius.
constexpr float kBlocksPerRadius = 4.f;

/// The blocks of `coarse` in `blocks` become the maxima over the aligned factor x factor
/// blocks of `fine` (partial blocks at the image edges).
void downsample_max(const cv::Mat& fine, int factor, const cv::Rect& blocks, cv::Mat& coarse,
                    std::vector<float>& row_buffer) {
  const int col_first = blocks.x * factor, col_end = std::min(blocks.br().x * factor, fine.cols);
  const int width = col_end - col_first;
  row_buffer.resize(width);
  for (int i = blocks.y; i < blocks.br().y; ++i) {
    // Rows first: a contiguous, vectorisable maximum; then groups of `factor` columns.
    std::copy_n(fine.ptr<float>(i * factor) + col_first, width, row_buffer.begin());
    for (int r = i * factor + 1; r < std::min((i + 1) * factor, fine.rows); ++r) {
      const float* row = fine.ptr<float>(r) + col_first;
      for (int j = 0; j < width; ++j) row_buffer[j] = std::max(row_buffer[j], row[j]);
    }
    float* out = coarse.ptr<float>(i) + blocks.x;
    const int whole_blocks = width / factor;
    if (factor == 2) {  // every level but the finest: a loop the compiler vectorises
      for (int j = 0; j < whole_blocks; ++j) out[j] = std::max(row_buffer[2 * j], row_buffer[2 * j + 1]);
    } else {
      for (int j = 0; j < whole_blocks; ++j)
        out[j] = *std::max_element(row_buffer.begin() + j * factor, row_buffer.begin() + (j + 1) * factor);
    }
    if (whole_blocks < blocks.width)
      out[whole_blocks] = *std::max_element(row_buffer.begin() + whole_blocks * factor, row_buffer.end());
  }
}

/// The blocks of size 2^level that cover `pixels`.
cv::Rect covering_blocks(const cv::Rect& pixels, int level) {
  if (pixels.empty()) return {};
  const int x0 = pixels.x >> level, y0 = pixels.y >> level;
  return {x0, y0, ((pixels.br().x - 1) >> level) - x0 + 1, ((pixels.br().y - 1) >> level) - y0 + 1};
}

/// max(best, values[first..last]) with independent partial maxima: a single running
/// maximum would wait on each comparison's latency.
float max_of(float best, const float* values, int first, int last) {
  float m[4] = {best, best, best, best};
  int j = first;
  for (; j + 3 <= last; j += 4)
    for (int q = 0; q < 4; ++q) m[q] = std::max(m[q], values[j + q]);
  for (; j <= last; ++j) m[0] = std::max(m[0], values[j]);
  return std::max(std::max(m[0], m[1]), std::max(m[2], m[3]));
}

}  // namespace

int InverseDepthPyramid::level_for(float radius) const {
  int level = 0;
  while (level + 1 < static_cast<int>(levels_.size()) && static_cast<float>(2 << level) * kBlocksPerRadius <= radius)
    ++level;
  return level == 0 ? 0 : std::max(level, finest_);
}

void InverseDepthPyramid::build(const cv::Mat& inverse_depth, const cv::Rect& footprint, float smallest_radius) {
  CV_Assert(inverse_depth.type() == CV_32FC1);
  std::size_t n = 1;
  for (int size = std::max(inverse_depth.rows, inverse_depth.cols); size > 1; size = (size + 1) / 2) ++n;
  levels_.resize(n);
  filled_.resize(n);
  levels_[0] = inverse_depth;
  finest_ = 0;  // level_for() without a floor gives the level the smallest radius reads
  finest_ = std::max(level_for(smallest_radius), n > 1 ? 1 : 0);
  for (std::size_t l = std::max(finest_, 1); l < n; ++l) {
    const int size = 1 << l;
    const cv::Size level_size((inverse_depth.cols + size - 1) / size, (inverse_depth.rows + size - 1) / size);
    if (levels_[l].size() != level_size) {
      levels_[l] = cv::Mat::zeros(level_size, CV_32FC1);
      filled_[l] = cv::Rect();
    }
    // Outside the footprint all is 0: clear what the last image filled, compute the footprint.
    if (!filled_[l].empty()) levels_[l](filled_[l]).setTo(0);
    filled_[l] = covering_blocks(footprint, static_cast<int>(l));
    if (filled_[l].empty()) continue;
    // The finest level straight from the image: reading the image once is most of the cost.
    if (static_cast<int>(l) == finest_)
      downsample_max(inverse_depth, size, filled_[l], levels_[l], row_buffer_);
    else
      downsample_max(levels_[l - 1], 2, filled_[l], levels_[l], row_buffer_);
  }
  read_first_.assign(levels_[0].rows, 1);
  read_last_.assign(levels_[0].rows, 0);
}

void InverseDepthPyramid::max_in_discs(float u, float v, float radius_step, int n, float* maxima) {
  float best = 0.f;
  int level = -1, touched_first = 0, touched_last = -1;
  auto forget_read_columns = [&] {
    for (int i = touched_first; i <= touched_last; ++i) read_first_[i] = 1, read_last_[i] = 0;
    touched_first = std::numeric_limits<int>::max();
    touched_last = -1;
  };
  for (int k = 0; k < n; ++k) {
    const float radius = static_cast<float>(k + 1) * radius_step;
    const int l = level_for(radius);
    if (l != level) {  // a coarser level: its blocks cover what the finer ones read, start over
      forget_read_columns();
      level = l;
    }
    const cv::Mat& blocks = levels_[level];
    const float b = static_cast<float>(1 << level), inverse_b = 1.f / b;  // exact: b is a power of two
    // A block covers the pixel centres [b·i, b·i + b - 1]: it meets the disc when that range
    // comes within the disc's half-width at the block row's nearest pixel row. Truncation
    // is the floor here: negative quotients are clamped to 0 anyway.
    const int row_first = std::max(0, static_cast<int>((v - radius) * inverse_b));
    const int row_last = std::min(blocks.rows - 1, static_cast<int>((v + radius) * inverse_b));
    touched_first = std::min(touched_first, row_first);
    touched_last = std::max(touched_last, row_last);
    for (int i = row_first; i <= row_last; ++i) {
      const float dy = std::max(0.f, std::max(b * i - v, v - (b * i + b - 1.f)));
      if (dy > radius) continue;
      const float half_width = std::sqrt(radius * radius - dy * dy);
      const int first = std::max(0, static_cast<int>((u - half_width) * inverse_b));
      const int last = std::min(blocks.cols - 1, static_cast<int>((u + half_width) * inverse_b));
      const float* row = blocks.ptr<float>(i);
      const bool none_read = read_first_[i] > read_last_[i];
      // The disc only grows: read the columns left and right of those read before.
      best = max_of(best, row, first, none_read ? last : read_first_[i] - 1);
      if (!none_read) best = max_of(best, row, read_last_[i] + 1, last);
      read_first_[i] = none_read ? first : std::min(first, read_first_[i]);
      read_last_[i] = none_read ? last : std::max(last, read_last_[i]);
    }
    maxima[k] = best;
  }
  forget_read_columns();
}

}  // namespace icgp
