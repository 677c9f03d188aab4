// SPDX-License-Identifier: GPL-2.0-or-later
#include <iostream>

#include "commands.h"
#include "icgp/base/stop_request.h"

int main(int argc, char** argv) {
  using icgp::app::kExitError;
  using icgp::app::kExitInterrupted;
  CLI::App app{"icgp: ICG+ multi-modality 6-DoF object tracking for ViSP"};
  app.require_subcommand(1);
  // Command-line errors read like every other error of the program: one line, its status.
  app.failure_message([](const CLI::App*, const CLI::Error& e) { return "icgp: error: " + std::string(e.what()) + "\n"; });
  icgp::app::register_render_command(app);
  icgp::app::register_bench_render_command(app);
  icgp::app::register_make_sequence_command(app);
  icgp::app::register_track_command(app);
  icgp::app::register_detect_command(app);
  icgp::app::register_bench_command(app);
  icgp::app::register_compare_command(app);
  icgp::app::register_model_command(app);
  icgp::app::register_config_command(app);
  icgp::app::register_servo_command(app);
  icgp::app::register_stereo_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : kExitError;  // --help is a ParseError that exits 0
  } catch (const icgp::app::CommandOutcome& e) {
    std::cerr << "icgp: " << e.what() << "\n";
    return e.status();
  } catch (const icgp::StopRequested& e) {
    std::cerr << "icgp: " << e.what() << "\n";
    return kExitInterrupted;
  } catch (const std::exception& e) {
    std::cerr << "icgp: error: " << e.what() << "\n";
    return kExitError;
  }
  return 0;
}
