// SPDX-License-Identifier: GPL-2.0-or-later
// The servo scenario reader (icgp::servo::load_scenario) on arbitrary YAML bytes. It only
// parses and validates: no model is generated, nothing is rendered. Model names resolve
// against the project's models/ folder, so a seed naming a real model reads on.
#include "fuzz_support.h"
#include "icgp/servo/scenario.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path file = icgp::fuzz::scratch_dir() / "scenario.yaml";
  icgp::fuzz::write_file(file, data, size);
  icgp::fuzz::refusing_like_a_loader([] { icgp::servo::load_scenario(file.string(), ICGP_MODELS_DIR); });
  return 0;
}
