// SPDX-License-Identifier: GPL-2.0-or-later
// Drawing a benchmark's plot with gnuplot, from a script the benchmark writes.
#pragma once

#include <string>

namespace icgp::app {

/// `text` quoted for a POSIX shell.
std::string shell_quote(const std::string& text);

/// The start of a script: who wrote it and how to redraw it, a PNG terminal of
/// `width`×`height` (cairo's when gnuplot has it) writing `png`, NaN as missing data, a grid.
std::string gnuplot_png_preamble(const std::string& written_by, const std::string& script_name, int width,
                                 int height, const std::string& png);

/// Writes `script_text` to `script` and runs gnuplot on it, which must draw `png`. Throws
/// std::runtime_error naming the script (and the file with gnuplot's messages) when
/// gnuplot is missing, fails, or leaves no PNG.
void draw_with_gnuplot(const std::string& script_text, const std::string& script, const std::string& png);

}  // namespace icgp::app
