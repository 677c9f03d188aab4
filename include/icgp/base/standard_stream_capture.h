// SPDX-License-Identifier: GPL-2.0-or-later
// Third-party code (ViSP above all) writes to std::cout and std::cerr what icgp either
// drops (the .cao parser's counts) or turns into its own messages (the parser's reasons for
// failing), and tests read what icgp itself says there: one scoped redirection of a
// standard stream serves all of them.
#pragma once

#include <mutex>
#include <ostream>
#include <sstream>
#include <string>

namespace icgp {

/// Redirects a standard stream (std::cout, std::cerr) into a string while alive.
/// Redirections take turns across threads, so two never swap a stream's buffer crosswise
/// (each would restore the other's); within one thread they nest, the inner one handing
/// the stream back to the outer.
class StandardStreamCapture {
 public:
  explicit StandardStreamCapture(std::ostream& stream)
      : turn_(redirection_mutex()), stream_(stream), previous_(stream.rdbuf(captured_.rdbuf())) {}
  ~StandardStreamCapture() { stream_.rdbuf(previous_); }
  StandardStreamCapture(const StandardStreamCapture&) = delete;
  StandardStreamCapture& operator=(const StandardStreamCapture&) = delete;

  /// What was written to the stream so far.
  std::string text() const { return captured_.str(); }

 private:
  /// One for all streams: a thread that redirects std::cout and then std::cerr cannot
  /// deadlock with one that does it the other way round.
  static std::recursive_mutex& redirection_mutex() {
    static std::recursive_mutex mutex;
    return mutex;
  }

  // Declared first: held before the stream is redirected and until it is given back.
  std::lock_guard<std::recursive_mutex> turn_;
  std::ostream& stream_;
  std::ostringstream captured_;
  std::streambuf* previous_;
};

}  // namespace icgp
