// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker's extension for several bodies: a second body tracked beside the object
// on rendered frames with exact ground truth, and the errors of the extension's calls.
#include <catch2/catch.hpp>
#include <filesystem>

#include "icgp/io/mesh_loader.h"
#include "icgp/render/renderer.h"
#include "icgp/visp/conversions.h"
#include "icgp/visp/rgbd_tracking_loop.h"
#include "test_scene.h"
#include "vpmbicgtracker_test_setup.h"

using namespace icgp;
using Catch::Contains;

namespace {

const std::string kBoxFile = std::string(ICGP_MODELS_DIR) + "/textured_box/textured_box.obj";

Pose pose(double rx, double ry, double rz, double tx, double ty, double tz) {
  return Pose::from_rotation_vector(Eigen::Vector3d(rx, ry, rz), Eigen::Vector3d(tx, ty, tz));
}

/// Two textured boxes in front of a clutter plane, seen by one RGB-D camera at the origin.
struct TwoBoxScene {
  Intrinsics k = Intrinsics::centred(320, 240, 300.0);
  Pose object_truth = pose(0.4, 0.5, 0.1, -0.07, 0.0, 0.45);
  Pose second_truth;
  vpImage<vpRGBa> color;
  vpImage<uint16_t> depth;  ///< 0.1 mm units

  explicit TwoBoxScene(const Pose& second = pose(-0.3, 0.6, 0.2, 0.08, 0.02, 0.5)) : second_truth(second) {
    Renderer renderer;
    const Mesh box = load_mesh(kBoxFile);
    renderer.set_body_pose(renderer.add_body(box, 1), object_truth);
    renderer.set_body_pose(renderer.add_body(box, 2), second_truth);
    renderer.set_body_pose(renderer.add_body(test::make_clutter_plane(2.f), 3),
                           Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 0.8)));
    const RenderOutput out = renderer.render(k, Pose(), kRenderColor | kRenderDepth);
    to_vp_image(out.color, color);
    depth.resize(k.height, k.width, 0);
    for (int r = 0; r < k.height; ++r)
      for (int c = 0; c < k.width; ++c) depth[r][c] = static_cast<uint16_t>(out.depth.at<float>(r, c) * 1e4f + 0.5f);
  }
};

void set_up(vpMbIcgTracker& tracker, const TwoBoxScene& scene) {
  test::configure_for_tests(tracker);
  tracker.loadModel(kBoxFile, kBoxFile);
  tracker.setCameraParameters(to_camera_parameters(scene.k), to_camera_parameters(scene.k));
  tracker.setCameraTransformationMatrix(kDepthCamera, vpHomogeneousMatrix());
  // Region and depth pull a pose offset from the truth back to it; the texture cue would
  // anchor its first keyframe at the offset start, as it should.
  tracker.setModalities({"region", "depth"});
}

double distance_mm(const vpHomogeneousMatrix& a, const Pose& b) {
  return (to_pose(a).translation() - b.translation()).norm() * 1000.0;
}

}  // namespace

TEST_CASE("vpMbIcgTracker: a second body is tracked beside the object, each from its own start") {
  const TwoBoxScene scene;
  vpMbIcgTracker tracker(kRgbdTrackerTypes);
  set_up(tracker, scene);
  tracker.addBody("second", kBoxFile);
  CHECK(tracker.getBodyNames() == std::vector<std::string>{"second"});
  const Eigen::Vector3d offset(0.004, -0.003, 0.004);
  tracker.setBodyPose("second",
                      to_homogeneous_matrix(Pose(scene.second_truth.rotation(), scene.second_truth.translation() - offset)));
  vpImage<unsigned char> grey;
  vpImageConvert::convert(scene.color, grey);
  tracker.initFromPose(grey, to_homogeneous_matrix(Pose(scene.object_truth.rotation(),
                                                        scene.object_truth.translation() + offset)));
  for (int frame = 0; frame < 5; ++frame) tracker.track(scene.color, scene.depth, 1e-4);

  CHECK(distance_mm(tracker.getPose(), scene.object_truth) < 0.1);
  CHECK(distance_mm(tracker.getBodyPose("second"), scene.second_truth) < 0.1);
  CHECK(tracker.getBodyPose(vpMbIcgTracker::getReferenceBodyName()) == tracker.getPose());
  CHECK(tracker.isBodyTracked("second"));
  CHECK(tracker.getBodyTrackingQuality("second") > 0.5);
  CHECK(tracker.getJointValues("second").empty());
}

TEST_CASE("vpMbIcgTracker: a second body out of view is reported lost where it is, never put on the object") {
  // The second box 80 cm to the side, where the image spans ±0.27 m: nothing of it in view,
  // and the object in view is the same box.
  const Pose out_of_view = pose(-0.3, 0.6, 0.2, 0.8, 0.02, 0.5);
  const TwoBoxScene scene(out_of_view);
  vpMbIcgTracker tracker(kRgbdTrackerTypes);
  set_up(tracker, scene);
  tracker.addBody("second", kBoxFile);
  tracker.setBodyPose("second", to_homogeneous_matrix(out_of_view));
  vpImage<unsigned char> grey;
  vpImageConvert::convert(scene.color, grey);
  const Eigen::Vector3d offset(0.004, -0.003, 0.004);
  tracker.initFromPose(grey, to_homogeneous_matrix(Pose(scene.object_truth.rotation(),
                                                        scene.object_truth.translation() + offset)));
  // Over more frames than the whole-image search's interval: the lost body is searched for.
  for (int frame = 0; frame < 12; ++frame) {
    INFO("frame " << frame);
    REQUIRE_NOTHROW(tracker.track(scene.color, scene.depth, 1e-4));
    CHECK(!tracker.isBodyTracked("second"));
    // Held where it was set, not put on the box in view.
    CHECK(distance_mm(tracker.getBodyPose("second"), out_of_view) < 1.0);
  }
  CHECK(distance_mm(tracker.getPose(), scene.object_truth) < 0.1);
  CHECK_NOTHROW(tracker.testTracking());
}

TEST_CASE("vpMbIcgTracker: the extension's bad calls throw vpException naming the body and the field") {
  vpMbIcgTracker tracker(kRgbdTrackerTypes);
  tracker.addBody("lid", kBoxFile, Joint::revolute("object", Pose(), Eigen::Vector3d::UnitX(), 0.0, 1.5));
  CHECK_THROWS_AS(tracker.addBody("object", kBoxFile), vpException);
  CHECK_THROWS_WITH(tracker.addBody("object", kBoxFile), Contains("body 'object': name: another body has this name"));
  CHECK_THROWS_WITH(tracker.addBody("lid", kBoxFile), Contains("body 'lid': name"));
  CHECK_THROWS_WITH(tracker.addBody("knob", kBoxFile, Joint::revolute("lod", Pose(), Eigen::Vector3d::UnitX(), 0, 1)),
                    Contains("body 'knob': parent: no body is named 'lod'"));
  CHECK_THROWS_WITH(tracker.addBody("knob", kBoxFile, Joint::revolute("lid", Pose(), Eigen::Vector3d::UnitX(), 1, 0)),
                    Contains("body 'knob': joint direction 0: limits: expected min <= max"));
  CHECK_THROWS_WITH(tracker.setBodyPose("ghost", vpHomogeneousMatrix()),
                    Contains("no body is named 'ghost' (the bodies are object, lid)"));
  CHECK_THROWS_WITH(tracker.setBodyPose("lid", vpHomogeneousMatrix()), Contains("'lid' is a link"));
  CHECK_THROWS_WITH(tracker.setJointValues("lid", {0.1, 0.2}), Contains("its joint has 1 values, got 2"));
  tracker.setJointValues("lid", {2.0});
  CHECK(tracker.getJointValues("lid") == std::vector<double>{1.5});  // clamped into the limits

  SECTION("an occluder mesh that cannot be read is named when the tracker is built") {
    const TwoBoxScene scene;
    vpMbIcgTracker with_hand(kRgbdTrackerTypes);
    set_up(with_hand, scene);
    with_hand.addOccluder("hand", "/no/such/hand.obj");
    vpImage<unsigned char> grey(scene.k.height, scene.k.width, 0);
    CHECK_THROWS_AS(with_hand.initFromPose(grey, to_homogeneous_matrix(scene.object_truth)), vpException);
    CHECK_THROWS_WITH(with_hand.initFromPose(grey, to_homogeneous_matrix(scene.object_truth)),
                      Contains("body 'hand': mesh: ") && Contains("/no/such/hand.obj"));
  }
}
