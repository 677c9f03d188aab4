// SPDX-License-Identifier: GPL-2.0-or-later
// Tracking times are compared single-threaded, as the paper reports them.
#pragma once

#include <omp.h>

#include <opencv2/core/utility.hpp>

namespace icgp::app {

/// Limits OpenMP (ViSP 3.5 is built with it) and OpenCV's own thread pool (TBB here, used
/// by KLT and image filters) to one thread while alive, then restores both. Without it,
/// vpMbGenericTracker spreads some loops over every core and its times would not compare
/// with a single-threaded tracker's; on a shared machine they would also vary with load.
/// The OpenMP runtime comes in with ViSP (its CMake package adds -fopenmp), which is why
/// this lives in the program rather than in the core library.
class SingleThreadScope {
 public:
  SingleThreadScope() : openmp_threads_(omp_get_max_threads()), opencv_threads_(cv::getNumThreads()) {
    omp_set_num_threads(1);
    cv::setNumThreads(1);
  }
  ~SingleThreadScope() {
    omp_set_num_threads(openmp_threads_);
    cv::setNumThreads(opencv_threads_);
  }
  SingleThreadScope(const SingleThreadScope&) = delete;
  SingleThreadScope& operator=(const SingleThreadScope&) = delete;

 private:
  int openmp_threads_;
  int opencv_threads_;
};

}  // namespace icgp::app
