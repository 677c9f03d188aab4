// SPDX-License-Identifier: GPL-2.0-or-later
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "commands.h"

namespace icgp::app {

std::string models_dir() {
  namespace fs = std::filesystem;
  if (const char* env = std::getenv("ICGP_MODELS_DIR")) return env;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / "share" / "icgp" / "models";
    if (fs::is_directory(installed)) return installed.string();
  }
  return ICGP_SOURCE_MODELS_DIR;
}

TrackerConfig benchmark_tracker_config(const std::string& explicit_file) {
  std::cerr << "tracker configuration: " << (explicit_file.empty() ? "icgp defaults" : explicit_file) << "\n";
  return explicit_file.empty() ? TrackerConfig{} : load_tracker_config(explicit_file);
}

TrackerConfig sequence_tracker_config(const std::string& explicit_file, const std::string& sequence_dir) {
  const std::filesystem::path own = std::filesystem::path(sequence_dir) / "icgp.yaml";
  if (explicit_file.empty() && std::filesystem::is_regular_file(own)) return benchmark_tracker_config(own.string());
  return benchmark_tracker_config(explicit_file);
}

std::string default_model_path() { return models_dir() + "/textured_box/textured_box.obj"; }

}  // namespace icgp::app
