// SPDX-License-Identifier: GPL-2.0-or-later
#include "background_views.h"

#include <algorithm>
#include <iostream>
#include <optional>
#include <system_error>

namespace icgp {

BackgroundViews::BackgroundViews(std::unique_ptr<ViewJob> job, int n_threads,
                                 std::function<void(const ViewJob&)> on_complete)
    : job_(std::move(job)),
      on_complete_(std::move(on_complete)),
      progress_(job_->label() + " (in the background)", job_->n_views(), job_->options.print_progress),
      ready_(new std::atomic<bool>[job_->n_views()]),
      state_(job_->n_views(), State::kPending) {
  for (int v = 0; v < job_->n_views(); ++v) ready_[v].store(false, std::memory_order_relaxed);
  const int n = std::clamp(n_threads, 1, job_->n_views());
  try {
    for (int t = 0; t < n; ++t) threads_.emplace_back([this] { work(); });
  } catch (...) {  // no thread to be had: stop those started, leave no joinable thread behind
    {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = std::current_exception();
    }
    for (std::thread& t : threads_) t.join();
    throw;
  }
}

BackgroundViews::~BackgroundViews() {
  // Nothing reads the models any more: finish them on every core, so they are cached.
  const int hardware = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  try {
    if (!complete())
      for (int t = static_cast<int>(threads_.size()); t < hardware; ++t) threads_.emplace_back([this] { work(); });
  } catch (const std::system_error&) {
    // No more threads: those running finish the views.
  }
  {
    std::unique_lock<std::mutex> lock(mutex_);
    view_made_.wait(lock, [&] { return complete() || error_; });
  }
  for (std::thread& t : threads_) t.join();
}

void BackgroundViews::require(int v) {
  focus_.store(v, std::memory_order_relaxed);
  if (ready_[v].load(std::memory_order_acquire)) return;
  std::unique_lock<std::mutex> lock(mutex_);
  // Threads run while any view is pending, so one takes it when it finishes its view.
  if (state_[v] == State::kPending) urgent_.push_back(v);
  view_made_.wait(lock, [&] { return state_[v] == State::kReady || error_; });
  rethrow_error();
}

void BackgroundViews::require_all() {
  std::unique_lock<std::mutex> lock(mutex_);
  view_made_.wait(lock, [&] { return complete() || error_; });
  rethrow_error();
}

void BackgroundViews::rethrow_error() const {
  if (error_) std::rethrow_exception(error_);
}

int BackgroundViews::next_view() const {
  for (auto it = urgent_.rbegin(); it != urgent_.rend(); ++it)
    if (state_[*it] == State::kPending) return *it;
  const Eigen::Vector3f& focus = job_->directions[focus_.load(std::memory_order_relaxed)];
  int best = -1;
  float best_dot = -2.f;
  for (int v = 0; v < job_->n_views(); ++v) {
    if (state_[v] != State::kPending) continue;
    const float d = job_->directions[v].dot(focus);
    if (d > best_dot) best_dot = d, best = v;
  }
  return best;
}

void BackgroundViews::work() {
  bool made_last = false;
  try {
    std::optional<ViewFiller> filler;  // its OpenGL context only once there is a view to make
    for (;;) {
      int v;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (error_) return;
        v = next_view();
        if (v < 0) return;  // the others are being made
        state_[v] = State::kInProgress;
        urgent_.erase(std::remove(urgent_.begin(), urgent_.end(), v), urgent_.end());
      }
      if (!filler) filler.emplace(*job_);
      filler->fill(v);
      {
        std::lock_guard<std::mutex> lock(mutex_);
        state_[v] = State::kReady;
        ready_[v].store(true, std::memory_order_release);
        made_last = n_ready_.fetch_add(1, std::memory_order_acq_rel) + 1 == job_->n_views();
      }
      view_made_.notify_all();
      progress_.view_done();
      if (made_last) break;
    }
  } catch (...) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!error_) error_ = std::current_exception();
    }
    view_made_.notify_all();
    return;
  }
  // Outside the generation's errors: the models are complete whatever happens here.
  if (made_last && on_complete_) {
    try {
      on_complete_(*job_);
    } catch (const std::exception& e) {
      std::cerr << "warning: " << job_->label() << ": after its generation: " << e.what() << "\n";
    }
  }
}

}  // namespace icgp
