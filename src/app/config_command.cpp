// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp config`: prints the effective tracker configuration as YAML, the defaults or a
// file read over them and validated (docs/configuration.md).
#include <iostream>
#include <memory>

#include "commands.h"
#include "icgp/tracker/tracker_config.h"

namespace icgp::app {

void register_config_command(CLI::App& app) {
  auto file = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("config", "Print the effective tracker configuration as YAML");
  CLI::Option* defaults = cmd->add_flag("--defaults", "Print the default configuration");
  CLI::Option* file_option = cmd->add_option("file", *file, "YAML configuration to validate and print over the defaults");
  defaults->excludes(file_option);
  cmd->require_option(1);
  cmd->callback([file, file_option] {
    std::cout << to_yaml(file_option->count() ? load_tracker_config(*file) : TrackerConfig{});
  });
}

}  // namespace icgp::app
