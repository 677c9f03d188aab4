// SPDX-License-Identifier: GPL-2.0-or-later
#include "gnuplot.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace icgp::app {

namespace fs = std::filesystem;

std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string gnuplot_png_preamble(const std::string& written_by, const std::string& script_name, int width,
                                 int height, const std::string& png) {
  const std::string size = std::to_string(width) + "," + std::to_string(height);
  return "# Written by " + written_by + "; redraw with: gnuplot " + script_name + "\n" +
         "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n  set terminal pngcairo size " + size +
         " noenhanced\n} else {\n  set terminal png size " + size + " noenhanced\n}\n" + "set output '" + png +
         "'\nset datafile missing 'NaN'\nset grid\n";
}

void draw_with_gnuplot(const std::string& script_text, const std::string& script, const std::string& png) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0)
    throw std::runtime_error("gnuplot is not installed: cannot draw " + png);
  std::ofstream out(script);
  out << script_text;
  if (!out.flush()) throw std::runtime_error(script + ": cannot write the gnuplot script");
  out.close();
  const std::string log = script + ".log";
  fs::remove(png);  // so that a failed run cannot pass for a drawn one
  const std::string command = "gnuplot " + shell_quote(script) + " >" + shell_quote(log) + " 2>&1";
  if (std::system(command.c_str()) != 0 || !fs::is_regular_file(png))
    throw std::runtime_error("gnuplot failed to draw " + png + " (script " + script + ", messages in " + log + ")");
  fs::remove(log);
}

}  // namespace icgp::app
