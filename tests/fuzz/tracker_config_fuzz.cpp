// SPDX-License-Identifier: GPL-2.0-or-later
// The tracker configuration reader (icgp::load_tracker_config) on arbitrary YAML bytes.
#include "fuzz_support.h"
#include "icgp/tracker/tracker_config.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path file = icgp::fuzz::scratch_dir() / "tracker.yaml";
  icgp::fuzz::write_file(file, data, size);
  icgp::fuzz::refusing_like_a_loader([] { icgp::load_tracker_config(file.string()); });
  return 0;
}
