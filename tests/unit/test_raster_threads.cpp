// SPDX-License-Identifier: GPL-2.0-or-later
// choose_software_raster_threads: Mesa's llvmpipe reads LP_NUM_THREADS when the process's
// EGL display opens, so each case runs in its own process (one CTest test per case) and
// opens the display itself. On llvmpipe the raster threads are seen as the process's
// threads named "llvmpipe-N"; with a GPU driver only the environment is checked.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "icgp/render/egl_context.h"

namespace {

/// Threads of this process whose name starts with "llvmpipe" (its raster threads).
int llvmpipe_threads() {
  int n = 0;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task")) {
    std::ifstream comm(task.path() / "comm");
    std::string name;
    if (std::getline(comm, name) && name.rfind("llvmpipe", 0) == 0) ++n;
  }
  return n;
}

bool on_llvmpipe(const icgp::EglContext& context) {
  return context.description().find("llvmpipe") != std::string::npos;
}

std::string lp_num_threads() {
  const char* value = std::getenv("LP_NUM_THREADS");
  return value ? value : "(unset)";
}

}  // namespace

TEST_CASE("by default the display opens with LP_NUM_THREADS=0: renders on the calling thread") {
  ::unsetenv("LP_NUM_THREADS");
  const icgp::EglContext context;
  CHECK(lp_num_threads() == "0");
  if (on_llvmpipe(context)) CHECK(llvmpipe_threads() == 0);
  // The display is open: a later choice cannot take effect and says so.
  CHECK_FALSE(icgp::choose_software_raster_threads(icgp::SoftwareRasterThreads::kPerCore));
  CHECK(lp_num_threads() == "0");
}

TEST_CASE("kPerCore, chosen before the display opens, leaves llvmpipe its raster threads") {
  ::unsetenv("LP_NUM_THREADS");
  REQUIRE(icgp::choose_software_raster_threads(icgp::SoftwareRasterThreads::kPerCore));
  const icgp::EglContext context;
  CHECK(lp_num_threads() == "(unset)");
  // llvmpipe starts one raster thread per core on a machine of more than one.
  if (on_llvmpipe(context) && std::thread::hardware_concurrency() > 1) {
    INFO("llvmpipe raster threads: " << llvmpipe_threads());
    CHECK(llvmpipe_threads() >= 1);
  }
}

TEST_CASE("a LP_NUM_THREADS the user set wins over the choice") {
  ::setenv("LP_NUM_THREADS", "1", 1);
  REQUIRE(icgp::choose_software_raster_threads(icgp::SoftwareRasterThreads::kCallingThread));
  const icgp::EglContext context;
  CHECK(lp_num_threads() == "1");
  if (on_llvmpipe(context)) CHECK(llvmpipe_threads() == 1);
}
