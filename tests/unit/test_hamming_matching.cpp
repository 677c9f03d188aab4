// SPDX-License-Identifier: GPL-2.0-or-later
// two_nearest_hamming against an exhaustive count of differing bits: the nearest and
// second nearest of every query, without groups and with them (the second nearest then
// being the nearest of another group than the nearest's).
#include <catch2/catch.hpp>

#include <algorithm>
#include <bitset>
#include <limits>

#include <opencv2/core.hpp>

#include "icgp/features/hamming_matching.h"

namespace icgp {
namespace {

int differing_bits(const cv::Mat& a, const cv::Mat& b) {
  int bits = 0;
  for (int i = 0; i < a.cols; ++i) bits += static_cast<int>(std::bitset<8>(a.at<std::uint8_t>(i) ^ b.at<std::uint8_t>(i)).count());
  return bits;
}

/// The nearest row's distance, and the nearest distance among rows that `other(row)` admits.
template <typename Admit>
int nearest_distance(const cv::Mat& query, const cv::Mat& train, Admit admit) {
  int best = std::numeric_limits<int>::max();
  for (int t = 0; t < train.rows; ++t)
    if (admit(t)) best = std::min(best, differing_bits(query, train.row(t)));
  return best;
}

TEST_CASE("hamming matching: nearest and second nearest as an exhaustive count finds them") {
  cv::RNG rng(7);
  for (const int bytes : {32, 61}) {  // ORB's size (the unrolled path) and an odd one
    cv::Mat train(300, bytes, CV_8U), query(40, bytes, CV_8U);
    rng.fill(train, cv::RNG::UNIFORM, 0, 256);
    rng.fill(query, cv::RNG::UNIFORM, 0, 256);
    train.row(5).copyTo(query.row(0));  // an exact match: distance 0
    std::vector<int> groups(train.rows);
    for (int t = 0; t < train.rows; ++t) groups[t] = t / 3;  // three rows per group

    std::vector<TwoNearest> plain, grouped;
    two_nearest_hamming(query, train, plain);
    two_nearest_hamming(query, train, grouped, &groups);
    REQUIRE(plain.size() == static_cast<std::size_t>(query.rows));
    REQUIRE(grouped.size() == static_cast<std::size_t>(query.rows));
    CHECK(plain[0].train_index == 5);
    CHECK(plain[0].best == 0.f);
    for (int q = 0; q < query.rows; ++q) {
      INFO("bytes " << bytes << ", query " << q);
      const cv::Mat row = query.row(q);
      const int index = plain[q].train_index;
      REQUIRE(index >= 0);
      const int best = nearest_distance(row, train, [](int) { return true; });
      CHECK(plain[q].best == best);
      CHECK(differing_bits(row, train.row(index)) == best);
      CHECK(plain[q].second == nearest_distance(row, train, [&](int t) { return t != index; }));
      CHECK(grouped[q].best == best);
      const int group = groups[grouped[q].train_index];
      CHECK(grouped[q].second == nearest_distance(row, train, [&](int t) { return groups[t] != group; }));
    }
  }
}

}  // namespace
}  // namespace icgp
