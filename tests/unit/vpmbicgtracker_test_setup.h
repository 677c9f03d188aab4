// SPDX-License-Identifier: GPL-2.0-or-later
// What the vpMbIcgTracker tests share: the teabox-blender frames and the tracker set up as
// a ViSP user would, with models coarse enough to be generated in about a second.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "icgp/eval/sequence.h"
#include "icgp/tracker/tracker_config.h"
#include "icgp/visp/vpMbIcgTracker.h"

namespace icgp::test {

inline const std::filesystem::path kTeaboxBlender = std::filesystem::path(ICGP_TEST_DATA_DIR) / "teabox-blender";

/// The first `n` frames of teabox-blender (colour "Camera1", depth "Camera2", ground truth).
inline std::vector<Frame> teabox_frames(int n) {
  const Sequence sequence = Sequence::open(kTeaboxBlender.string());
  std::vector<Frame> frames;
  for (int i = 0; i < n; ++i) frames.push_back(sequence.load(i));
  return frames;
}

/// The sequence's own parameters (icgp.yaml, as ViSP reads teabox.xml) with the coarse
/// viewpoint models of tests/configs/coarse_models.yaml, cached in the build tree.
inline void configure_for_tests(vpMbIcgTracker& tracker) {
  tracker.loadConfigFile((kTeaboxBlender / "icgp.yaml").string(), false);
  TrackerConfig config = tracker.getTrackerConfig();
  const TrackerConfig coarse = load_tracker_config(ICGP_TEST_CONFIGS_DIR "/coarse_models.yaml");
  config.region_model = coarse.region_model;
  config.depth_model = coarse.depth_model;
  config.cache_dir = ICGP_TEST_CACHE_DIR;
  tracker.setTrackerConfig(config);
}

}  // namespace icgp::test
