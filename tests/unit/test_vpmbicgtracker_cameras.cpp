// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker's cameras as vpMbGenericTracker's: named and typed as its constructors do,
// depth-only rigs that need no colour image, colour cues that need one, ViSP's pixel mask,
// and one object described by different model files for different cameras.
#include <catch2/catch.hpp>
#include <functional>
#include <iostream>
#include <sstream>
#include <visp3/core/vpException.h>
#include <visp3/mbt/vpMbGenericTracker.h>

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
const std::filesystem::path kRealsenseModels =
    std::filesystem::path(ICGP_TEST_DATA_DIR) / "realsense-cube" / "models" / "teabox";


/// The depth camera's organised cloud of a frame, in ViSP's map form under `camera`.
struct CloudMaps {
  std::map<std::string, const std::vector<vpColVector>*> clouds;
  std::map<std::string, unsigned int> widths, heights;

  CloudMaps(const std::string& camera, const VispRgbdFrame& input)
      : clouds{{camera, &input.point_cloud}},
        widths{{camera, input.depth_width}},
        heights{{camera, input.depth_height}} {}
};

}  // namespace

TEST_CASE("vpMbIcgTracker tracks depth alone with one camera under ViSP's default name \"Camera\"") {
  const std::vector<Frame> frames = test::teabox_frames(8);
  const DepthImage& depth = frames.front().depths.front();
  vpMbIcgTracker tracker(1, vpMbIcgTracker::DEPTH_DENSE_TRACKER);
  CHECK(tracker.getCameraNames() == vpMbGenericTracker(1, vpMbGenericTracker::DEPTH_DENSE_TRACKER).getCameraNames());
  test::configure_for_tests(tracker);
  tracker.loadModel(kTeaboxCao);
  tracker.setCameraParameters(to_camera_parameters(depth.intrinsics));
  // The depth camera is the reference: its pose of the object is depth_M_color * cMo.
  const vpHomogeneousMatrix depth_M_color = to_homogeneous_matrix(depth.camera_T_reference);
  tracker.initFromPose(vpImage<unsigned char>(), depth_M_color * to_homogeneous_matrix(*frames.front().truth()));
  VispRgbdFrame input;
  std::map<std::string, const vpImage<unsigned char>*> no_images;
  for (const Frame& frame : frames) {
    input.convert(frame);
    CloudMaps maps("Camera", input);
    REQUIRE_NOTHROW(tracker.track(no_images, maps.clouds, maps.widths, maps.heights));
    const Pose depth_T_object = depth.camera_T_reference * *frame.truth();
    INFO("frame " << frame.index);
    CHECK(translation_error_mm(to_pose(tracker.getPose()), depth_T_object) < 0.5);
    CHECK(rotation_error_deg(to_pose(tracker.getPose()), depth_T_object) < 0.3);
  }
}

TEST_CASE("vpMbIcgTracker: an RGB-D rig configured for the depth cue alone tracks without a colour image") {
  const std::vector<Frame> frames = test::teabox_frames(6);
  vpMbIcgTracker tracker(kRgbdTrackerTypes);
  test::configure_for_tests(tracker);
  tracker.setModalities({"depth"});
  tracker.loadModel(kTeaboxCao);
  tracker.setCameraParameters(to_camera_parameters(frames.front().colors.front().intrinsics),
                              to_camera_parameters(frames.front().depths.front().intrinsics));
  tracker.setCameraTransformationMatrix(kDepthCamera,
                                        to_homogeneous_matrix(frames.front().depths.front().camera_T_reference));
  tracker.initFromPose(vpImage<unsigned char>(), to_homogeneous_matrix(*frames.front().truth()));
  VispRgbdFrame input;
  std::map<std::string, const vpImage<unsigned char>*> no_images;
  for (const Frame& frame : frames) {
    input.convert(frame);
    CloudMaps maps(kDepthCamera, input);
    REQUIRE_NOTHROW(tracker.track(no_images, maps.clouds, maps.widths, maps.heights));
    INFO("frame " << frame.index);
    CHECK(translation_error_mm(to_pose(tracker.getPose()), *frame.truth()) < 0.5);
  }
}

TEST_CASE("vpMbIcgTracker: a colour cue without its camera's image is refused, naming the camera") {
  const std::vector<Frame> frames = test::teabox_frames(1);
  vpMbIcgTracker tracker(kRgbdTrackerTypes);
  test::configure_for_tests(tracker);
  tracker.loadModel(kTeaboxCao);
  tracker.setCameraParameters(to_camera_parameters(frames.front().colors.front().intrinsics),
                              to_camera_parameters(frames.front().depths.front().intrinsics));
  tracker.initFromPose(vpImage<unsigned char>(), to_homogeneous_matrix(*frames.front().truth()));
  VispRgbdFrame input;
  input.convert(frames.front());
  CloudMaps maps(kDepthCamera, input);
  std::map<std::string, const vpImage<unsigned char>*> no_images;
  const vpException e = vp_exception_of([&] { tracker.track(no_images, maps.clouds, maps.widths, maps.heights); });
  CHECK(e.getCode() == vpException::badValue);
  CHECK_THAT(e.getStringMessage(), Contains("no image of camera 'Camera1'"));
}

TEST_CASE("vpMbIcgTracker: ViSP's tutorial set-up, default constructor and setTrackerType, tracks grey images") {
  const std::vector<Frame> frames = test::teabox_frames(6);
  vpMbIcgTracker tracker;
  tracker.setTrackerType(vpMbIcgTracker::EDGE_TRACKER | vpMbIcgTracker::KLT_TRACKER);
  test::configure_for_tests(tracker);
  tracker.loadConfigFile((test::kTeaboxBlender / "teabox.xml").string(), false);
  tracker.loadModel(kTeaboxCao);
  VispRgbdFrame input;
  input.convert(frames.front(), false);
  tracker.initFromPose(input.grey, to_homogeneous_matrix(*frames.front().truth()));
  for (const Frame& frame : frames) {
    input.convert(frame, false);
    REQUIRE_NOTHROW(tracker.track(input.grey));
    INFO("frame " << frame.index);
    // teabox.xml's principal point is Blender's less half a pixel: a few mm along the line
    // of sight for a monocular tracker.
    CHECK(translation_error_mm(to_pose(tracker.getPose()), *frame.truth()) < 5.0);
    CHECK(rotation_error_deg(to_pose(tracker.getPose()), *frame.truth()) < 1.0);
  }
}

TEST_CASE("vpMbIcgTracker::setMask: every cue ignores the pixels the mask excludes") {
  const std::vector<Frame> frames = test::teabox_frames(1);
  const Frame& frame = frames.front();
  const auto tracked = [&](const vpImage<bool>* mask) {
    auto tracker = std::make_unique<vpMbIcgTracker>(kRgbdTrackerTypes);
    test::configure_for_tests(*tracker);
    tracker->loadModel(kTeaboxCao);
    tracker->setCameraParameters(to_camera_parameters(frame.colors.front().intrinsics),
                                 to_camera_parameters(frame.depths.front().intrinsics));
    tracker->setCameraTransformationMatrix(kDepthCamera,
                                           to_homogeneous_matrix(frame.depths.front().camera_T_reference));
    if (mask) tracker->setMask(*mask);
    VispRgbdFrame input;
    input.convert(frame);
    tracker->initFromPose(input.grey, to_homogeneous_matrix(*frame.truth()));
    std::map<std::string, const vpImage<unsigned char>*> images{{kColorCamera, &input.grey}};
    CloudMaps maps(kDepthCamera, input);
    // Two frames: texture measures from the second, after its first keyframe.
    tracker->track(images, maps.clouds, maps.widths, maps.heights);
    tracker->track(images, maps.clouds, maps.widths, maps.heights);
    return tracker;
  };
  const unsigned int width = static_cast<unsigned int>(frame.colors.front().intrinsics.width);
  const unsigned int height = static_cast<unsigned int>(frame.colors.front().intrinsics.height);
  const double half = width / 2.0;

  const auto unmasked = tracked(nullptr);
  const auto left_columns = [&](const vpMbIcgTracker& t, double type) {
    int n = 0;
    for (const std::vector<double>& f : const_cast<vpMbIcgTracker&>(t).getFeaturesForDisplay())
      n += f[0] == type && f[2] < half ? 1 : 0;
    return n;
  };
  REQUIRE(left_columns(*unmasked, 0.0) > 10);  // the box spans both halves of the image
  REQUIRE(left_columns(*unmasked, 1.0) > 10);
  REQUIRE(unmasked->getNbFeaturesDepthDense() > 50);

  vpImage<bool> right_half(height, width, false);
  for (unsigned int r = 0; r < height; ++r)
    for (unsigned int c = width / 2; c < width; ++c) right_half[r][c] = true;
  const auto masked = tracked(&right_half);
  // Region lines start from allowed pixels; their contour lies within the line's length of
  // it. Texture keypoints must lie on allowed pixels.
  for (const std::vector<double>& f : masked->getFeaturesForDisplay()) {
    INFO("feature type " << f[0] << " at column " << f[2]);
    if (f[0] == 0.0) CHECK(f[2] >= half - 20.0);
    if (f[0] == 1.0) CHECK(f[2] >= half - 0.5);
  }
  CHECK(masked->getNbFeaturesEdge() > 10);
  CHECK(masked->getNbFeaturesEdge() < unmasked->getNbFeaturesEdge());

  // The depth image has the mask's size here: none of its points are used under an all-false mask.
  const vpImage<bool> nothing(height, width, false);
  REQUIRE(frame.depths.front().intrinsics.width == static_cast<int>(width));
  CHECK(tracked(&nothing)->getNbFeaturesDepthDense() == 0);
}

TEST_CASE("vpMbIcgTracker::loadModel: a .wrl and a .cao of one object for two cameras, as ViSP's RGB-D test loads them") {
  vpMbIcgTracker tracker(kRgbdTrackerTypes);
  const std::string wrl = (kRealsenseModels / "teabox.wrl").string();
  const std::string cao = (kRealsenseModels / "teabox.cao").string();
  REQUIRE_NOTHROW(tracker.loadModel(wrl, cao));
  // ViSP's faces of the .wrl (its projection-error model) are there, as in vpMbGenericTracker.
  CHECK(tracker.getNbPolygon() == 6);

  // Another object for the second camera is said on stderr, naming both files; the
  // reference camera's model is the one tracked, as one rigid object.
  vpMbIcgTracker other(kRgbdTrackerTypes);
  const std::string cube = (kRealsenseModels.parent_path() / "cube" / "cube.cao").string();
  const auto stderr_during = [](const std::function<void()>& call) {
    const icgp::StandardStreamCapture said(std::cerr);
    call();
    return said.text();
  };
  CHECK_THAT(stderr_during([&] { other.loadModel(cao, cube); }),
             Contains("cube.cao") && Contains("teabox.cao") && Contains("does not describe the object"));
  vpMbIcgTracker same(kRgbdTrackerTypes);
  CHECK(stderr_during([&] { same.loadModel(wrl, cao); }).find("does not describe") == std::string::npos);
}

TEST_CASE("vpMbIcgTracker with KLT_TRACKER alone: the texture cue's first frame, keyframe only, is not a loss") {
  const std::vector<Frame> frames = test::teabox_frames(6);
  vpMbIcgTracker tracker(1, vpMbIcgTracker::KLT_TRACKER);
  test::configure_for_tests(tracker);
  tracker.loadModel(kTeaboxCao);
  tracker.setCameraParameters(to_camera_parameters(frames.front().colors.front().intrinsics));
  VispRgbdFrame input;
  input.convert(frames.front(), false);
  tracker.initFromPose(input.grey, to_homogeneous_matrix(*frames.front().truth()));
  for (const Frame& frame : frames) {
    input.convert(frame, false);
    tracker.track(input.grey);
    INFO("frame " << frame.index);
    CHECK_NOTHROW(tracker.testTracking());
    CHECK(translation_error_mm(to_pose(tracker.getPose()), *frame.truth()) < 5.0);
  }
}

TEST_CASE("vpMbIcgTracker with KLT_TRACKER alone follows corners from frame to frame with ViSP's KLT settings") {
  const std::vector<Frame> frames = test::teabox_frames(12);
  vpMbIcgTracker tracker(1, vpMbIcgTracker::KLT_TRACKER);
  test::configure_for_tests(tracker);
  // A ViSP XML's <klt> block and setKltOpencv / setKltMaskBorder set the flow cue.
  tracker.loadConfigFile((test::kTeaboxBlender / "teabox.xml").string(), false);
  CHECK(tracker.getTrackerConfig().flow.max_features == 300);
  vpKltOpencv klt = tracker.getKltOpencv();
  klt.setWindowSize(7);
  klt.setMinDistance(4);
  tracker.setKltOpencv(klt);
  tracker.setKltMaskBorder(3);
  const icgp::FlowParams& flow = tracker.getTrackerConfig().flow;
  CHECK(flow.window_size == 7);
  CHECK(flow.min_distance == 4.0);
  CHECK(flow.mask_border == 3);
  REQUIRE(icgp::has_cue(tracker.getTrackerConfig().modalities, icgp::cue::kFlow));

  tracker.loadModel(kTeaboxCao);
  tracker.setCameraParameters(to_camera_parameters(frames.front().colors.front().intrinsics));
  VispRgbdFrame input;
  input.convert(frames.front(), false);
  tracker.initFromPose(input.grey, to_homogeneous_matrix(*frames.front().truth()));
  double max_mm = 0.0, max_deg = 0.0;
  unsigned int fewest = 100000;
  for (const Frame& frame : frames) {
    input.convert(frame, false);
    tracker.track(input.grey);
    CHECK_NOTHROW(tracker.testTracking());
    fewest = std::min(fewest, tracker.getNbFeaturesKlt());
    max_mm = std::max(max_mm, translation_error_mm(to_pose(tracker.getPose()), *frame.truth()));
    max_deg = std::max(max_deg, rotation_error_deg(to_pose(tracker.getPose()), *frame.truth()));
  }
  const Pose& first = *frames.front().truth();
  const Pose& last = *frames.back().truth();
  INFO("max error " << max_mm << " mm, " << max_deg << " deg; a frozen pose: " << translation_error_mm(first, last)
                    << " mm, " << rotation_error_deg(first, last) << " deg; fewest KLT features " << fewest);
  CHECK(max_mm < 2.0);
  CHECK(max_deg < 0.5);
  CHECK(max_mm < 0.5 * translation_error_mm(first, last));
  CHECK(fewest >= 100);  // 50 points: ViSP counts x and y of each
  CHECK(2 * tracker.getKltNbPoints() == static_cast<int>(tracker.getNbFeaturesKlt()));
}

TEST_CASE("vpMbIcgTracker with ViSP's RGB-D types: flow and edge work only in frames without depth") {
  // The default tracker against one whose flow and edge work in every frame, on the same
  // frames: first with depth, then without (ViSP's cloud of width and height 0).
  test::RgbdTeabox rig(6), always(6);
  TrackerConfig config = always.tracker.getTrackerConfig();
  REQUIRE(config.depth_stand_ins == std::vector<std::string>{cue::kFlow, cue::kEdge});
  config.depth_stand_ins.clear();
  always.tracker.setTrackerConfig(config);
  const auto track_frame = [](test::RgbdTeabox& r, int i, bool depth) {
    r.input.convert(r.frames[i]);
    r.widths[kDepthCamera] = depth ? r.input.depth_width : 0;
    r.heights[kDepthCamera] = depth ? r.input.depth_height : 0;
    r.track();
    return translation_error_mm(r.pose(), *r.frames[i].truth());
  };
  // Bounds a pose frozen at the start misses: it is 4.6 mm off on average over these frames.
  constexpr double kBoundWithDepthMm = 1.0, kBoundWithoutMm = 2.5;
  const auto frozen_mm = [&](int i) { return translation_error_mm(*rig.frames[0].truth(), *rig.frames[i].truth()); };
  rig.init_at_truth();
  always.init_at_truth();
  for (int i = 1; i <= 2; ++i) {
    CHECK(track_frame(rig, i, true) < kBoundWithDepthMm);
    track_frame(always, i, true);
  }
  // With depth, the KLT points are the texture cue's keyframe matches alone, and the edge
  // features the region cue's lines alone: flow's corners and edge's samples are missing.
  const int klt_with_depth = rig.tracker.getKltNbPoints();
  const unsigned int edge_with_depth = rig.tracker.getNbFeaturesEdge();
  INFO("KLT points " << klt_with_depth << " (flow and edge in every frame: " << always.tracker.getKltNbPoints()
                     << "), edge features " << edge_with_depth << " (" << always.tracker.getNbFeaturesEdge() << ")");
  CHECK(always.tracker.getKltNbPoints() > klt_with_depth + 20);
  CHECK(always.tracker.getNbFeaturesEdge() > edge_with_depth + 20);

  // The first frame without depth starts them at its converged pose; from the next on they
  // work, and the pose holds without depth about as well as with them working all along.
  // The two reach these frames from different histories: with depth, the default tracker
  // weighs its texture keyframe against region and depth alone (0.07 mm off, measured), the
  // other against flow and edge as well (0.97 mm). Without depth the line of sight rests on
  // contours and corners, and such histories part by up to 0.6 mm (2.1 against 1.6 mm).
  constexpr double kHistoriesPartMm = 1.0;
  CHECK(track_frame(rig, 3, false) < kBoundWithoutMm);
  track_frame(always, 3, false);
  CHECK(rig.tracker.getKltNbPoints() < klt_with_depth + 20);
  for (int i = 4; i <= 5; ++i) {
    const double error_mm = track_frame(rig, i, false), always_mm = track_frame(always, i, false);
    INFO("frame " << i << ": " << error_mm << " mm (working all along: " << always_mm << " mm, frozen: " << frozen_mm(i)
                  << " mm), KLT points " << rig.tracker.getKltNbPoints() << ", edge features "
                  << rig.tracker.getNbFeaturesEdge());
    CHECK(error_mm < kBoundWithoutMm);
    CHECK(frozen_mm(i) > 2.0 * kBoundWithoutMm);
    CHECK(error_mm < always_mm + kHistoriesPartMm);
    CHECK(rig.tracker.getKltNbPoints() > klt_with_depth + 20);
    CHECK(rig.tracker.getNbFeaturesEdge() > edge_with_depth + 20);
  }
}
