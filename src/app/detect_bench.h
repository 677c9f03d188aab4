// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp bench --detect`: detection alone over rendered frames of the sweep's objects and a
// textureless figurine at many poses and distances, with each depth sensor class and grey
// without depth, beside distractors, partly occluded, in frames without the object and on
// a white table under a hunting auto-exposure; against vpKeyPoint.
#pragma once

#include <string>
#include <vector>

namespace icgp::app {

struct DetectBenchOptions {
  std::string out = "out/detect-bench";  ///< rendered sequences (cached)
  std::string summary;                   ///< JSON rows; empty: none
  std::string plot = "docs/images/detection_occlusion.png";  ///< success against occlusion
  int frames = 12;                       ///< frames per cell (object x sensor x distance)
  std::vector<std::string> objects;      ///< of the bench's objects, these only; empty: all
};

/// Renders (or reuses) every cell's sequence, detects the object in each frame with icgp's
/// defaults and with vpKeyPoint (textured objects), prints one row per object, scene and
/// sensor, and writes the summary and the plot of success against occlusion.
void run_detect_bench(const DetectBenchOptions& options);

}  // namespace icgp::app
