// SPDX-License-Identifier: GPL-2.0-or-later
// The model and body name a command uses for a single-object sequence.
#pragma once

#include <string>

#include "icgp/eval/sequence.h"

namespace icgp::app {

/// The model: `model` when given, else the one the sequence in `directory` names for its
/// only object. Throws std::runtime_error asking for --model otherwise.
std::string sequence_model_path(const std::string& model, const Sequence& sequence, const std::string& directory);
/// The body takes the name the sequence stores its ground truth under, so frames' truths
/// are found: its only object's, or of several the one whose mesh is `model`'s file; else
/// the model's file name.
std::string sequence_body_name(const Sequence& sequence, const std::string& model);

}  // namespace icgp::app
