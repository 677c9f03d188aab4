// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/servo/blender_process.h"

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <deque>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <poll.h>
#include <spawn.h>
#include <stdexcept>
#include <sys/socket.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "icgp/io/yaml_reader.h"

extern char** environ;

namespace icgp::servo {
namespace {

/// Lines of Blender's log quoted in an error.
constexpr int kQuotedLogLines = 12;
/// How long Blender may take to finish after "quit" before it is killed.
constexpr auto kQuitGrace = std::chrono::seconds(5);

bool is_executable(const std::string& path) { return ::access(path.c_str(), X_OK) == 0; }

/// Waits up to `grace` for the child to exit; true when it did (and was reaped).
bool reaped_within(pid_t pid, std::chrono::milliseconds grace) {
  const auto deadline = std::chrono::steady_clock::now() + grace;
  int status = 0;
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

}  // namespace

std::string blender_executable() {
  if (const char* chosen = std::getenv("ICGP_BLENDER"); chosen && *chosen) {
    if (!is_executable(chosen))
      throw std::runtime_error(std::string("ICGP_BLENDER is ") + chosen + ", which is not an executable program");
    return chosen;
  }
  if (const char* path = std::getenv("PATH")) {
    std::string folders = path;
    for (std::size_t start = 0; start <= folders.size();) {
      const std::size_t end = std::min(folders.find(':', start), folders.size());
      const std::string candidate = (std::filesystem::path(folders.substr(start, end - start)) / "blender").string();
      if (end > start && is_executable(candidate)) return candidate;
      start = end + 1;
    }
  }
  throw std::runtime_error(
      "camera.renderer cycles renders with Blender's Cycles, and no `blender` program is on the PATH: install it "
      "with `scripts/setup --cycles` (Debian 12: apt install blender), or set ICGP_BLENDER to its path");
}

BlenderProcess::BlenderProcess(const std::string& script, const std::string& log_file, double timeout_s)
    : log_file_(log_file), timeout_s_(timeout_s) {
  const std::string executable = blender_executable();
  int ends[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, ends) != 0)
    throw std::runtime_error("cannot make a socket to talk to Blender");
  const int log = ::open(log_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (log < 0) {
    ::close(ends[0]);
    ::close(ends[1]);
    throw std::runtime_error(log_file + ": cannot write Blender's log there");
  }
  // The script reads its requests on stdin and answers on descriptor 3: both are our socket.
  constexpr int kAnswerDescriptor = 3;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, ends[1], 0);
  posix_spawn_file_actions_adddup2(&actions, log, 1);
  posix_spawn_file_actions_adddup2(&actions, log, 2);
  posix_spawn_file_actions_adddup2(&actions, ends[1], kAnswerDescriptor);
  std::vector<std::string> arguments = {executable, "-b",     "--factory-startup", "-noaudio", "--python-exit-code",
                                        "1",        "--python", script,             "--",       std::to_string(kAnswerDescriptor)};
  std::vector<char*> argv;
  for (std::string& a : arguments) argv.push_back(a.data());
  argv.push_back(nullptr);
  // A process group of its own: Ctrl-C stops the run at its next step, which then ends
  // Blender; Blender must not die of the same signal first and fail that step.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  const int spawned = ::posix_spawn(&pid_, executable.c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  ::close(ends[1]);
  ::close(log);
  socket_ = ends[0];
  if (spawned != 0) {
    ::close(socket_);
    socket_ = -1;
    pid_ = -1;
    throw std::runtime_error(executable + ": cannot start Blender");
  }
}

BlenderProcess::~BlenderProcess() {
  if (pid_ > 0) {
    const std::string quit = "{\"op\": \"quit\"}\n";
    ::send(socket_, quit.data(), quit.size(), MSG_NOSIGNAL);
    if (!reaped_within(pid_, kQuitGrace)) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  if (socket_ >= 0) ::close(socket_);
}

void BlenderProcess::request(const std::string& line) {
  if (pid_ <= 0) throw std::runtime_error("Blender is no longer running (it failed on an earlier request)");
  const std::string message = line + "\n";
  for (std::size_t sent = 0; sent < message.size();) {
    const ssize_t n = ::send(socket_, message.data() + sent, message.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("Blender stopped reading its requests");
    sent += static_cast<std::size_t>(n);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s_);
  std::size_t end_of_line;
  while ((end_of_line = received_.find('\n')) == std::string::npos) {
    const auto now = std::chrono::steady_clock::now();
    if (now >= deadline) fail("Blender did not answer within " + yaml::plain_number(timeout_s_) + " s");
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - now);
    pollfd readable{socket_, POLLIN, 0};
    const int ready = ::poll(&readable, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno != EINTR) fail("cannot wait for Blender's answer");
    if (ready <= 0) continue;
    char buffer[4096];
    const ssize_t n = ::recv(socket_, buffer, sizeof buffer, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("Blender exited");
    received_.append(buffer, static_cast<std::size_t>(n));
  }
  const std::string answer = received_.substr(0, end_of_line);
  received_.erase(0, end_of_line + 1);
  if (answer == "ok") return;
  throw std::runtime_error("Blender: " + (answer.rfind("error ", 0) == 0 ? answer.substr(6) : "unexpected answer " + answer));
}

void BlenderProcess::fail(const std::string& what) {
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }
  throw std::runtime_error(what + "; its last messages:\n" + last_messages());
}

std::string BlenderProcess::last_messages() const {
  std::ifstream log(log_file_);
  std::deque<std::string> lines;
  for (std::string line; std::getline(log, line);) {
    lines.push_back(line);
    if (static_cast<int>(lines.size()) > kQuotedLogLines) lines.pop_front();
  }
  std::string text;
  for (const std::string& line : lines) text += (text.empty() ? "  " : "\n  ") + line;
  return text.empty() ? "  (none)" : text;
}

}  // namespace icgp::servo
