// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace icgp {

/// Why a list of named bodies cannot be put in tree order (parents_first).
struct TreeOrderProblem {
  enum class Kind { kUnknownParent, kCycle };
  Kind kind;
  std::size_t body;   ///< the body it is reported at
  std::string chain;  ///< kCycle: the names around the cycle, "a -> b -> a"
};

/// The order of a kinematic forest, or why there is none.
struct TreeOrder {
  std::vector<std::size_t> order;  ///< indices into the list, every parent before its links
  std::optional<TreeOrderProblem> problem;
};

/// Orders bodies `names` whose parents are `parents` (the parent's name, empty for a
/// root) so that every parent comes before its links. A parent among `outside_roots` is
/// not in the list but already placed (a tracker's main body). The first problem found, in
/// list order: a parent that is neither in the list nor an outside root, or a cycle.
TreeOrder parents_first(const std::vector<std::string>& names, const std::vector<std::string>& parents,
                        const std::vector<std::string>& outside_roots = {});

}  // namespace icgp
