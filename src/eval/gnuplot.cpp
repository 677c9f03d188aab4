// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/eval/gnuplot.h"

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace icgp {
namespace {

namespace fs = std::filesystem;

/// `text` quoted for a POSIX shell.
std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

bool is_png(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  char signature[4] = {};
  in.read(signature, 4);
  return in && signature[0] == '\x89' && signature[1] == 'P' && signature[2] == 'N' && signature[3] == 'G';
}

/// The end of gnuplot's messages: enough to see the error, not a page of data.
std::string last_messages(const fs::path& log) {
  std::ifstream in(log, std::ios::binary);
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  constexpr std::size_t kShown = 2000;
  return text.size() > kShown ? "..." + text.substr(text.size() - kShown) : text;
}

}  // namespace

std::string gnuplot_png_preamble(const std::string& written_by, const std::string& redraw_hint, int width, int height) {
  const std::string size = std::to_string(width) + "," + std::to_string(height);
  return "# Written by " + written_by + "; redraw with: " + redraw_hint + "\n" +
         "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n  set terminal pngcairo size " + size +
         " noenhanced\n} else {\n  set terminal png size " + size + " noenhanced\n}\n" +
         "set datafile missing 'NaN'\nset grid\n";
}

void draw_with_gnuplot(const std::string& script_text, const fs::path& script, const std::vector<fs::path>& figures) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0)
    throw std::runtime_error("gnuplot is not installed: cannot draw the figures of " + script.string());
  std::ofstream out(script);
  out << script_text;
  if (!out.flush()) throw std::runtime_error(script.string() + ": cannot write the gnuplot script");
  out.close();
  std::error_code error;
  for (const fs::path& figure : figures) fs::remove(figure, error);  // a failed run cannot pass for a drawn one
  const fs::path folder = script.parent_path().empty() ? fs::path(".") : script.parent_path();
  const fs::path log = fs::path(script).concat(".log");
  const std::string command = "cd " + shell_quote(folder.string()) + " && gnuplot " +
                              shell_quote(script.filename().string()) + " >" +
                              shell_quote(log.filename().string()) + " 2>&1";
  const int status = std::system(command.c_str());
  bool drawn = status == 0;
  for (const fs::path& figure : figures) drawn = drawn && is_png(figure);
  if (!drawn) {
    const std::string messages = last_messages(log);
    throw std::runtime_error("gnuplot failed to draw the figures of " + script.string() + " (exit status " +
                             std::to_string(status) + ", messages in " + log.string() + ")" +
                             (messages.empty() ? std::string() : ":\n" + messages));
  }
  fs::remove(log, error);
}

}  // namespace icgp
