// SPDX-License-Identifier: GPL-2.0-or-later
// The assimp mesh loader (icgp::load_mesh) on arbitrary OBJ, PLY (ascii and binary: the
// bytes say which) and STL bytes. The first input byte picks the file's extension, the
// rest is the file.
#include "fuzz_support.h"
#include "icgp/io/mesh_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const kExtensions[] = {".obj", ".ply", ".stl"};
  const std::filesystem::path file = icgp::fuzz::scratch_dir() / (std::string("mesh") + kExtensions[data[0] % 3]);
  icgp::fuzz::write_file(file, data + 1, size - 1);
  icgp::fuzz::refusing_like_a_loader([&] { icgp::load_mesh(file.string()); });
  return 0;
}
