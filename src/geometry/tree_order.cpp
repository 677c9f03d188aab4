// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/geometry/tree_order.h"

#include <algorithm>
#include <map>

namespace icgp {

TreeOrder parents_first(const std::vector<std::string>& names, const std::vector<std::string>& parents,
                        const std::vector<std::string>& outside_roots) {
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < names.size(); ++i) index[names[i]] = i;
  auto outside = [&](const std::string& name) {
    return std::find(outside_roots.begin(), outside_roots.end(), name) != outside_roots.end();
  };
  TreeOrder result;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (parents[i].empty()) continue;
    if (!index.count(parents[i]) && !outside(parents[i])) {
      result.problem = TreeOrderProblem{TreeOrderProblem::Kind::kUnknownParent, i, ""};
      return result;
    }
    // Walk up the parents: reaching the body again closes a cycle. A chain without one has
    // fewer steps than there are bodies; a cycle above this body is reported at its bodies.
    std::string chain = names[i];
    std::size_t up = i;
    for (std::size_t step = 0; step < names.size() && index.count(parents[up]); ++step) {
      up = index.at(parents[up]);
      chain += " -> " + names[up];
      if (up == i) {
        result.problem = TreeOrderProblem{TreeOrderProblem::Kind::kCycle, i, chain};
        return result;
      }
    }
  }
  std::vector<bool> placed(names.size(), false);
  auto parent_placed = [&](std::size_t i) {
    return parents[i].empty() || !index.count(parents[i]) || placed[index.at(parents[i])];
  };
  while (result.order.size() < names.size())
    for (std::size_t i = 0; i < names.size(); ++i)
      if (!placed[i] && parent_placed(i)) {
        placed[i] = true;
        result.order.push_back(i);
      }
  return result;
}

}  // namespace icgp
