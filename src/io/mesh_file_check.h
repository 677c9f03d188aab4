// SPDX-License-Identifier: GPL-2.0-or-later
// Checks of mesh file structure that assimp's parsers do not make before they index memory.
#pragma once

#include <string>

namespace icgp {

/// For .ply and .stl files: throws std::runtime_error "load_mesh: '<path>': …" when the
/// header is malformed or promises more data than the file holds (assimp's binary PLY
/// reader has been seen to crash on such a file). Other formats pass unchecked.
void check_mesh_file_structure(const std::string& path);

}  // namespace icgp
