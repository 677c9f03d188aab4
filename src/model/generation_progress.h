// SPDX-License-Identifier: GPL-2.0-or-later
// Private to model generation: its progress lines.
#pragma once

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>

namespace icgp {

/// "region+depth model textured_box: 1024/2562 views, 12.0 s, about 18.0 s left" on stderr
/// every few seconds and at the end. Thread-safe.
class GenerationProgress {
 public:
  GenerationProgress(std::string label, int n_views, bool enabled);
  void view_done();

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::seconds kInterval{3};
  const std::string label_;
  const int n_views_;
  const bool enabled_;
  const Clock::time_point start_;
  std::atomic<int> done_{0};
  std::mutex mutex_;
  Clock::time_point last_print_;
};

}  // namespace icgp
