// SPDX-License-Identifier: GPL-2.0-or-later
// The simulated RGB-D sensor against independent truth: the exact render matches the
// analytic geometry, and each imperfection has the statistics the scenario asks for.
#include <catch2/catch.hpp>
#include <cmath>
#include <opencv2/core.hpp>
#include <visp3/core/vpImageConvert.h>

#include "icgp/servo/rgbd_simulator.h"
#include "icgp/servo/simulated_robot.h"
#include "icgp/visp/conversions.h"

using namespace icgp::servo;

namespace {

/// The textured box (0.08 x 0.16 x 0.06 m) straight ahead of a free-flying camera: its
/// +z face (3 cm in front of its origin) faces the camera at `distance` metres.
Scenario facing_box(double distance) {
  Scenario s;
  s.object.model = ICGP_MODELS_DIR "/textured_box/textured_box.obj";
  s.camera.color = s.camera.depth = icgp::Intrinsics::centred(320, 240, 300.0);
  s.initial_cMo = icgp::Pose::from_rotation_vector(Eigen::Vector3d(M_PI, 0, 0), Eigen::Vector3d(0, 0, distance));
  s.desired_cMo = s.initial_cMo;
  return s;
}

/// Depth in metres of a capture.
cv::Mat depth_of(const RgbdCapture& c) {
  cv::Mat raw(c.depth_raw.getHeight(), c.depth_raw.getWidth(), CV_16UC1, const_cast<uint16_t*>(c.depth_raw.bitmap));
  cv::Mat metres;
  raw.convertTo(metres, CV_32F, c.depth_scale);
  return metres;
}

struct Rig {
  Scenario scenario;
  std::unique_ptr<SimulatedRobot> robot;
  std::unique_ptr<RgbdSimulator> simulator;
  explicit Rig(const Scenario& s, unsigned seed = 1) : scenario(s), robot(make_robot(s)) {
    simulator = std::make_unique<RgbdSimulator>(s, robot->world_T_camera(), initial_world_T_object(s, *robot), seed);
  }
  RgbdCapture& capture(double time = 0.0) {
    const vpHomogeneousMatrix wMc = robot->world_T_camera();
    return simulator->capture(time, wMc, wMc);
  }
};

}  // namespace

TEST_CASE("rgbd simulator: exact depth of a facing box and the true pose") {
  Rig rig(facing_box(0.4));
  const RgbdCapture& c = rig.capture();
  const cv::Mat depth = depth_of(c);
  // The box's front face is 3 cm in front of its origin; the background plane 0.3 m behind.
  CHECK(depth.at<float>(120, 160) == Approx(0.37).margin(1e-4));
  CHECK(depth.at<float>(5, 5) == Approx(0.7).margin(1e-3));
  const icgp::Pose truth = icgp::to_pose(c.cMo_true);
  CHECK(truth.matrix().isApprox(rig.scenario.initial_cMo.matrix(), 1e-9));
  CHECK_FALSE(c.dropped);
}

TEST_CASE("rgbd simulator: depth noise grows as Z^2, dropout removes the asked fraction") {
  Scenario exact = facing_box(0.4);
  Scenario noisy = exact;
  noisy.camera.noise.depth_sigma_at_1m = 0.01;
  noisy.camera.noise.depth_dropout = 0.2;
  Rig a(exact), b(noisy);
  const cv::Mat z = depth_of(a.capture()).clone();
  const cv::Mat z_noisy = depth_of(b.capture());
  // Statistics per region at the same depth: the box face (0.37 m) and the plane (0.7 m).
  for (const cv::Rect& region : {cv::Rect(150, 110, 20, 20), cv::Rect(0, 0, 60, 40)}) {
    double sum = 0.0, sum2 = 0.0;
    int present = 0, total = 0;
    const double Z = z.at<float>(region.y, region.x);
    for (int r = region.y; r < region.y + region.height; ++r)
      for (int c = region.x; c < region.x + region.width; ++c) {
        ++total;
        if (z_noisy.at<float>(r, c) == 0.f) continue;
        ++present;
        const double e = z_noisy.at<float>(r, c) - z.at<float>(r, c);
        sum += e;
        sum2 += e * e;
      }
    const double sigma = std::sqrt(sum2 / present - (sum / present) * (sum / present));
    INFO("Z " << Z << ": sigma " << sigma << ", present " << present << " of " << total);
    CHECK(sigma == Approx(0.01 * Z * Z).epsilon(0.15));
    CHECK(static_cast<double>(total - present) / total == Approx(0.2).margin(0.05));
  }
}

TEST_CASE("rgbd simulator: depth is missing at grazing angles and along depth edges") {
  Scenario s = facing_box(0.4);
  // Turn the box 60 degrees about its vertical axis: its front face is then seen 60
  // degrees off its normal, and one side face at about 30 degrees.
  s.initial_cMo = s.initial_cMo * icgp::Pose::from_rotation_vector(Eigen::Vector3d(0, 60 * M_PI / 180, 0),
                                                                      Eigen::Vector3d::Zero());
  Scenario grazing = s;
  grazing.camera.noise.grazing_angle_deg = 45.0;
  Scenario edges = s;
  edges.camera.noise.depth_edge_holes_px = 3;
  Rig exact(s), a(grazing), b(edges);
  const cv::Mat z = depth_of(exact.capture()).clone();
  const cv::Mat z_grazing = depth_of(a.capture()).clone();
  const cv::Mat z_edges = depth_of(b.capture());
  const cv::Mat object = (z > 0.f) & (z < 0.6f);
  const int object_pixels = cv::countNonZero(object);
  const int kept = cv::countNonZero(object & (z_grazing > 0.f));
  INFO("object pixels " << object_pixels << ", kept at 45 deg " << kept);
  // Part of the box (the face seen at 60 degrees) is removed, not all of it; the plane
  // behind, seen head-on, stays whole.
  CHECK(kept < 0.9 * object_pixels);
  CHECK(kept > 0.1 * object_pixels);
  CHECK(cv::countNonZero(z_grazing(cv::Rect(0, 0, 40, 40)) > 0.f) == 1600);
  // Along the box's outline (a depth step of 0.3 m) a band is removed; far from it nothing.
  const int removed = cv::countNonZero((z > 0.f) & (z_edges == 0.f));
  CHECK(removed > 0);
  CHECK(cv::countNonZero(z_edges(cv::Rect(0, 0, 40, 40)) > 0.f) == 1600);
}

TEST_CASE("rgbd simulator: dropped frames repeat the last images, at the asked rate") {
  Scenario s = facing_box(0.4);
  s.camera.noise.frame_drop = 0.3;
  s.camera.noise.color_sigma = 5.0;  // every new frame differs from the last
  Rig rig(s);
  vpImage<vpRGBa> previous = rig.capture(0.0).color;
  int dropped = 0;
  constexpr int kFrames = 200;
  for (int i = 1; i <= kFrames; ++i) {
    RgbdCapture& c = rig.capture(i / 30.0);
    const bool same = c.color == previous;
    CHECK(same == c.dropped);
    dropped += c.dropped;
    previous = c.color;
  }
  CHECK(static_cast<double>(dropped) / kFrames == Approx(0.3).margin(0.08));
}

TEST_CASE("rgbd simulator: a moving target follows its velocity during its motion only") {
  Scenario s = facing_box(0.4);
  s.object.linear_velocity = Eigen::Vector3d(0.05, 0, 0);
  s.object.motion_start = 1.0;
  s.object.motion_duration = 2.0;
  Rig rig(s);
  const vpHomogeneousMatrix start = rig.simulator->world_T_object(0.0);
  const auto shift = [&](double t) { return rig.simulator->world_T_object(t)[0][3] - start[0][3]; };
  CHECK(shift(0.9) == Approx(0.0).margin(1e-12));
  CHECK(shift(2.0) == Approx(0.05));
  CHECK(shift(3.0) == Approx(0.10));
  CHECK(shift(5.0) == Approx(0.10));
}

TEST_CASE("rgbd simulator: an object taken away is out of every view, then back where it was put") {
  Scenario s = facing_box(0.4);
  s.object.removed_at = 1.0;
  s.object.removed_for = 1.5;
  s.object.put_back = icgp::Pose::from_rotation_vector(Eigen::Vector3d(0, 0.2, 0), Eigen::Vector3d(0.03, 0, 0.02));
  Rig rig(s);
  const vpHomogeneousMatrix start = rig.simulator->world_T_object(0.0);
  CHECK(rig.simulator->world_T_object(0.99) == start);
  const RgbdCapture& away = rig.capture(1.5);
  CHECK(away.cMo_true[2][3] > 100.0);
  // Nothing of it in the depth image: a kilometre is beyond every depth range.
  for (unsigned i = 0; i < away.depth_raw.getHeight(); i += 8)
    for (unsigned j = 0; j < away.depth_raw.getWidth(); j += 8) CHECK(away.depth_raw[i][j] * away.depth_scale < 100.0);
  const vpHomogeneousMatrix back = rig.simulator->world_T_object(2.6);
  const vpHomogeneousMatrix expected = start * icgp::to_homogeneous_matrix(s.object.put_back);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) CHECK(back[r][c] == Approx(expected[r][c]).margin(1e-12));
}

TEST_CASE("rgbd simulator: the scenario's lighting shades the object") {
  Scenario front = facing_box(0.4);
  Scenario ambient_only = front;
  ambient_only.lighting.direction_in_camera = Eigen::Vector3d(0, 0, -1);  // light from behind the object
  Rig a(front), b(ambient_only);
  cv::Mat lit, dark;
  vpImageConvert::convert(a.capture().grey, lit);
  vpImageConvert::convert(b.capture().grey, dark);
  const cv::Rect face(150, 100, 20, 40);
  // Headlight: ambient + diffuse = 1 on the facing front; from behind: ambient 0.35 only.
  CHECK(cv::mean(dark(face))[0] == Approx(0.35 * cv::mean(lit(face))[0]).epsilon(0.05));
}

TEST_CASE("rgbd simulator: a flickering light and a moving one shade the facing face as their closed forms say") {
  // The facing front under the headlight reads (ambient + diffuse·s·cos θ) · albedo: check
  // the ratio of two captures against the same ratio of the closed form.
  const cv::Rect face(150, 100, 20, 40);
  const auto brightness = [&](const Scenario& s, double time) {
    Rig rig(s);
    cv::Mat grey;
    vpImageConvert::convert(rig.capture(time).grey, grey);
    return cv::mean(grey(face))[0];
  };
  // Ambient 0.2 and diffuse 0.5, so that no pixel saturates even at the flicker's peak.
  Scenario steady = facing_box(0.4);
  steady.lighting.ambient = 0.2;
  steady.lighting.diffuse = 0.5;
  Scenario flicker = steady;
  flicker.lighting.flicker_amplitude = 0.3;
  flicker.lighting.flicker_hz = 100.0;
  // sin(2π 100 t) is +1 at t = 2.5 ms and -1 at t = 7.5 ms.
  const double bright = brightness(flicker, 0.0025), dim = brightness(flicker, 0.0075);
  CHECK(bright / dim == Approx((0.2 + 0.5 * 1.3) / (0.2 + 0.5 * 0.7)).epsilon(0.03));
  CHECK(brightness(flicker, 0.0) == Approx(brightness(steady, 0.0)).epsilon(0.01));

  Scenario moving = steady;
  moving.lighting.motion_axis = Eigen::Vector3d(0, 1, 0);
  moving.lighting.motion_rate = 30.0 * kDegree;  // 60° away after 2 s
  CHECK(brightness(moving, 2.0) / brightness(moving, 0.0) == Approx((0.2 + 0.5 * 0.5) / (0.2 + 0.5)).epsilon(0.03));
}
