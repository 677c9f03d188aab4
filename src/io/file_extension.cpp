// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/io/file_extension.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace icgp {

std::string lower_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

}  // namespace icgp
