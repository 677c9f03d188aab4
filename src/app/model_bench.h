// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp bench --model`: what a new object costs before its first tracked frame: the sparse
// viewpoint models' generation per kind, the first frame through vpMbIcgTracker on a cold
// cache, the cache files and the memory.
#pragma once

#include <string>
#include <vector>

namespace icgp::app {

struct ModelBenchOptions {
  std::string out = "out/model-bench";  ///< caches (emptied per measurement) and the rendered frames
  std::string summary;                  ///< JSON of the rows; empty: none
  std::vector<std::string> meshes;      ///< only these (folder names of models/, torus_10k); empty: all
};

/// For each main mesh of models/ and a generated 10 000-triangle torus (not convex): the
/// region model alone, the depth model alone and both together (one render per view), each
/// generated into an empty cache, with the cache files' size; then vpMbIcgTracker with the
/// defaults on an empty cache, loadModel → initFromPose → the first track() on one rendered
/// frame at 0.5 m; the process's peak resident memory after each mesh.
void run_model_bench(const ModelBenchOptions& options);

}  // namespace icgp::app
