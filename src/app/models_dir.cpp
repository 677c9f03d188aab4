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

TrackerConfig sequence_tracker_config(const std::string& explicit_file, const std::string& sequence_dir) {
  std::string file = explicit_file;
  const std::filesystem::path own = std::filesystem::path(sequence_dir) / "icgp.yaml";
  if (file.empty() && std::filesystem::is_regular_file(own)) file = own.string();
  std::cerr << "tracker configuration: " << (file.empty() ? "icgp defaults" : file) << "\n";
  return file.empty() ? TrackerConfig{} : load_tracker_config(file);
}

std::string default_model_path() { return models_dir() + "/textured_box/textured_box.obj"; }

}  // namespace icgp::app
