// SPDX-License-Identifier: GPL-2.0-or-later
// The Blender process's failure modes, with stand-ins for Blender (shell scripts given as
// ICGP_BLENDER): a request is answered, or fails within its timeout with the script's last
// messages; never a hang. No Blender is needed.
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "icgp/servo/blender_process.h"

using icgp::servo::BlenderProcess;

namespace {

namespace fs = std::filesystem;

/// A stand-in for Blender: `body` runs as a shell script (answers go to descriptor 3), and
/// is ICGP_BLENDER while this lives.
class FakeBlender {
 public:
  explicit FakeBlender(const std::string& body) {
    folder_ = fs::temp_directory_path() / ("icgp-fake-blender-" + std::to_string(::getpid()));
    fs::create_directories(folder_);
    const fs::path program = folder_ / "blender";
    std::ofstream(program) << "#!/bin/sh\n" << body << "\n";
    fs::permissions(program, fs::perms::owner_all);
    ::setenv("ICGP_BLENDER", program.c_str(), 1);
  }
  ~FakeBlender() {
    ::unsetenv("ICGP_BLENDER");
    std::error_code ignored;
    fs::remove_all(folder_, ignored);
  }
  std::string log() const { return (folder_ / "blender.log").string(); }

 private:
  fs::path folder_;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

TEST_CASE("blender process: each request gets its answer, and an error answer throws its message") {
  FakeBlender fake("while read line; do case \"$line\" in *bad*) echo 'error ValueError: no such body' >&3 ;; "
                   "*quit*) exit 0 ;; *) echo ok >&3 ;; esac; done");
  BlenderProcess blender("server.py", fake.log(), 10.0);
  CHECK_NOTHROW(blender.request("{\"op\": \"setup\"}"));
  CHECK_NOTHROW(blender.request("{\"op\": \"color\"}"));
  CHECK_THROWS_WITH(blender.request("{\"op\": \"bad\"}"), "Blender: ValueError: no such body");
  CHECK_NOTHROW(blender.request("{\"op\": \"color\"}"));  // an error answer leaves it running
}

TEST_CASE("blender process: a Blender that exits mid-run fails the request with its last messages") {
  FakeBlender fake("echo 'Blender 3.4.1 (stand-in)'; read line; echo ok >&3; read line; "
                   "echo 'Error: Not freed memory blocks'; echo 'Segmentation fault (stand-in)'; exit 139");
  BlenderProcess blender("server.py", fake.log(), 10.0);
  REQUIRE_NOTHROW(blender.request("{\"op\": \"setup\"}"));
  const auto start = std::chrono::steady_clock::now();
  CHECK_THROWS_WITH(blender.request("{\"op\": \"color\"}"),
                    Catch::Contains("Blender exited") && Catch::Contains("Segmentation fault (stand-in)") &&
                        Catch::Contains("Blender 3.4.1 (stand-in)"));
  CHECK(seconds_since(start) < 5.0);
  CHECK_THROWS_WITH(blender.request("{\"op\": \"color\"}"), Catch::Contains("no longer running"));
}

TEST_CASE("blender process: a Blender that hangs fails the request at its timeout, and is ended") {
  FakeBlender fake("echo 'Fra:1 Mem:12M | Rendering 1 / 16 samples'; exec sleep 600");
  BlenderProcess blender("server.py", fake.log(), 1.0);
  const auto start = std::chrono::steady_clock::now();
  CHECK_THROWS_WITH(blender.request("{\"op\": \"color\"}"),
                    Catch::Contains("did not answer within 1 s") && Catch::Contains("Rendering 1 / 16 samples"));
  const double waited = seconds_since(start);
  CHECK(waited >= 0.9);  // it waited for the timeout, and not without bound
  CHECK(waited < 5.0);
}

TEST_CASE("blender process: without Blender the error says how to install it") {
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  ::unsetenv("ICGP_BLENDER");
  ::setenv("PATH", "/nonexistent", 1);
  CHECK_THROWS_WITH(BlenderProcess("server.py", "blender.log", 10.0),
                    Catch::Contains("no `blender` program is on the PATH") &&
                        Catch::Contains("scripts/setup --cycles"));
  ::setenv("PATH", path.c_str(), 1);
  ::setenv("ICGP_BLENDER", "/nonexistent/blender", 1);
  CHECK_THROWS_WITH(BlenderProcess("server.py", "blender.log", 10.0),
                    "ICGP_BLENDER is /nonexistent/blender, which is not an executable program");
  ::unsetenv("ICGP_BLENDER");
}
