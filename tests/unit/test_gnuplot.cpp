// SPDX-License-Identifier: GPL-2.0-or-later
// The one gnuplot runner of the reports: it draws what a script names, in the script's
// folder, and says what went wrong when gnuplot fails or draws nothing.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "icgp/eval/gnuplot.h"
#include "test_temp_dir.h"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

std::string first_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string bytes(4, '\0');
  in.read(bytes.data(), 4);
  return bytes;
}

const std::string kPreamble = icgp::gnuplot_png_preamble("test_gnuplot", "gnuplot plot.gp", 320, 240);

}  // namespace

TEST_CASE("draw_with_gnuplot: a script naming its figure by file name draws it beside the script") {
  icgp::test::TempDir dir("icgp_test_gnuplot_draws");
  const fs::path script = dir.path() / "plots" / "plot.gp";
  fs::create_directories(script.parent_path());
  icgp::draw_with_gnuplot(kPreamble + "set output 'sine.png'\nplot sin(x)\nset output\n", script,
                          {script.parent_path() / "sine.png"});
  CHECK(first_bytes(script.parent_path() / "sine.png") == "\x89PNG");
  CHECK(fs::exists(script));                   // kept: it redraws the figure
  CHECK_FALSE(fs::exists(script.string() + ".log"));  // gnuplot's messages, only kept on failure
}

TEST_CASE("draw_with_gnuplot: a failing script or a figure not drawn is an error with gnuplot's messages") {
  icgp::test::TempDir dir("icgp_test_gnuplot_fails");
  const fs::path script = dir.path() / "plot.gp";
  CHECK_THROWS_WITH(icgp::draw_with_gnuplot(kPreamble + "set output 'a.png'\nplot no_such_function(x)\n", script,
                                            {dir.path() / "a.png"}),
                    Contains(script.string()) && Contains("exit status") && Contains("no_such_function"));
  // gnuplot succeeds, but the figure the caller expects is not among its outputs.
  CHECK_THROWS_WITH(icgp::draw_with_gnuplot(kPreamble + "set output 'a.png'\nplot x\nset output\n", script,
                                            {dir.path() / "b.png"}),
                    Contains("failed to draw the figures of " + script.string()));
}
