// SPDX-License-Identifier: GPL-2.0-or-later
// The .cao loader (icgp::load_cao_mesh, ViSP's parser behind it) on arbitrary bytes.
#include "fuzz_support.h"
#include "icgp/visp/cao_mesh_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path file = icgp::fuzz::scratch_dir() / "model.cao";
  icgp::fuzz::write_file(file, data, size);
  // Few segments keep each run fast; the curved primitives are still meshed.
  icgp::fuzz::refusing_like_a_loader([] { icgp::load_cao_mesh(file.string(), icgp::Pose(), icgp::CaoTessellation{3, 3}); });
  return 0;
}
