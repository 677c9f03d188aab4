// SPDX-License-Identifier: GPL-2.0-or-later
// Loss detection with the default configuration on a rendered sequence with injected
// losses: blanked frames (no image, no depth), a board in front of the camera covering 65 %
// of the image, and pose jumps (the object is somewhere else from one frame to the next).
// Each injected frame must be reported lost and no other frame may be: recall and precision
// are printed and must both be 1. As a user re-detecting the object would, the tracker is
// restarted at the true pose on the first clean frame after a reported loss.
#include <catch2/catch.hpp>

#include <cstdio>
#include <set>

#include "icgp/io/mesh_loader.h"
#include "icgp/tracker/tracker_builder.h"
#include "icgp/tracker/tracker_config.h"
#include "test_scene.h"
#include "test_temp_dir.h"

namespace icgp {
namespace {

enum class Injection { kNone, kBlank, kBoard, kJump };

/// The object turning and drifting slowly 45 cm in front of the camera; from `jump` frames on
/// it is 9 cm further sideways and turned 40 degrees more (one jump per entry).
Pose object_pose(int frame, const std::set<int>& jumps) {
  const double t = frame / 30.0;
  Eigen::Vector3d rotation(0.5 + 0.3 * t, -0.6 + 0.2 * t, 0.3);
  Eigen::Vector3d translation(0.01 + 0.01 * t, -0.015, 0.45 + 0.02 * t);
  for (int jump : jumps)
    if (frame >= jump) {
      rotation.y() += deg_to_rad(40.0);
      translation.x() += (jump % 2 == 0 ? 0.09 : -0.09);
    }
  return Pose::from_rotation_vector(rotation, translation);
}

/// A flat grey board 25 cm from the camera over the central 65 % of both images.
void cover_with_board(Frame& frame) {
  const double side = std::sqrt(0.65);
  for (ColorImage& color : frame.colors) {
    const cv::Size size = color.image.size();
    const cv::Rect board(int(size.width * (1 - side) / 2), int(size.height * (1 - side) / 2), int(size.width * side),
                         int(size.height * side));
    color.image(board).setTo(cv::Scalar(128, 128, 128));
  }
  for (DepthImage& depth : frame.depths) {
    const cv::Size size = depth.depth.size();
    const cv::Rect board(int(size.width * (1 - side) / 2), int(size.height * (1 - side) / 2), int(size.width * side),
                         int(size.height * side));
    depth.depth(board).setTo(0.25f);
  }
}

void blank(Frame& frame) {
  for (ColorImage& color : frame.colors) color.image.setTo(cv::Scalar::all(0));
  for (DepthImage& depth : frame.depths) depth.depth.setTo(0.f);
}

}  // namespace

TEST_CASE("loss detection: blanked frames, a board over 65 % of the image and pose jumps are lost, nothing else") {
  const test::TempDir cache("icgp-loss-cache");
  TrackerConfig config = load_tracker_config(ICGP_TEST_DATA_DIR "/../configs/coarse_models.yaml");
  config.cache_dir = cache.path().string();
  const Mesh mesh = load_mesh(ICGP_MODELS_DIR "/textured_box/textured_box.obj");
  const Intrinsics color_k{650.0, 648.0, 321.3, 238.9, 640, 480};
  const Intrinsics depth_k{580.0, 580.0, 318.2, 243.1, 640, 480};
  const Pose depth_T_color{Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.05, 0.002, 0.001)};
  test::SceneRenderer scene(mesh, color_k, depth_k, depth_T_color);

  const int n_frames = 60;
  const std::set<int> jumps{24, 48};
  std::vector<Injection> injection(n_frames, Injection::kNone);
  for (int f : {8, 9, 10, 40}) injection[f] = Injection::kBlank;
  for (int f : {16, 17, 18, 33}) injection[f] = Injection::kBoard;
  for (int f : jumps) injection[f] = Injection::kJump;

  std::unique_ptr<Tracker> tracker = build_tracker(config, mesh, "object");
  const auto restart = [&](const Frame& frame, const Pose& truth) {
    tracker->body("object").reference_T_body = truth;
    tracker->start(frame);
  };

  int true_losses = 0, missed_losses = 0, false_alarms = 0, clean_frames = 0;
  bool lost = false;
  for (int i = 0; i < n_frames; ++i) {
    const Pose truth = object_pose(i, jumps);
    Frame frame = scene.render(truth);
    if (injection[i] == Injection::kBlank) blank(frame);
    if (injection[i] == Injection::kBoard) cover_with_board(frame);
    if (i == 0 || (lost && injection[i] == Injection::kNone)) restart(frame, truth);
    const BodyResult result = tracker->track(frame).front();
    lost = !result.tracked;
    const bool injected = injection[i] != Injection::kNone;
    INFO("frame " << i << " injected " << int(injection[i]) << " quality " << result.quality);
    CHECK(lost == injected);
    if (injected) (lost ? true_losses : missed_losses)++;
    if (!injected) {
      ++clean_frames;
      if (lost) ++false_alarms;
    }
  }
  const double recall = double(true_losses) / (true_losses + missed_losses);
  const double precision = true_losses + false_alarms == 0 ? 1.0 : double(true_losses) / (true_losses + false_alarms);
  std::printf("loss detection: %d injected losses (blank, board, jump), %d clean frames: recall %.2f, precision %.2f, "
              "%d missed, %d false alarms\n",
              true_losses + missed_losses, clean_frames, recall, precision, missed_losses, false_alarms);
  CHECK(recall == 1.0);
  CHECK(precision == 1.0);
}

}  // namespace icgp
