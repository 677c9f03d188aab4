// SPDX-License-Identifier: GPL-2.0-or-later
// What the vpMbIcgTracker tests share: the teabox-blender frames and the tracker set up as
// a ViSP user would, with models coarse enough to be generated in about a second.
#pragma once

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "icgp/eval/sequence.h"
#include "icgp/tracker/tracker_config.h"
#include "icgp/visp/visp_camera_xml.h"
#include "icgp/visp/vpMbIcgTracker.h"

namespace icgp::test {

inline const std::filesystem::path kTeaboxBlender = std::filesystem::path(ICGP_TEST_DATA_DIR) / "teabox-blender";

/// The first `n` frames of teabox-blender (colour "Camera1", depth "Camera2", ground truth).
inline std::vector<Frame> teabox_frames(int n) {
  // Blender's principal point convention, for both trackers alike: these tests measure the
  // trackers, not how far the XML's (320, 240) is from the renderer's camera.
  SequenceOptions blender = visp_sequence_options();
  blender.blender_principal_point = true;
  const Sequence sequence = Sequence::open(kTeaboxBlender.string(), blender);
  std::vector<Frame> frames;
  for (int i = 0; i < n; ++i) frames.push_back(sequence.load(i));
  return frames;
}

/// icgp's defaults with the coarse viewpoint models of tests/configs/coarse_models.yaml,
/// cached in the build tree.
inline void configure_for_tests(vpMbIcgTracker& tracker) {
  tracker.loadConfigFile(ICGP_TEST_CONFIGS_DIR "/coarse_models.yaml", false);
  TrackerConfig config = tracker.getTrackerConfig();
  config.cache_dir = ICGP_TEST_CACHE_DIR;
  tracker.setTrackerConfig(config);
}

/// The exception of type E (vpException or a subclass) that `call` throws; a failed check
/// (and code -1) when it throws none. Any other exception reaches Catch and fails the test:
/// vpMbIcgTracker throws ViSP's only.
template <class E = vpException, class Call>
E vp_exception_of(Call&& call) {
  try {
    call();
  } catch (const E& e) {
    return e;
  }
  FAIL_CHECK("no exception was thrown");
  return E(-1, "no exception was thrown");
}

}  // namespace icgp::test
