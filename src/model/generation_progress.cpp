// SPDX-License-Identifier: GPL-2.0-or-later
#include "generation_progress.h"

#include <iomanip>
#include <iostream>
#include <sstream>

namespace icgp {

GenerationProgress::GenerationProgress(std::string label, int n_views, bool enabled)
    : label_(std::move(label)), n_views_(n_views), enabled_(enabled), start_(Clock::now()), last_print_(start_) {}

void GenerationProgress::view_done() {
  const int done = ++done_;
  if (!enabled_) return;
  const auto now = Clock::now();
  std::lock_guard<std::mutex> lock(mutex_);
  if (done < n_views_ && now - last_print_ < kInterval) return;
  last_print_ = now;
  std::ostringstream line;  // one write, so lines of concurrent generations do not interleave
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  line << label_ << ": " << done << "/" << n_views_ << " views, " << std::fixed << std::setprecision(1) << elapsed
       << " s";
  if (done < n_views_) line << ", about " << elapsed / done * (n_views_ - done) << " s left";
  line << "\n";
  std::cerr << line.str() << std::flush;
}

}  // namespace icgp
