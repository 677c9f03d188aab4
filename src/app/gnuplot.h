// SPDX-License-Identifier: GPL-2.0-or-later
// Drawing a benchmark's plot with gnuplot, from a script the benchmark writes.
#pragma once

#include <string>

namespace icgp::app {

/// `text` quoted for a POSIX shell.
std::string shell_quote(const std::string& text);

/// Writes `script_text` to `script` and runs gnuplot on it, which must draw `png`. Throws
/// std::runtime_error naming the script (and the file with gnuplot's messages) when
/// gnuplot is missing, fails, or leaves no PNG.
void draw_with_gnuplot(const std::string& script_text, const std::string& script, const std::string& png);

}  // namespace icgp::app
