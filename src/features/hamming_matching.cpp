// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/features/hamming_matching.h"

#include <cstdint>
#include <cstring>
#include <limits>

namespace icgp {
namespace {

/// Hamming distance of two binary descriptors of `bytes` bytes, 64 bits at a time.
inline int hamming(const std::uint8_t* a, const std::uint8_t* b, int bytes) {
  int distance = 0, i = 0;
  for (; i + 8 <= bytes; i += 8) {
    std::uint64_t x, y;
    std::memcpy(&x, a + i, 8);
    std::memcpy(&y, b + i, 8);
    distance += __builtin_popcountll(x ^ y);
  }
  for (; i < bytes; ++i) distance += __builtin_popcount(static_cast<unsigned>(a[i] ^ b[i]));
  return distance;
}

/// The distance is inlined and the bookkeeping integer: OpenCV's per-pair call made
/// matching 300 x 300 ORB descriptors cost 0.7 ms; this takes 0.1 ms. kBytes > 0 fixes the
/// descriptor size at compile time so that the popcounts unroll (ORB: 32 bytes); 0 takes it
/// from the matrix. The second nearest of another group is kept exactly: when a new nearest
/// of another group comes, the old nearest is the best of the rest.
template <int kBytes, bool kGrouped>
__attribute__((always_inline)) inline void two_nearest_rows(const cv::Mat& query, const cv::Mat& train,
                                                            std::vector<TwoNearest>& out, const int* groups) {
  const int bytes = kBytes > 0 ? kBytes : query.cols;
  for (int q = 0; q < query.rows; ++q) {
    const std::uint8_t* a = query.ptr<std::uint8_t>(q);
    int best = std::numeric_limits<int>::max(), second = best, index = -1;
    for (int t = 0; t < train.rows; ++t) {
      const int d = hamming(a, train.ptr<std::uint8_t>(t), bytes);
      if (d >= second) continue;
      const bool same_group = kGrouped && index >= 0 && groups[t] == groups[index];
      if (d < best) {
        if (!same_group) second = best;
        best = d;
        index = t;
      } else if (!same_group) {
        second = d;
      }
    }
    out[q] = {index, static_cast<float>(best), static_cast<float>(second)};
  }
}

template <bool kGrouped>
__attribute__((always_inline)) inline void two_nearest_any_size(const cv::Mat& query, const cv::Mat& train,
                                                                std::vector<TwoNearest>& out, const int* groups) {
  if (query.cols == 32)
    two_nearest_rows<32, kGrouped>(query, train, out, groups);
  else
    two_nearest_rows<0, kGrouped>(query, train, out, groups);
}

}  // namespace

/// Compiled twice (hardware popcount, and baseline x86-64 without it), picked at load time;
/// everything it calls is inlined into each clone, or the popcounts would be the
/// baseline's.
__attribute__((target_clones("popcnt", "default"))) void two_nearest_hamming(const cv::Mat& query, const cv::Mat& train,
                                                                             std::vector<TwoNearest>& out,
                                                                             const std::vector<int>* groups) {
  CV_Assert(query.type() == CV_8U && train.type() == CV_8U && (train.empty() || query.cols == train.cols));
  CV_Assert(!groups || static_cast<int>(groups->size()) == train.rows);
  out.resize(query.rows);
  if (groups)
    two_nearest_any_size<true>(query, train, out, groups->data());
  else
    two_nearest_any_size<false>(query, train, out, nullptr);
}

}  // namespace icgp
