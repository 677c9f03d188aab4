// SPDX-License-Identifier: GPL-2.0-or-later
// The link from the control law to the robot: commands arrive late, in order, and are held.
#pragma once

#include <deque>
#include <utility>
#include <vector>
#include <visp3/core/vpColVector.h>

namespace icgp::servo {

/// Simulated times this close are one instant: k·T plus a latency of d·T and (k + d)·T
/// differ by rounding.
inline constexpr double kSameInstant = 1e-9;

/// Velocity commands on their way to the robot (CameraSpec::latency). Each is held from the
/// time it arrives until the next one arrives (a zero-order hold), and none overtakes the
/// one sent before it, as on a real link.
class CommandChannel {
 public:
  /// Holds `initial` (zeros: the robot at rest) until the first command arrives.
  explicit CommandChannel(vpColVector initial);

  /// Sends `velocity` to arrive at `arrival` seconds of simulated time, or with the command
  /// sent before it if that arrives later.
  void send(const vpColVector& velocity, double arrival);

  /// A stretch of time over which one command is held.
  struct Hold {
    double duration = 0.0;  ///< seconds
    vpColVector velocity;
  };
  /// The commands held over the `period` seconds from `from`, in order, with how long each
  /// is held; the commands that arrive in it are consumed. Arrivals within a nanosecond of
  /// a period's start count as at its start, so that a latency of whole frame periods
  /// switches commands on frame times.
  std::vector<Hold> holds(double from, double period);

  /// The command held now.
  const vpColVector& held() const { return held_; }

 private:
  vpColVector held_;
  std::deque<std::pair<double, vpColVector>> in_flight_;  ///< arrival time, command
};

}  // namespace icgp::servo
