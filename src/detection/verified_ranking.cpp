// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/detection/verified_ranking.h"

#include <algorithm>
#include <numeric>

namespace icgp {

std::vector<std::size_t> rank_verified(const std::vector<VerifiedScores>& scores, const VerifiedRanking& ranking) {
  std::vector<std::size_t> order(scores.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  if (order.empty()) return order;
  const auto fit = [&](std::size_t a, std::size_t b) { return scores[a].quality > scores[b].quality; };
  const auto look = [&](std::size_t a, std::size_t b) { return scores[a].appearance > scores[b].appearance; };
  std::stable_sort(order.begin(), order.end(), fit);
  const double floor = scores[order.front()].quality - ranking.quality_margin;
  const auto contenders = std::partition_point(order.begin(), order.end(),
                                               [&](std::size_t i) { return scores[i].quality >= floor; });
  std::stable_sort(order.begin(), contenders, look);
  const double best_look = scores[order.front()].appearance;
  const auto alike = std::partition_point(order.begin(), contenders, [&](std::size_t i) {
    return scores[i].appearance >= best_look - ranking.alike_appearance;
  });
  std::stable_sort(order.begin(), alike, fit);
  return order;
}

}  // namespace icgp
