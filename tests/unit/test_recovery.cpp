// SPDX-License-Identifier: GPL-2.0-or-later
// Recovery after a loss (docs/detection.md, "Recovery") never trusts a pose the images do
// not support: while the tracked box is hidden, a similar box (15 % larger) stands 15 cm
// beside where it was; the tracker must report the box lost all that time, never put it on
// the other box, and trust it again once it is back. A can whose model has no texture,
// spinning about its axis, keeps the turn its cues followed when found again. And
// frames_to_confirm, the motion prior: the farther a found pose is from the last trusted
// one, the more frames confirm it.
#include <catch2/catch.hpp>

#include <cstdio>

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include "icgp/eval/metrics.h"
#include "icgp/eval/single_body_tracker.h"
#include "icgp/io/mesh_loader.h"
#include "icgp/render/renderer.h"
#include "icgp/tracker/tracker_config.h"
#include "test_meshes.h"
#include "test_scene.h"
#include "test_temp_dir.h"

namespace icgp {
namespace {

/// A colour and a depth camera before a clutter plane, with the tracked box and a similar
/// one, either of which may be out of the scene.
class TwoBoxScene {
 public:
  TwoBoxScene(const Mesh& tracked, const Mesh& similar) {
    tracked_ = renderer_.add_body(tracked, 1);
    similar_ = renderer_.add_body(similar, 2);
    renderer_.set_body_pose(renderer_.add_body(test::make_clutter_plane(3.f), 3),
                            Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.0, 0.8)));
  }

  /// `tracked` or `similar` empty: that box is out of the scene.
  Frame render(const std::optional<Pose>& tracked, const std::optional<Pose>& similar) {
    const Pose away(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.0, -10.0));  // behind the cameras
    renderer_.set_body_pose(tracked_, tracked.value_or(away));
    renderer_.set_body_pose(similar_, similar.value_or(away));
    Frame frame;
    frame.colors.push_back({"Camera1", color_k, Pose(), renderer_.render(color_k, Pose(), kRenderColor).color});
    frame.depths.push_back(
        {"Camera2", depth_k, depth_T_color, renderer_.render(depth_k, depth_T_color, kRenderDepth).depth});
    return frame;
  }

  const Intrinsics color_k{650.0, 648.0, 321.3, 238.9, 640, 480};
  const Intrinsics depth_k{580.0, 580.0, 318.2, 243.1, 640, 480};
  const Pose depth_T_color{Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.05, 0.002, 0.001)};

 private:
  Renderer renderer_;
  Renderer::BodyHandle tracked_, similar_;
};

}  // namespace

TEST_CASE("recovery: a similar box in view while the tracked one is hidden is never taken for it") {
  const test::TempDir cache("icgp-recovery-cache");
  TrackerConfig config = load_tracker_config(ICGP_TEST_DATA_DIR "/../configs/coarse_models.yaml");
  config.cache_dir = cache.path().string();
  const Mesh box = test::make_box(0.08f, 0.16f, 0.06f);
  TwoBoxScene scene(box, test::make_box(0.092f, 0.184f, 0.069f));
  // The tracked box drifts and turns slowly 45 cm away; the similar box stands still 15 cm
  // to its left, turned like the tracked box was at the start.
  const auto tracked_at = [](int i) {
    return Pose::from_rotation_vector(Eigen::Vector3d(0.5 + 0.004 * i, -0.6, 0.3),
                                      Eigen::Vector3d(0.05 + 0.001 * i, -0.01, 0.45));
  };
  const Pose similar_at = Pose::from_rotation_vector(Eigen::Vector3d(0.5, -0.6, 0.3), Eigen::Vector3d(-0.1, -0.01, 0.47));
  constexpr int kHiddenFrom = 8, kBackFrom = 28, kFrames = 44;

  SingleBodyTracker tracker(config, box, "object");
  int wrong_trusted = 0, trusted_while_hidden = 0, first_trusted_again = -1;
  double last_error_mm = 1e9;
  for (int i = 0; i < kFrames; ++i) {
    const bool hidden = i >= kHiddenFrom && i < kBackFrom;
    const Frame frame = scene.render(hidden ? std::nullopt : std::optional<Pose>(tracked_at(i)),
                                     i >= kHiddenFrom ? std::optional<Pose>(similar_at) : std::nullopt);
    if (i == 0) tracker.start(frame, tracked_at(0));
    const BodyResult result = tracker.track(frame);
    if (!result.tracked) continue;
    const double t = translation_error_mm(result.reference_T_body, tracked_at(i));
    const double r = rotation_error_deg(result.reference_T_body, tracked_at(i));
    INFO("frame " << i << ": trusted " << t << " mm, " << r << " deg from the tracked box");
    CHECK_FALSE(hidden);
    trusted_while_hidden += hidden;
    if (t > 50.0 || r > 15.0) ++wrong_trusted;
    if (i >= kBackFrom && first_trusted_again < 0) first_trusted_again = i;
    last_error_mm = t;
  }
  std::printf("similar box beside the hidden one: %d frames trusted while hidden, %d trusted poses off the box by "
              "more than 5 cm / 15 deg, trusted again at frame %d (back at %d), last error %.2f mm\n",
              trusted_while_hidden, wrong_trusted, first_trusted_again, kBackFrom, last_error_mm);
  CHECK(wrong_trusted == 0);
  // Back where the search near its last trusted pose finds it (it moved 2 cm meanwhile).
  CHECK(first_trusted_again >= kBackFrom);
  CHECK(first_trusted_again <= kBackFrom + 6);
  CHECK(last_error_mm < 5.0);
}

TEST_CASE("recovery: the farther a found pose is from the last trusted one, the more frames confirm it") {
  CHECK(Recovery::frames_to_confirm(0.0) == 1);
  CHECK(Recovery::frames_to_confirm(1.0) == 1);  // within the local search's window
  CHECK(Recovery::frames_to_confirm(1.5) == 2);
  CHECK(Recovery::frames_to_confirm(3.0) == 3);
  CHECK(Recovery::frames_to_confirm(4.3) == 4);  // the castle put 151 degrees off: 4.3 windows of 35 degrees
  CHECK(Recovery::frames_to_confirm(1e6) == 6);  // never more
  for (double d = 0.5; d < 100.0; d *= 1.3) CHECK(Recovery::frames_to_confirm(d * 1.3) >= Recovery::frames_to_confirm(d));
}

TEST_CASE("recovery: a round body whose model has no texture keeps the turn its cues followed when found again") {
  const test::TempDir cache("icgp-recovery-can-cache");
  TrackerConfig config = load_tracker_config(ICGP_TEST_DATA_DIR "/../configs/coarse_models.yaml");
  config.cache_dir = cache.path().string();
  // The frames show the labelled can; the tracker knows its shape alone (as from a .cao):
  // only its texture cue, following the label, sees it spin about its axis.
  const Mesh labelled = load_mesh(ICGP_MODELS_DIR "/labelled_cylinder/labelled_cylinder.obj");
  Mesh plain = labelled;
  for (MeshPart& part : plain.parts) part.material = Material{};
  const Intrinsics color_k{650.0, 648.0, 321.3, 238.9, 640, 480};
  const Intrinsics depth_k{580.0, 580.0, 318.2, 243.1, 640, 480};
  const Pose depth_T_color{Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.05, 0.002, 0.001)};
  test::SceneRenderer scene(labelled, color_k, depth_k, depth_T_color);
  // Spinning at 1 rad/s about its axis (y) at 30 frames a second, 40 cm away, seen from a
  // little above.
  const auto at = [](int i) {
    const Eigen::Matrix3d tilt = Eigen::AngleAxisd(-0.35, Eigen::Vector3d::UnitX()).toRotationMatrix();
    const Eigen::Matrix3d spin = Eigen::AngleAxisd(i / 30.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
    return Pose(tilt * spin, Eigen::Vector3d(0.01, 0.0, 0.4));
  };
  SingleBodyTracker tracker(config, plain, "object");
  int found_again = 0;
  double max_rotation_deg = 0.0;
  for (int i = 0; i < 60; ++i) {
    Frame frame = scene.render(at(i));
    cv::Mat grey;
    cv::cvtColor(frame.colors.front().image, grey, cv::COLOR_BGR2GRAY);  // the grey image ViSP's programs give
    frame.colors.front().image = grey;
    // A board hides the middle of the view for one frame now and then: the body is lost
    // and searched for again, and its shape cannot say how far it turned.
    if (i % 20 == 10) {
      const cv::Rect board(160, 120, 320, 240);
      frame.colors.front().image(board).setTo(128);
      frame.depths.front().depth(board).setTo(0.2f);
    }
    if (i == 0) tracker.start(frame, at(0));
    bool found = false;
    const BodyResult result = tracker.track(frame, nullptr, &found);
    found_again += found;
    max_rotation_deg = std::max(max_rotation_deg, rotation_error_deg(result.reference_T_body, at(i)));
  }
  std::printf("spinning can, plain model, grey: found again %d times, rotation error at most %.2f deg (it spins "
              "%.0f deg)\n",
              found_again, max_rotation_deg, 59 / 30.0 * 180.0 / kPi);
  CHECK(found_again >= 2);
  // Each board hides 1.9 degrees of its turn, which nothing can see: 3.4 degrees at most
  // when this was written; 17 degrees with the turn the templates happened to find (the
  // search's round turns are 15 degrees apart).
  CHECK(max_rotation_deg < 5.0);
}

}  // namespace icgp
