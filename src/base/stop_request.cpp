// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/base/stop_request.h"

#include <atomic>
#include <csignal>

namespace icgp {
namespace {

// Lock-free, so reading and writing it in a signal handler is defined.
std::atomic<bool> stop_flag{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void on_sigint(int) {
  stop_flag.store(true);
  std::signal(SIGINT, SIG_DFL);
}

}  // namespace

bool stop_requested() { return stop_flag.load(); }
void request_stop() { stop_flag.store(true); }
void clear_stop_request() { stop_flag.store(false); }
void install_stop_on_sigint() { std::signal(SIGINT, on_sigint); }

}  // namespace icgp
