// SPDX-License-Identifier: GPL-2.0-or-later
// Drawing figures with gnuplot from a script a report writes: the benchmarks' plots and the
// servo simulator's.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace icgp {

/// The start of a script: who wrote it and how to redraw it, a PNG terminal of
/// `width`×`height` (cairo's when gnuplot has it), NaN as missing data, a grid. The script
/// sets its outputs itself.
std::string gnuplot_png_preamble(const std::string& written_by, const std::string& redraw_hint, int width, int height);

/// Writes `script_text` to `script` and runs gnuplot on it in the script's folder, so that a
/// script that names its figures by file name redraws them where it lies. Each of `figures`
/// (relative to the working folder, like `script`) must then be a PNG. Throws
/// std::runtime_error naming the script, gnuplot's exit status and its last messages when
/// gnuplot is missing, fails, or leaves a figure undrawn.
void draw_with_gnuplot(const std::string& script_text, const std::filesystem::path& script,
                       const std::vector<std::filesystem::path>& figures);

}  // namespace icgp
