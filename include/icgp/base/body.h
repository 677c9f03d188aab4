// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <string>

#include "icgp/base/pose.h"
#include "icgp/base/mesh.h"

namespace icgp {

/// A tracked rigid object: its geometry and its current pose. The pose is relative to the
/// frame's reference camera (the first colour camera), like ViSP's cMo.
struct Body {
  std::string name;
  Mesh mesh;
  Pose reference_T_body;
};

}  // namespace icgp
