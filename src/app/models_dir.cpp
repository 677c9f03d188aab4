// SPDX-License-Identifier: GPL-2.0-or-later
#include <cstdlib>
#include <filesystem>

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

std::string default_model_path() { return models_dir() + "/textured_box/textured_box.obj"; }

}  // namespace icgp::app
