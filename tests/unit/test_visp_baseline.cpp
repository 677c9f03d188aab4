// SPDX-License-Identifier: GPL-2.0-or-later
// ViSP's own vpMbGenericTracker through icgp's baseline adapter and sequence runner on the teabox-blender frames:
// it must track as ViSP's tutorial does (tests/data/README.md: 0.66 mm mean on edge + dense depth).
#include <catch2/catch.hpp>
#include <filesystem>

#include "icgp/eval/metrics.h"
#include "icgp/eval/sequence.h"
#include "icgp/eval/sequence_run.h"
#include "icgp/visp/visp_baseline.h"
#include "icgp/visp/visp_camera_xml.h"

using namespace icgp;
using Catch::Matchers::Contains;

namespace {

const std::filesystem::path kBlender = std::filesystem::path(ICGP_TEST_DATA_DIR) / "teabox-blender";

}  // namespace

TEST_CASE("vpMbGenericTracker edge + dense depth follows 10 teabox-blender frames where the box moves") {
  const Sequence sequence = Sequence::open(kBlender.string(), visp_sequence_options());
  // From frame 20: over the first frames the box barely moves, and a pose frozen at the
  // start would meet the bounds below (8.6 mm mean over frames 20-29).
  std::vector<Frame> frames;
  for (int i = 20; i < 30; ++i) frames.push_back(sequence.load(i));

  const VispTrackerConfiguration edge_depth = visp_reference_configurations().front();
  REQUIRE(edge_depth.edge);
  REQUIRE(edge_depth.dense_depth);
  const VispModelFiles files = VispModelFiles::beside_model((kBlender / "teabox.cao").string());
  VispRgbdTracker tracker(edge_depth, files);
  int tracked_frames = 0;
  double sum_t_mm = 0.0, sum_r_deg = 0.0;
  run_sequence(FrameSource::of(frames), tracker.as_run_tracker(), *frames.front().truth(),
               [&](const Frame& frame, const TrackedFrame& outcome) {
                 CHECK(frame.index == 20 + tracked_frames);
                 CHECK(outcome.tracked);
                 CHECK(outcome.ms > 0.0);
                 sum_t_mm += translation_error_mm(outcome.reference_T_body, *frame.truth());
                 sum_r_deg += rotation_error_deg(outcome.reference_T_body, *frame.truth());
                 ++tracked_frames;
               });
  REQUIRE(tracked_frames == static_cast<int>(frames.size()));
  CHECK(sum_t_mm / frames.size() < 2.0);
  CHECK(sum_r_deg / frames.size() < 0.5);
}

TEST_CASE("ViSP model files are found beside the .cao, and a missing one is named") {
  const VispModelFiles files = VispModelFiles::beside_model((kBlender / "teabox.cao").string());
  CHECK(files.color_config == (kBlender / "teabox.xml").string());
  CHECK(files.depth_config == (kBlender / "teabox_depth.xml").string());
  CHECK_THROWS_WITH(VispModelFiles::beside_model((kBlender / "coffee.cao").string()), Contains("coffee.cao"));
}

TEST_CASE("a ViSP configuration needs a colour feature") {
  const VispModelFiles files = VispModelFiles::beside_model((kBlender / "teabox.cao").string());
  CHECK_THROWS_AS(VispRgbdTracker(VispTrackerConfiguration{"depth only", false, false, true}, files),
                  std::invalid_argument);
}
