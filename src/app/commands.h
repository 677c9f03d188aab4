// SPDX-License-Identifier: GPL-2.0-or-later
// Each subcommand of the icgp program registers itself on the main CLI11 app.
#pragma once

#include <CLI/CLI.hpp>
#include <stdexcept>
#include <string>

#include "icgp/tracker/tracker_config.h"

namespace icgp::app {

/// The exit status of the icgp program (docs/servo.md, "Exit status").
enum ExitStatus : int {
  kExitSuccess = 0,
  kExitError = 1,        ///< nothing or not all was done: bad input, an option out of range, a missing file
  kExitNotAchieved = 2,  ///< the work ran and its results are written, but it did not reach its goal
  kExitInterrupted = 130,  ///< stopped by SIGINT after writing what was done (128 + SIGINT, the shell's convention)
};

/// Thrown by a command that has done its work and written its results, to end the program
/// with `status` and a one-line `reason` on stderr ("icgp: <reason>").
class CommandOutcome : public std::runtime_error {
 public:
  CommandOutcome(ExitStatus status, const std::string& reason) : std::runtime_error(reason), status_(status) {}
  ExitStatus status() const { return status_; }

 private:
  ExitStatus status_;
};

void register_render_command(CLI::App& app);
void register_bench_render_command(CLI::App& app);
void register_make_sequence_command(CLI::App& app);
void register_track_command(CLI::App& app);
void register_detect_command(CLI::App& app);
void register_bench_command(CLI::App& app);
void register_compare_command(CLI::App& app);
void register_model_command(CLI::App& app);
void register_config_command(CLI::App& app);
void register_servo_command(CLI::App& app);
void register_stereo_command(CLI::App& app);

/// Said before a benchmark's first vpMbIcgTracker run, whose times the generation shares.
inline constexpr const char* kModelsOnFirstUse =
    "vpMbIcgTracker makes its viewpoint models on first use, while it tracks (the first round shares the cores "
    "with that); later runs read them from the cache\n";

/// Help of the flag that applies SequenceOptions::blender_principal_point.
inline constexpr const char* kBlenderPrincipalPointHelp =
    "visp-blender sequences: read the XML's principal point in Blender's pixel-edge convention (0.5 px "
    "less), for every tracker compared (default: exactly as the XML writes it)";

/// The tracker configuration for a sequence: the explicit file when given, else the
/// sequence folder's own icgp.yaml (as ViSP data folders carry their tracker XML), else the
/// icgp defaults (preset "default"). Says on stderr which one it uses.
TrackerConfig sequence_tracker_config(const std::string& explicit_file, const std::string& sequence_dir);
/// The icgp configuration a benchmark compares: the explicit file when given, else icgp's
/// defaults. Benchmarks never read a sequence folder's icgp.yaml: settings fitted to the
/// data would be compared against ViSP's defaults. Says on stderr which one it uses.
TrackerConfig benchmark_tracker_config(const std::string& explicit_file);

/// `icgp bench --ablation`: ICG+ rows with each descriptor and without each cue, on
/// teabox-blender and rendered ambiguous-geometry sequences; JSON rows to summary_path.
void run_ablation(const std::string& summary_path, int frame_limit);

/// The folder of models shipped with icgp: $ICGP_MODELS_DIR, else the installed share
/// folder next to the program, else the source tree's models/.
std::string models_dir();
/// The default model, rendered and tracked when no model is given.
std::string default_model_path();
/// The scenario `icgp servo` runs when none is given: scenarios/default.yaml, installed
/// beside the models or in the source tree.
std::string default_scenario_path();

}  // namespace icgp::app
