// SPDX-License-Identifier: GPL-2.0-or-later
// The simulated RGB-D sensor against independent truth: the exact render matches the
// analytic geometry, and each imperfection has the statistics the scenario asks for.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <opencv2/core.hpp>
#include <visp3/core/vpImageConvert.h>

#include "../unit/test_temp_dir.h"
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

namespace {

/// The facing box with a matte label (no highlight: roughness 1, specular 0), so that its
/// front reads albedo x (ambient + Σ strength x cos) in linear light, a closed form.
Scenario matte_facing_box(const icgp::test::TempDir& dir) {
  namespace fs = std::filesystem;
  for (const char* file : {"textured_box.obj", "textured_box.png"})
    fs::copy_file(fs::path(ICGP_MODELS_DIR) / "textured_box" / file, dir.path() / file);
  dir.write("textured_box.mtl", "newmtl label\nKd 1 1 1\nKs 0 0 0\nPr 1\nmap_Kd textured_box.png\n");
  Scenario s = facing_box(0.4);
  s.object.model = (dir.path() / "textured_box.obj").string();
  s.lighting.ambient = 0.2;
  s.lighting.diffuse = 0.5;  // at most 0.2 + 0.5 x 1.3 < 1: nothing saturates
  return s;
}

/// Mean linear light (sRGB decoded) of a capture over `region` and the three channels, as
/// the auto-exposure meters it.
double linear_mean(const RgbdCapture& capture, const cv::Rect& region) {
  const vpImage<vpRGBa>& color = capture.color;
  double sum = 0.0;
  for (int row = region.y; row < region.br().y; ++row)
    for (int col = region.x; col < region.br().x; ++col)
      for (const unsigned char level : {color[row][col].R, color[row][col].G, color[row][col].B}) {
        const double c = level / 255.0;
        sum += c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
      }
  return sum / (3.0 * region.area());
}

/// The same at `time` of a fresh run of `s`.
double linear_mean(const Scenario& s, const cv::Rect& region, double time = 0.0) {
  Rig rig(s);
  return linear_mean(rig.capture(time), region);
}

/// A patch of the box's front, facing the camera.
const cv::Rect kFront(150, 100, 20, 40);

}  // namespace

TEST_CASE("rgbd simulator: the scenario's lights shade the object as their closed forms say") {
  icgp::test::TempDir dir("icgp-matte");
  const Scenario front = matte_facing_box(dir);
  // The lamp from behind the object leaves its front the ambient light alone.
  Scenario from_behind = front;
  from_behind.lighting.direction_in_camera = Eigen::Vector3d(0, 0, -1);
  const double lit = linear_mean(front, kFront), ambient = linear_mean(from_behind, kFront);
  CHECK(ambient / lit == Approx(0.2 / (0.2 + 0.5)).epsilon(0.03));

  SECTION("flicker scales every lamp's strength by 1 + amplitude sin(2π f t)") {
    Scenario flicker = front;
    flicker.lighting.flicker_amplitude = 0.3;
    flicker.lighting.flicker_hz = 100.0;
    // sin(2π 100 t) is +1 at t = 2.5 ms and -1 at t = 7.5 ms.
    const double bright = linear_mean(flicker, kFront, 0.0025), dim = linear_mean(flicker, kFront, 0.0075);
    CHECK(bright / dim == Approx((0.2 + 0.5 * 1.3) / (0.2 + 0.5 * 0.7)).epsilon(0.02));
    CHECK(linear_mean(flicker, kFront, 0.0) == Approx(lit).epsilon(0.01));
  }
  SECTION("a moving light turns the camera's lamp: 60° off the face, half its light") {
    Scenario moving = front;
    moving.lighting.motion_axis = Eigen::Vector3d(0, 1, 0);
    moving.lighting.motion_rate = 30.0 * kDegree;  // 60° away after 2 s
    CHECK(linear_mean(moving, kFront, 2.0) / lit == Approx((0.2 + 0.5 * 0.5) / (0.2 + 0.5)).epsilon(0.02));
  }
  SECTION("a lamp fixed in the scene adds strength x cos, and stays in the scene as the camera turns") {
    // In the start camera's frame the lamp shines 60° off the face's normal.
    Scenario lamp = from_behind;
    lamp.lighting.scene_lamps = {{Eigen::Vector3d(std::sin(60 * kDegree), 0, std::cos(60 * kDegree)), 0.4}};
    CHECK(linear_mean(lamp, kFront) / ambient == Approx((0.2 + 0.4 * 0.5) / 0.2).epsilon(0.03));
  }
}

TEST_CASE("rgbd simulator: vignetting darkens the image by 1 - v (1 - cos⁴θ) in linear light") {
  icgp::test::TempDir dir("icgp-matte");
  const Scenario plain = matte_facing_box(dir);
  Scenario vignetted = plain;
  vignetted.camera.vignetting = 0.6;
  // The same scene with and without: patches on the box at the centre and on the background
  // towards a corner, each a ratio of the two images.
  const cv::Rect centre(155, 115, 10, 10), corner(20, 15, 10, 10);
  const icgp::Intrinsics k = plain.camera.color;
  const double x = (corner.x + 4.5 - k.pu) / k.fu, y = (corner.y + 4.5 - k.pv) / k.fv;
  const double cos2 = 1.0 / (1.0 + x * x + y * y);
  const double expected = 1.0 - 0.6 * (1.0 - cos2 * cos2);
  CHECK(linear_mean(vignetted, centre) / linear_mean(plain, centre) == Approx(1.0).epsilon(0.02));
  CHECK(linear_mean(vignetted, corner) / linear_mean(plain, corner) == Approx(expected).epsilon(0.03));
  CHECK(expected < 0.8);
}

TEST_CASE("rgbd simulator: auto-exposure corrects towards its target with its time constant") {
  // Darkening towards half the scene's light: nothing saturates, so the image's light is the
  // gain times the fixed exposure's, and log gain closes 1 - exp(-Δt / τ) of its gap to the
  // target at each image.
  icgp::test::TempDir dir("icgp-matte");
  const Scenario fixed = matte_facing_box(dir);
  const cv::Rect whole(0, 0, 320, 240);
  const double nominal = linear_mean(fixed, whole);
  Scenario automatic = fixed;
  automatic.camera.auto_exposure = {nominal / 2.0, 0.2};
  Rig rig(automatic);
  CHECK(linear_mean(rig.capture(0.0), whole) == Approx(nominal).epsilon(0.01));
  CHECK(linear_mean(rig.capture(0.2), whole) == Approx(nominal * std::pow(0.5, 1.0 - std::exp(-1.0))).epsilon(0.02));
  CHECK(linear_mean(rig.capture(2.0), whole) == Approx(nominal / 2.0).epsilon(0.02));
}
