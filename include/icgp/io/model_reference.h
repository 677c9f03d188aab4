// SPDX-License-Identifier: GPL-2.0-or-later
// The model a YAML file names (a servo scenario's object, a make-sequence scene's body): a
// folder of the models directory ("textured_box") or a mesh file relative to the file.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "icgp/io/yaml_reader.h"

namespace icgp {

/// The files `reference` may name, in order: <models_dir>/<reference>/<reference>.obj and
/// <models_dir>/<reference>/object.obj (a relative reference, models_dir not empty), then
/// <file_dir>/<reference>.
std::vector<std::string> model_candidates(const std::string& reference, const std::string& file_dir,
                                          const std::string& models_dir);
/// The first candidate that is a file.
std::optional<std::string> find_model(const std::vector<std::string>& candidates);
/// "tried a, b, c", for messages.
std::string tried(const std::vector<std::string>& candidates);
/// The model file the value names; "expected a model folder of <models_dir> or an existing
/// mesh file (tried …)" otherwise.
std::string model_file(const yaml::Value& v, const std::string& file_dir, const std::string& models_dir);

}  // namespace icgp
