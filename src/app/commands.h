// SPDX-License-Identifier: GPL-2.0-or-later
// Each subcommand of the icgp program registers itself on the main CLI11 app.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace icgp::app {

void register_render_command(CLI::App& app);
void register_bench_render_command(CLI::App& app);
void register_make_sequence_command(CLI::App& app);
void register_track_command(CLI::App& app);
void register_bench_command(CLI::App& app);
void register_model_command(CLI::App& app);
void register_config_command(CLI::App& app);

/// The folder of models shipped with icgp: $ICGP_MODELS_DIR, else the installed share
/// folder next to the program, else the source tree's models/.
std::string models_dir();
/// The default model, rendered and tracked when no model is given.
std::string default_model_path();

}  // namespace icgp::app
