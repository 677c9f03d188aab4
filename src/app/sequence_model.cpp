// SPDX-License-Identifier: GPL-2.0-or-later
#include "sequence_model.h"

#include <filesystem>
#include <stdexcept>

namespace icgp::app {

std::string sequence_model_path(const std::string& model, const Sequence& sequence, const std::string& directory) {
  if (!model.empty()) return model;
  if (sequence.objects().size() == 1 && !sequence.objects().front().mesh_path.empty())
    return sequence.objects().front().mesh_path;
  throw std::runtime_error("the sequence in " + directory + " names no single model: give --model");
}

std::string sequence_body_name(const Sequence& sequence, const std::string& model) {
  if (sequence.objects().size() == 1) return sequence.objects().front().name;
  // Of several objects, the one whose mesh is the model's file.
  for (const SequenceObject& object : sequence.objects()) {
    std::error_code ec;
    if (!object.mesh_path.empty() && std::filesystem::equivalent(object.mesh_path, model, ec) && !ec) return object.name;
  }
  return std::filesystem::path(model).stem().string();
}

}  // namespace icgp::app
