// SPDX-License-Identifier: GPL-2.0-or-later
// Private to model generation: models made while they are used.
#pragma once

#include <atomic>
#include <condition_variable>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "generation_progress.h"
#include "icgp/model/viewpoint_model.h"
#include "view_job.h"

namespace icgp {

/// Fills the views of a job on background threads while its models are in use: a view
/// required by a reader is made next (the reader waits for it), the others in the order of
/// their closeness to the view required last, so the views around where a tracker looks are
/// ready before it turns to them. Every view is the one a foreground generation makes, so
/// whatever the order, the complete models are byte-identical to it.
///
/// Once every view is made, `on_complete` runs on the thread that made the last. Destroying
/// it finishes the generation first, on every core (nothing reads the models any more), so
/// that they get cached: a program that ends before them waits for them at exit, unless a
/// stop was requested (StopRequested ends the generation, as any error does).
class BackgroundViews : public ViewSupply {
 public:
  BackgroundViews(std::unique_ptr<ViewJob> job, int n_threads, std::function<void(const ViewJob&)> on_complete);
  ~BackgroundViews() override;
  BackgroundViews(const BackgroundViews&) = delete;
  BackgroundViews& operator=(const BackgroundViews&) = delete;

  void require(int v) override;
  void require_all() override;
  bool complete() const override { return n_ready_.load(std::memory_order_acquire) == job_->n_views(); }

 private:
  enum class State { kPending, kInProgress, kReady };

  void work();
  /// The next view to make, -1 when none is pending. Under mutex_.
  int next_view() const;
  /// Throws the generation's error if it failed. Under mutex_.
  void rethrow_error() const;

  const std::unique_ptr<ViewJob> job_;
  const std::function<void(const ViewJob&)> on_complete_;
  GenerationProgress progress_;
  /// Per view: made (set after its arrays are written; read without the lock).
  const std::unique_ptr<std::atomic<bool>[]> ready_;
  std::atomic<int> n_ready_{0};
  std::atomic<int> focus_{0};  ///< the view required last

  mutable std::mutex mutex_;
  std::vector<State> state_;
  std::vector<int> urgent_;  ///< required, not yet started: the last is made first
  std::exception_ptr error_;
  std::condition_variable view_made_;
  std::vector<std::thread> threads_;
};

}  // namespace icgp
