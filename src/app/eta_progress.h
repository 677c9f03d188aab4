// SPDX-License-Identifier: GPL-2.0-or-later
// "[3/10, elapsed 12 s, ETA 28 s]": how far a long command is and an estimate of the time
// left, for its progress lines (servo trials, sweeps and replays).
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace icgp::app {

/// Counts the units of work done (trials, frames) of `total`, from its construction.
class EtaProgress {
 public:
  explicit EtaProgress(long long total) : total_(total), begin_(std::chrono::steady_clock::now()) {}

  /// One more unit done: the bracket, the time left extrapolated from the mean time of a
  /// unit so far.
  std::string done() {
    ++done_;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin_).count();
    const double left = elapsed / done_ * (total_ - done_);
    char text[96];
    std::snprintf(text, sizeof text, "[%lld/%lld, elapsed %.0f s, ETA %.0f s]", done_, total_, elapsed, left);
    return text;
  }

 private:
  long long total_, done_ = 0;
  std::chrono::steady_clock::time_point begin_;
};

}  // namespace icgp::app
