// SPDX-License-Identifier: GPL-2.0-or-later
// A Blender process in the background, driven line by line: what the Cycles backend renders with.
#pragma once

#include <string>
#include <sys/types.h>

namespace icgp::servo {

/// The Blender executable to run: $ICGP_BLENDER when set, else `blender` on the PATH.
/// Throws std::runtime_error saying how to install it when there is none.
std::string blender_executable();

/// One Blender started once in the background (`blender -b --factory-startup`) running a
/// Python script that answers requests: each request is one line on the script's standard
/// input, and the script answers it with one line, "ok" or "error <message>", on the file
/// descriptor whose number follows `--` on its command line. Blender's own messages go to
/// `log_file`. Nothing waits without bound: an answer that does not come within
/// `timeout_s`, or a Blender that exits, ends the process and throws with its last messages.
class BlenderProcess {
 public:
  BlenderProcess(const std::string& script, const std::string& log_file, double timeout_s);
  /// Asks the script to finish, then ends the process if it does not.
  ~BlenderProcess();
  BlenderProcess(const BlenderProcess&) = delete;
  BlenderProcess& operator=(const BlenderProcess&) = delete;

  /// Sends `line` (without its newline) and waits for the answer. Throws std::runtime_error
  /// with the script's error or Blender's last messages; after a crash or a timeout the
  /// process is gone and every later request throws at once.
  void request(const std::string& line);

 private:
  [[noreturn]] void fail(const std::string& what);
  std::string last_messages() const;

  std::string log_file_;
  double timeout_s_;
  pid_t pid_ = -1;
  int socket_ = -1;  ///< our end of the socket pair that is the script's stdin and answer channel
  std::string received_;
};

}  // namespace icgp::servo
