// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/servo/command_channel.h"

#include <algorithm>

namespace icgp::servo {

CommandChannel::CommandChannel(vpColVector initial) : held_(std::move(initial)) {}

void CommandChannel::send(const vpColVector& velocity, double arrival) {
  if (!in_flight_.empty()) arrival = std::max(arrival, in_flight_.back().first);
  in_flight_.emplace_back(arrival, velocity);
}

std::vector<CommandChannel::Hold> CommandChannel::holds(double from, double period) {
  // Times within the period are kept as offsets from its start, so that a period in which
  // nothing changes is held for exactly `period` (the ideal loop's moves, bit for bit).
  std::vector<Hold> stretches;
  double elapsed = 0.0;
  while (!in_flight_.empty() && in_flight_.front().first - from < period - kSameInstant) {
    const double at = std::max(elapsed, in_flight_.front().first - from);
    if (at - elapsed > kSameInstant) {
      stretches.push_back({at - elapsed, held_});
      elapsed = at;
    }
    held_ = in_flight_.front().second;
    in_flight_.pop_front();
  }
  if (period - elapsed > kSameInstant) stretches.push_back({period - elapsed, held_});
  return stretches;
}

}  // namespace icgp::servo
