// SPDX-License-Identifier: GPL-2.0-or-later
// The principal-point convention of teabox-blender, decided by the data itself: the
// ground-truth pose rendered with the corrected intrinsics reproduces Blender's exact depth
// images, the intrinsics as written in the XML do not.
#include <catch2/catch.hpp>

#include "icgp/eval/sequence.h"
#include "icgp/render/renderer.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/visp_camera_xml.h"

using namespace icgp;

namespace {

/// Mean (rendered − measured) depth over pixels where both see the box, in metres.
double mean_depth_difference(const Sequence& sequence, int index) {
  static const Mesh teabox = load_cao_mesh(ICGP_TEST_DATA_DIR "/teabox-blender/teabox.cao");
  Renderer renderer;
  const auto body = renderer.add_body(teabox, 1);
  const Frame frame = sequence.load(index);
  const DepthImage& measured = frame.depths[0];
  renderer.set_body_pose(body, measured.camera_T_reference * *frame.truth());
  const cv::Mat rendered = renderer.render(measured.intrinsics, Pose(), kRenderDepth).depth;
  double sum = 0.0;
  int n = 0;
  for (int i = 0; i < rendered.rows; ++i)
    for (int j = 0; j < rendered.cols; ++j) {
      const float r = rendered.at<float>(i, j), m = measured.depth.at<float>(i, j);
      if (r > 0.f && m > 0.f) {
        sum += r - m;
        ++n;
      }
    }
  REQUIRE(n > 1000);
  return sum / n;
}

}  // namespace

TEST_CASE("teabox-blender: the corrected principal point reproduces Blender's depth") {
  const Sequence as_written = Sequence::open(ICGP_TEST_DATA_DIR "/teabox-blender", visp_sequence_options());
  SequenceOptions options = visp_sequence_options();
  options.blender_principal_point = true;
  const Sequence corrected = Sequence::open(ICGP_TEST_DATA_DIR "/teabox-blender", options);
  for (int index : {50, 99}) {
    INFO("frame " << index);
    CHECK(std::abs(mean_depth_difference(corrected, index)) < 3e-5);
    CHECK(std::abs(mean_depth_difference(as_written, index)) > 1e-4);
  }
}
