// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker's exception contract: every error path a ViSP program can reach ends in a
// vpException (vpTrackingException for a frame that cannot be tracked) whose message names
// the method and what is at fault, never in another exception type, a crash or a hang.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <visp3/core/vpException.h>
#include <visp3/core/vpTrackingException.h>

#include "icgp/base/standard_stream_capture.h"
#include "icgp/eval/metrics.h"
#include "icgp/visp/conversions.h"
#include "icgp/visp/rgbd_tracking_loop.h"
#include "test_temp_dir.h"
#include "vpmbicgtracker_test_setup.h"

using namespace icgp;
using Catch::Matchers::Contains;

namespace {

const std::string kTeaboxCao = (test::kTeaboxBlender / "teabox.cao").string();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Every point of `cloud` set to (x, y, z).
void fill(std::vector<vpColVector>& cloud, double x, double y, double z) {
  for (vpColVector& p : cloud) {
    p[0] = x;
    p[1] = y;
    p[2] = z;
  }
}

/// vpMbTracker's projection-error model (protected: ViSP offers no accessor).
class ProjectionErrorModel : public vpMbIcgTracker {
 public:
  std::size_t lines() const { return m_projectionErrorLines.size(); }
  std::size_t faces() { return m_projectionErrorFaces.size(); }
};

}  // namespace

TEST_CASE("vpMbIcgTracker exceptions: files are ioError when missing or unreadable, badValue when malformed") {
  vpMbIcgTracker tracker;
  const std::filesystem::path missing = std::filesystem::temp_directory_path() / "icgp-no-such-dir";

  SECTION("missing model file") {
    REQUIRE_THROWS_AS(tracker.loadModel((missing / "box.cao").string()), vpException);
    REQUIRE_THROWS_WITH(tracker.loadModel((missing / "box.cao").string()),
                        Contains("vpMbIcgTracker") && Contains("box.cao") && Contains("does not exist"));
    CHECK(test::vp_exception_of([&] { tracker.loadModel((missing / "box.cao").string()); }).getCode() ==
          vpException::ioError);
  }
  SECTION("a model path that is a directory") {
    const vpException e = test::vp_exception_of([&] { tracker.loadModel(missing.parent_path().string()); });
    CHECK(e.getCode() == vpException::ioError);
    CHECK_THAT(e.getStringMessage(), Contains("is not a regular file"));
  }
  SECTION("a model file that is no mesh") {
    const test::TempDir dir("icgp-exceptions");
    const std::string garbage = dir.write("garbage.obj", "this is not a mesh\n\x01\x02\x03");
    const vpException e = test::vp_exception_of([&] { tracker.loadModel(garbage); });
    CHECK(e.getCode() == vpException::badValue);
    CHECK_THAT(e.getStringMessage(), Contains("vpMbIcgTracker::loadModel") && Contains("garbage.obj"));
    CHECK(tracker.getNbPolygon() == 0);  // nothing of it was kept
  }
  SECTION("malformed YAML configuration") {
    const test::TempDir dir("icgp-exceptions");
    const std::string yaml = dir.write("malformed.yaml", "region_model: {n_divides: [3\n");
    const vpException e = test::vp_exception_of([&] { tracker.loadConfigFile(yaml, false); });
    CHECK(e.getCode() == vpException::badValue);
    CHECK_THAT(e.getStringMessage(), Contains("vpMbIcgTracker::loadConfigFile") && Contains("malformed.yaml") &&
                                         Contains("YAML syntax error"));
  }
  SECTION("a YAML value out of its type") {
    const test::TempDir dir("icgp-exceptions");
    const std::string yaml = dir.write("wrong-type.yaml", "region_model: {n_divides: many}\n");
    const vpException e = test::vp_exception_of([&] { tracker.loadConfigFile(yaml, false); });
    CHECK(e.getCode() == vpException::badValue);
    CHECK_THAT(e.getStringMessage(), Contains("n_divides") && Contains("wrong-type.yaml"));
  }
}

TEST_CASE("vpMbIcgTracker exceptions: bad arguments are badValue naming the value") {
  vpMbIcgTracker tracker(kRgbdTrackerTypes);

  SECTION("unknown modality") {
    REQUIRE_THROWS_AS(tracker.setModalities({"edges"}), vpException);
    REQUIRE_THROWS_WITH(tracker.setModalities({"edges"}), Contains("setModalities") && Contains("'edges'"));
  }
  SECTION("unknown camera name") {
    const vpException e = test::vp_exception_of(
        [&] { tracker.setCameraParameters(std::map<std::string, vpCameraParameters>{{"Kamera1", {}}}); });
    CHECK(e.getCode() == vpException::badValue);
    CHECK_THAT(e.getStringMessage(), Contains("setCameraParameters") && Contains("'Kamera1'") &&
                                         Contains("\"Camera1\", \"Camera2\""));
  }
  SECTION("invalid tracker type") {
    const vpException e = test::vp_exception_of([&] { tracker.setTrackerType(64); });
    CHECK(e.getCode() == vpException::badValue);
    CHECK_THAT(e.getStringMessage(), Contains("64"));
  }
  SECTION("a display of an impossible size") {
    tracker.loadModel(kTeaboxCao);
    vpHomogeneousMatrix cMo(0, 0, 0.5, 0, 0, 0);
    const vpException e = test::vp_exception_of(
        [&] { tracker.getModelForDisplay(2000000000u, 480, cMo, vpCameraParameters(600, 600, 320, 240)); });
    CHECK(e.getCode() == vpException::badValue);
    CHECK_THAT(e.getStringMessage(), Contains("getModelForDisplay") && Contains("2000000000") &&
                                         Contains("[1, 16384]"));
  }
}

TEST_CASE("vpMbIcgTracker exceptions: tracking before initialisation is vpTrackingException::initializationError") {
  vpMbIcgTracker tracker;
  const vpImage<unsigned char> I(480, 640, 0);
  REQUIRE_THROWS_AS(tracker.track(I), vpTrackingException);
  CHECK(test::vp_exception_of<vpTrackingException>([&] { tracker.track(I); }).getCode() ==
        vpTrackingException::initializationError);
  REQUIRE_THROWS_WITH(tracker.track(I), Contains("track(I)") && Contains("initFromPose"));
}

TEST_CASE("vpMbIcgTracker exceptions: clouds and depth of a wrong size are refused before anything is read") {
  test::RgbdTeabox t(3);
  t.init_at_truth();
  const unsigned int w = t.input.depth_width, h = t.input.depth_height;

  SECTION("a cloud that is not width x height") {
    t.widths[kDepthCamera] = w / 2;
    const vpException e = test::vp_exception_of([&] { t.track(); });
    CHECK(e.getCode() == vpException::badValue);
    CHECK_THAT(e.getStringMessage(), Contains(std::to_string(w * h)) && Contains(std::to_string(w / 2)));
  }
  SECTION("a huge width and height") {
    t.widths[kDepthCamera] = 100000;
    t.heights[kDepthCamera] = 100000;
    const vpException e = test::vp_exception_of([&] { t.track(); });
    CHECK(e.getCode() == vpException::badValue);
    CHECK_THAT(e.getStringMessage(), Contains("Camera2") && Contains("100000 x 100000") && Contains("[1, 16384]"));
  }
  SECTION("a width of 0 with a height (0 x 0 alone means no depth)") {
    const std::vector<vpColVector> empty;
    t.clouds[kDepthCamera] = &empty;
    t.widths[kDepthCamera] = 0;
    t.heights[kDepthCamera] = 5;
    const vpException e = test::vp_exception_of([&] { t.track(); });
    CHECK(e.getCode() == vpException::badValue);
    CHECK_THAT(e.getStringMessage(), Contains("0 x 5"));
  }
  SECTION("a null cloud") {
    t.clouds[kDepthCamera] = nullptr;
    const vpException e = test::vp_exception_of([&] { t.track(); });
    CHECK(e.getCode() == vpException::badValue);
    CHECK_THAT(e.getStringMessage(), Contains("null"));
  }
  // A refused frame leaves the tracker as it was: the next good frame tracks.
  t.clouds[kDepthCamera] = &t.input.point_cloud;
  t.widths[kDepthCamera] = w;
  t.heights[kDepthCamera] = h;
  REQUIRE_NOTHROW(t.track());
  CHECK(translation_error_mm(t.pose(), *t.frame.truth()) < 0.5);
}

TEST_CASE("vpMbIcgTracker exceptions: a camera's image and depth of different sizes are refused naming both") {
  // One camera with every cue reads its image and its registered raw depth.
  const std::vector<Frame> frames = test::teabox_frames(1);
  const Frame& frame = frames.front();
  VispRgbdFrame input;
  input.convert(frame, false);
  vpMbIcgTracker tracker;
  test::configure_for_tests(tracker);
  tracker.loadModel(kTeaboxCao);
  tracker.setCameraParameters(to_camera_parameters(frame.colors.front().intrinsics));
  tracker.initFromPose(input.grey, to_homogeneous_matrix(*frame.truth()));
  const unsigned int w = input.grey.getWidth(), h = input.grey.getHeight();
  const vpImage<uint16_t> half_depth(h / 2, w / 2, 1000);
  const vpException e = test::vp_exception_of([&] { tracker.track(input.grey, half_depth, 0.001); });
  CHECK(e.getCode() == vpException::badValue);
  CHECK_THAT(e.getStringMessage(), Contains("track(I, I_depth_raw, depthScale)") && Contains("'Camera'") &&
                                       Contains(std::to_string(w) + " x " + std::to_string(h) + " image") &&
                                       Contains(std::to_string(w / 2) + " x " + std::to_string(h / 2) + " depth"));
}

TEST_CASE("vpMbIcgTracker exceptions: a cloud without one valid measurement is no depth") {
  SECTION("with the colour cues: the frame is tracked by them, and said once") {
    test::RgbdTeabox t(3);
    t.init_at_truth();
    std::vector<vpColVector> nan_cloud = t.input.point_cloud;
    t.clouds[kDepthCamera] = &nan_cloud;
    for (std::size_t i = 1; i < t.frames.size(); ++i) {
      t.input.convert(t.frames[i]);
      // Points with a finite Z but a NaN X, then NaN depth: neither is a measurement.
      if (i == 1)
        fill(nan_cloud, kNaN, 0.0, 0.5);
      else
        fill(nan_cloud, 0.0, 0.0, kNaN);
      const StandardStreamCapture cerr(std::cerr);
      REQUIRE_NOTHROW(t.track());
      INFO("frame " << i);
      if (i == 1)
        CHECK_THAT(cerr.text(), Contains("camera 'Camera2'") && Contains("has no valid measurement"));
      else
        CHECK_THAT(cerr.text(), !Contains("no valid measurement"));  // said once for the run
      CHECK(t.tracker.getNbFeaturesDepthDense() == 0);
      CHECK(translation_error_mm(t.pose(), *t.frames[i].truth()) < 5.0);  // region and texture alone
      CHECK(rotation_error_deg(t.pose(), *t.frames[i].truth()) < 1.0);
    }
    // A frame with depth again: the depth cue is back.
    t.clouds[kDepthCamera] = &t.input.point_cloud;
    t.track();
    CHECK(t.tracker.getNbFeaturesDepthDense() > 100);
  }
  SECTION("alone: vpTrackingException::notEnoughPointError, as vpMbGenericTracker's depth trackers") {
    test::RgbdTeabox t(3);
    t.init_at_truth();
    t.tracker.setModalities({"depth"});
    t.tracker.initFromPose(t.input.grey, to_homogeneous_matrix(*t.frame.truth()));
    std::vector<vpColVector> inf_cloud = t.input.point_cloud;
    fill(inf_cloud, 0.0, 0.0, std::numeric_limits<double>::infinity());
    t.clouds[kDepthCamera] = &inf_cloud;
    const vpTrackingException e = test::vp_exception_of<vpTrackingException>([&] { t.track(); });
    CHECK(e.getCode() == vpTrackingException::notEnoughPointError);
    CHECK_THAT(e.getStringMessage(), Contains("vpMbIcgTracker::track") && Contains("'Camera2'") &&
                                         Contains("no valid measurement"));
  }
}

TEST_CASE("vpMbIcgTracker exceptions: an object started out of view is lost, and testTracking says why") {
  // The object 20 m to the side: no cue has anything to measure. The frame is tracked, the
  // pose held where it was given, and testTracking's vpTrackingException gives the reason.
  test::RgbdTeabox t(3);
  t.init_at_truth(Eigen::Vector3d(20.0, 0.0, 0.0));
  const Pose truth = *t.frame.truth();
  const vpHomogeneousMatrix given = t.tracker.getPose();
  REQUIRE_NOTHROW(t.track());
  const vpTrackingException e = test::vp_exception_of<vpTrackingException>([&] { t.tracker.testTracking(); });
  CHECK(e.getCode() == vpTrackingException::fatalError);
  INFO(e.getStringMessage());
  CHECK_THAT(e.getStringMessage(), Contains("lost"));
  CHECK(translation_error_mm(t.pose(), to_pose(given)) < 1e-6);
  // The program may go on: a pose in view, and the frame tracks.
  t.tracker.initFromPose(t.input.grey, to_homogeneous_matrix(truth));
  REQUIRE_NOTHROW(t.track());
  CHECK_NOTHROW(t.tracker.testTracking());
  CHECK(translation_error_mm(t.pose(), truth) < 0.5);
}

TEST_CASE("vpMbIcgTracker exceptions: a camera without valid parameters is badValue from the core's check") {
  test::RgbdTeabox t(3);
  t.init_at_truth();
  t.tracker.setCameraParameters(vpCameraParameters(-600.0, 600.0, 320.0, 240.0),
                                to_camera_parameters(t.frame.depths.front().intrinsics));
  const vpException e = test::vp_exception_of([&] { t.track(); });
  CHECK(e.getCode() == vpException::badValue);
  CHECK_THAT(e.getStringMessage(), Contains("Camera1") && Contains("focal lengths must be positive"));
}

TEST_CASE("vpMbIcgTracker: resetTracker and reInitModel forget ViSP's projection-error model") {
  ProjectionErrorModel tracker;
  test::configure_for_tests(tracker);
  tracker.loadModel(kTeaboxCao);
  // The teabox: 6 faces of 4 points, 12 edges.
  REQUIRE(tracker.lines() == 12);
  REQUIRE(tracker.faces() == 6);

  tracker.resetTracker();
  CHECK(tracker.lines() == 0);
  CHECK(tracker.faces() == 0);
  test::configure_for_tests(tracker);
  tracker.loadModel(kTeaboxCao);
  CHECK(tracker.lines() == 12);
  CHECK(tracker.faces() == 6);

  const vpImage<unsigned char> I(480, 640, 0);
  tracker.setCameraParameters(vpCameraParameters(600, 600, 320, 240));
  tracker.reInitModel(I, kTeaboxCao, vpHomogeneousMatrix(0, 0, 0.5, 0, 0, 0));
  CHECK(tracker.lines() == 12);
  CHECK(tracker.faces() == 6);
}
