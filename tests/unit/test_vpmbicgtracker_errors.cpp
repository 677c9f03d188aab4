// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker reports misuse as a ViSP program expects from vpMbGenericTracker: a
// vpException (or vpTrackingException) with ViSP's error code and a message naming the
// file, camera or size at fault.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <visp3/core/vpException.h>
#include <visp3/core/vpTrackingException.h>

#include "icgp/base/standard_stream_capture.h"
#include "icgp/eval/metrics.h"
#include "icgp/visp/conversions.h"
#include "icgp/visp/rgbd_tracking_loop.h"
#include "vpmbicgtracker_test_setup.h"

using namespace icgp;
using icgp::test::vp_exception_of;
using Catch::Matchers::Contains;

namespace {

const std::string kTeaboxCao = (test::kTeaboxBlender / "teabox.cao").string();

}  // namespace

TEST_CASE("vpMbIcgTracker: missing and unsupported files are ViSP exceptions naming the file") {
  vpMbIcgTracker tracker(kRgbdTrackerTypes);
  const std::filesystem::path missing = std::filesystem::temp_directory_path() / "icgp-no-such-dir";

  SECTION("missing mesh") {
    const vpException e = vp_exception_of([&] { tracker.loadModel((missing / "box.obj").string()); });
    CHECK(e.getCode() == vpException::ioError);
    CHECK_THAT(e.getStringMessage(), Contains("box.obj"));
  }
  SECTION("missing .cao") {
    const vpException e = vp_exception_of([&] { tracker.loadModel((missing / "box.cao").string()); });
    CHECK(e.getCode() == vpException::ioError);
    CHECK_THAT(e.getStringMessage(), Contains("box.cao"));
  }
  SECTION("unsupported model extension") {
    // The file exists and holds points, so only the extension can be refused.
    const std::filesystem::path xyz = std::filesystem::temp_directory_path() / "icgp-test-points.xyz";
    std::ofstream(xyz) << "0 0 0\n0.1 0 0\n0 0.1 0\n";
    const vpException e = vp_exception_of([&] { tracker.loadModel(xyz.string()); });
    std::filesystem::remove(xyz);
    CHECK(e.getCode() == vpException::badValue);
    CHECK_THAT(e.getStringMessage(), Contains(".xyz"));
  }
  SECTION("missing parameter file") {
    const vpException e = vp_exception_of([&] { tracker.loadConfigFile((missing / "icgp.yaml").string(), false); });
    CHECK(e.getCode() == vpException::ioError);
    CHECK_THAT(e.getStringMessage(), Contains("icgp.yaml"));
  }
  SECTION("missing ViSP XML of the depth camera") {
    const vpException e = vp_exception_of([&] {
      tracker.loadConfigFile((test::kTeaboxBlender / "teabox.xml").string(), (missing / "depth.xml").string(), false);
    });
    CHECK(e.getCode() == vpException::ioError);
    CHECK_THAT(e.getStringMessage(), Contains("depth.xml"));
  }
}

TEST_CASE("vpMbIcgTracker: setModalities refuses a name that is no cue, naming it, and keeps the cues it had") {
  vpMbIcgTracker tracker;
  tracker.setModalities({"region", "depth"});
  const vpException e = vp_exception_of([&] { tracker.setModalities({"region", "edges"}); });
  CHECK(e.getCode() == vpException::badValue);
  CHECK_THAT(e.getStringMessage(), Contains("setModalities") && Contains("'edges'") &&
                                       Contains("region, depth, texture"));
  CHECK(tracker.getTrackerConfig().modalities == std::vector<std::string>{icgp::cue::kRegion, icgp::cue::kDepth});
}

TEST_CASE("vpMbIcgTracker: tracking before initFromPose is a vpTrackingException") {
  test::RgbdTeabox f(1);
  const vpTrackingException e = vp_exception_of<vpTrackingException>([&] { f.track(); });
  CHECK(e.getCode() == vpTrackingException::initializationError);
  CHECK_THAT(e.getStringMessage(), Contains("initFromPose"));
}

TEST_CASE("vpMbIcgTracker: a mask that hides the whole object is a loss with its reason; the pose is held, not moved") {
  test::RgbdTeabox f(1);
  f.init_at_truth();
  const std::vector<Frame> frames = test::teabox_frames(10);
  vpImage<bool> nowhere(f.input.grey.getHeight(), f.input.grey.getWidth(), false),
      everywhere(f.input.grey.getHeight(), f.input.grey.getWidth(), true);
  vpHomogeneousMatrix before_mask;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const bool masked = i >= 2 && i < 6;
    INFO("frame " << i << (masked ? ", all masked" : ""));
    f.tracker.setMask(masked ? nowhere : everywhere);
    f.input.convert(frames[i]);
    REQUIRE_NOTHROW(f.track());
    if (i == 1) before_mask = f.tracker.getPose();
    if (masked) {
      const vpTrackingException e = vp_exception_of<vpTrackingException>([&] { f.tracker.testTracking(); });
      CHECK(e.getCode() == vpTrackingException::fatalError);
      CHECK_THAT(e.getStringMessage(), Contains("lost"));
      INFO(e.getStringMessage());
      // The box moved about 2 mm a frame meanwhile; the reported pose is the last one seen.
      CHECK((to_pose(f.tracker.getPose()).translation() - to_pose(before_mask).translation()).norm() < 1e-4);
    } else if (i >= 8) {
      // Found again near where it was lost once the mask lifts: back on the truth, which a
      // pose held from frame 1 misses by about 14 mm by now.
      CHECK_NOTHROW(f.tracker.testTracking());
      CHECK(translation_error_mm(f.pose(), *frames[i].truth()) < 1.0);
    }
  }
  CHECK(translation_error_mm(to_pose(before_mask), *frames.back().truth()) > 5.0);
}

TEST_CASE("vpMbIcgTracker: RGB-D maps with an unknown camera or a cloud of the wrong size are refused") {
  test::RgbdTeabox f(1);
  f.init_at_truth();

  SECTION("unknown camera in the point cloud maps") {
    for (auto* map : {&f.widths, &f.heights}) (*map)["Camera3"] = (*map)[kDepthCamera];
    f.clouds["Camera3"] = f.clouds[kDepthCamera];
    const vpException e = vp_exception_of([&] { f.track(); });
    CHECK(e.getCode() == vpException::badValue);
    CHECK_THAT(e.getStringMessage(), Contains("Camera3"));
  }
  SECTION("unknown camera in the image map") {
    f.images["Camera3"] = &f.input.grey;
    const vpException e = vp_exception_of([&] { f.track(); });
    CHECK(e.getCode() == vpException::badValue);
    CHECK_THAT(e.getStringMessage(), Contains("Camera3"));
  }
  SECTION("cloud smaller than width x height") {
    f.heights[kDepthCamera] += 1;
    const vpException e = vp_exception_of([&] { f.track(); });
    CHECK(e.getCode() == vpException::badValue);
    CHECK_THAT(e.getStringMessage(), Contains(std::to_string(f.input.point_cloud.size())));
  }
}

TEST_CASE("vpMbIcgTracker: width and height 0 in the cloud maps mean no depth this frame, as in ViSP") {
  test::RgbdTeabox f(1);
  f.init_at_truth();
  const std::vector<Frame> frames = test::teabox_frames(8);
  const std::vector<vpColVector> empty_cloud;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    f.input.convert(frames[i]);
    const bool depth = i % 2 == 0;
    // ViSP's programs pass 0 x 0 with the last cloud or with an empty one.
    f.clouds[kDepthCamera] = depth || i % 4 == 1 ? &f.input.point_cloud : &empty_cloud;
    f.widths[kDepthCamera] = depth ? f.input.depth_width : 0;
    f.heights[kDepthCamera] = depth ? f.input.depth_height : 0;
    INFO("frame " << i << (depth ? " with depth" : " without depth"));
    REQUIRE_NOTHROW(f.track());
    vpHomogeneousMatrix cMo;
    f.tracker.getPose(cMo);
    // Region and texture alone hold the pose, less exactly along the line of sight.
    CHECK(translation_error_mm(to_pose(cMo), *frames[i].truth()) < (depth ? 0.5 : 5.0));
    CHECK(rotation_error_deg(to_pose(cMo), *frames[i].truth()) < 1.0);
    // The depth cue's residuals are in getError() only on frames with depth: on this exact
    // synthetic depth its point-to-plane errors are micrometres, where the region and
    // texture cues' errors are fractions of a pixel.
    const vpColVector residuals = f.tracker.getError();
    int tiny = 0;
    for (unsigned int k = 0; k < residuals.size(); ++k) tiny += std::abs(residuals[k]) < 1e-4 ? 1 : 0;
    if (depth)
      CHECK(tiny > 100);
    else
      CHECK(tiny < 10);
  }
}

TEST_CASE("vpMbIcgTracker: resetTracker keeps the camera transformation matrix, as vpMbGenericTracker does") {
  test::RgbdTeabox f(1);
  f.init_at_truth();
  const std::vector<Frame> frames = test::teabox_frames(6);
  // What ViSP's RGB-D example does after a reset: settings, model, cameras and pose again,
  // but not the depth camera's extrinsics (here a 10 cm baseline).
  f.tracker.resetTracker();
  test::configure_for_tests(f.tracker);
  f.tracker.loadModel(kTeaboxCao, kTeaboxCao);
  f.tracker.setCameraParameters(to_camera_parameters(f.frame.colors.front().intrinsics),
                                to_camera_parameters(f.frame.depths.front().intrinsics));
  f.input.convert(frames.front());
  f.tracker.initFromPose(f.input.grey, to_homogeneous_matrix(*frames.front().truth()));
  for (const Frame& frame : frames) {
    f.input.convert(frame);
    f.track();
    vpHomogeneousMatrix cMo;
    f.tracker.getPose(cMo);
    INFO("frame " << frame.index);
    CHECK(translation_error_mm(to_pose(cMo), *frame.truth()) < 0.5);
    CHECK(rotation_error_deg(to_pose(cMo), *frame.truth()) < 0.2);
  }
}

TEST_CASE("vpMbIcgTracker: track(I) with the depth cue alone is a vpException naming the call") {
  test::RgbdTeabox f(1);
  f.init_at_truth();
  f.tracker.setModalities({"depth"});
  f.tracker.initFromPose(f.input.grey, to_homogeneous_matrix(*f.frame.truth()));
  const vpException e = vp_exception_of([&] { f.tracker.track(f.input.grey); });
  CHECK(e.getCode() == vpException::badValue);
  CHECK_THAT(e.getStringMessage(), Contains("track(I)"));
}

TEST_CASE("vpMbIcgTracker: setScanLineVisibilityTest is accepted and reported once as having no effect") {
  vpMbIcgTracker tracker;
  std::string text;
  {
    const icgp::StandardStreamCapture said(std::cerr);
    tracker.setScanLineVisibilityTest(true);
    tracker.setScanLineVisibilityTest(false);
    text = said.text();
  }
  CHECK_THAT(text, Contains("setScanLineVisibilityTest: no effect"));
  CHECK(text.find("setScanLineVisibilityTest") == text.rfind("setScanLineVisibilityTest"));  // once
}

TEST_CASE("vpMbIcgTracker: a depth sampling step of 0 is a vpException naming the step") {
  vpMbIcgTracker tracker(1, vpMbIcgTracker::DEPTH_DENSE_TRACKER);
  const vpException dense = vp_exception_of([&] { tracker.setDepthDenseSamplingStep(0, 2); });
  CHECK(dense.getCode() == vpException::badValue);
  CHECK_THAT(dense.getStringMessage(),
             Contains("setDepthDenseSamplingStep") && Contains("(0, 2)") && Contains("pixels from 1"));
  const vpException normal = vp_exception_of([&] { tracker.setDepthNormalSamplingStep(3, 0); });
  CHECK(normal.getCode() == vpException::badValue);
  CHECK_THAT(normal.getStringMessage(), Contains("setDepthNormalSamplingStep") && Contains("(3, 0)"));
}
