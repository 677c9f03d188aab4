// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <stdexcept>

namespace icgp {

/// A process-wide request to stop long work (batch servo trials, model generation,
/// benchmarks) at the next safe point, so that what is done can still be written. Set by
/// SIGINT once install_stop_on_sigint() has run, or by request_stop(); long loops poll
/// stop_requested() between units of work.
bool stop_requested();
void request_stop();
void clear_stop_request();

/// Installs a SIGINT handler that requests a stop. A second SIGINT ends the process the
/// default way, so a program that stopped polling can still be interrupted.
void install_stop_on_sigint();

/// Thrown by work that polled stop_requested() and stopped at a safe point: nothing half
/// written is left behind, and the message says what was not finished.
class StopRequested : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace icgp
