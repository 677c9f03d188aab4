// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/io/model_reference.h"

#include <filesystem>

namespace icgp {

namespace fs = std::filesystem;

std::vector<std::string> model_candidates(const std::string& reference, const std::string& file_dir,
                                          const std::string& models_dir) {
  std::vector<fs::path> candidates;
  if (fs::path(reference).is_relative() && !models_dir.empty()) {
    candidates.push_back(fs::path(models_dir) / reference / (reference + ".obj"));
    candidates.push_back(fs::path(models_dir) / reference / "object.obj");
  }
  candidates.push_back(fs::path(file_dir) / reference);
  std::vector<std::string> names;
  for (const fs::path& candidate : candidates) names.push_back(candidate.lexically_normal().string());
  return names;
}

std::optional<std::string> find_model(const std::vector<std::string>& candidates) {
  std::error_code error;
  for (const std::string& candidate : candidates)
    if (fs::is_regular_file(candidate, error)) return candidate;
  return std::nullopt;
}

std::string tried(const std::vector<std::string>& candidates) { return "tried " + yaml::join(candidates); }

std::string model_file(const yaml::Value& v, const std::string& file_dir, const std::string& models_dir) {
  const std::string reference = v.as(yaml::kNonEmptyString);
  const std::vector<std::string> candidates = model_candidates(reference, file_dir, models_dir);
  if (std::optional<std::string> file = find_model(candidates)) return *file;
  v.expected("a model folder of " + models_dir + " or an existing mesh file (" + tried(candidates) + ")");
}

}  // namespace icgp
