// SPDX-License-Identifier: GPL-2.0-or-later
// An outside project on the installed icgp package, as a ViSP user's program:
//  1. renders a cube of known size at a ViSP pose and checks the depth at the image centre
//     against the analytic distance to its front face;
//  2. tracks that cube with vpMbIcgTracker held as a vpMbTracker*: a mesh file written here,
//     RGB-D frames rendered at a known pose with the depth as the uint16 image of an RGB-D
//     sensor, and a start 5 mm away from the truth that must converge back to it;
//  3. runs the installed default servo scenario (icgp::servo) with the ground truth in the
//     loop and checks it converges to the desired pose.
#include <icgp/render/renderer.h>
#include <icgp/servo/scenario.h>
#include <icgp/servo/servo_run.h>
#include <icgp/visp/conversions.h>
#include <icgp/visp/vpMbIcgTracker.h>
#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace {

/// A cube of side 2 * half centred on its origin, outward-facing triangles.
icgp::Mesh make_cube(float half) {
  icgp::MeshPart part;
  for (int i = 0; i < 8; ++i)
    part.vertices.emplace_back((i & 1) ? half : -half, (i & 2) ? half : -half, (i & 4) ? half : -half);
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    part.triangles.emplace_back(q[0], q[1], q[2]);
    part.triangles.emplace_back(q[0], q[2], q[3]);
  }
  icgp::Mesh mesh;
  mesh.parts.push_back(part);
  return mesh;
}

void write_obj(const icgp::Mesh& mesh, const std::filesystem::path& path) {
  std::ofstream out(path);
  for (const Eigen::Vector3f& v : mesh.parts.front().vertices)
    out << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
  for (const Eigen::Vector3i& t : mesh.parts.front().triangles)
    out << "f " << t.x() + 1 << " " << t.y() + 1 << " " << t.z() + 1 << "\n";
}

bool check_rendered_depth(const icgp::Mesh& cube) {
  const vpCameraParameters cam(600, 600, 319.5, 239.5);
  const vpHomogeneousMatrix cMo(0, 0, 0.5, 0, 0, 0);
  icgp::Renderer renderer;
  const auto body = renderer.add_body(cube, 1);
  renderer.set_body_pose(body, icgp::to_pose(cMo));
  const cv::Mat depth = renderer.render(icgp::to_intrinsics(cam, 640, 480), icgp::Pose(), icgp::kRenderDepth).depth;
  const float centre = depth.at<float>(240, 320);
  std::cout << "depth at the image centre: " << centre << " m (expected 0.45)\n";
  return std::abs(centre - 0.45f) < 1e-5f;
}

bool check_tracking(const icgp::Mesh& cube, const std::filesystem::path& work_dir) {
  const vpCameraParameters cam(600, 600, 319.5, 239.5);
  // Turned so that three faces are in view: depth alone then fixes all six degrees of freedom.
  const vpHomogeneousMatrix cMo_true(0.01, -0.02, 0.5, 0.4, -0.5, 0.2);
  const double depth_scale = 1e-4;  // metres per raw unit: 0.1 mm steps, as a RealSense can be set to

  icgp::Renderer renderer;
  renderer.set_body_pose(renderer.add_body(cube, 1), icgp::to_pose(cMo_true));
  const icgp::RenderOutput rendered =
      renderer.render(icgp::to_intrinsics(cam, 640, 480), icgp::Pose(), icgp::kRenderDepth | icgp::kRenderColor);
  vpImage<vpRGBa> I_color;
  icgp::to_vp_image(rendered.color, I_color);
  vpImage<uint16_t> I_depth_raw(480, 640, 0);
  for (unsigned int i = 0; i < I_depth_raw.getHeight(); ++i)
    for (unsigned int j = 0; j < I_depth_raw.getWidth(); ++j)
      I_depth_raw[i][j] = static_cast<uint16_t>(std::lround(rendered.depth.at<float>(i, j) / depth_scale));

  const std::filesystem::path model = work_dir / "cube.obj";
  write_obj(cube, model);

  vpMbIcgTracker icg(1, vpMbIcgTracker::DEPTH_DENSE_TRACKER);  // one camera, "Camera", depth only
  // Coarse viewpoint models, generated in about a second into a folder of this build.
  icgp::TrackerConfig config = icg.getTrackerConfig();
  config.region_model.n_divides = config.depth_model.n_divides = 3;
  config.region_model.image_size = config.depth_model.image_size = 800;
  config.cache_dir = (work_dir / "model-cache").string();
  icg.setTrackerConfig(config);
  icg.setModalities({"depth"});
  icg.setCameraParameters(cam);

  // From here on, code written for any ViSP model-based tracker.
  vpMbTracker* tracker = &icg;
  tracker->loadModel(model.string());
  const vpHomogeneousMatrix cMo_start = vpHomogeneousMatrix(0.003, 0, -0.004, 0, 0, 0) * cMo_true;  // 5 mm off
  tracker->initFromPose(I_color, cMo_start);
  vpHomogeneousMatrix cMo;
  tracker->getPose(cMo);
  std::cout << "vpMbIcgTracker starts "
            << (cMo.getTranslationVector() - cMo_true.getTranslationVector()).frobeniusNorm() * 1e3
            << " mm from the truth\n";
  double error_mm = 0.0, error_deg = 0.0;
  for (int i = 0; i < 5; ++i) {
    icg.track(I_color, I_depth_raw, depth_scale);
    tracker->getPose(cMo);
    error_mm = (cMo.getTranslationVector() - cMo_true.getTranslationVector()).frobeniusNorm() * 1e3;
    error_deg = vpMath::deg(vpThetaUVector(cMo_true.getRotationMatrix().t() * cMo.getRotationMatrix()).getTheta());
    std::cout << "vpMbIcgTracker, depth only, frame " << i + 1 << ": " << error_mm << " mm, " << error_deg
              << " deg from the truth\n";
  }
  tracker->testTracking();  // throws vpTrackingException when the fit is poor
  return error_mm < 1.0 && error_deg < 0.5;
}

bool check_servo() {
  icgp::servo::Scenario scenario =
      icgp::servo::load_scenario(ICGP_CONSUMER_SCENARIOS_DIR "/default.yaml", ICGP_CONSUMER_MODELS_DIR);
  scenario.tracker.kind = icgp::servo::TrackerKind::kOracle;
  icgp::servo::ServoRunOptions options;
  options.progress = false;
  const icgp::servo::ServoResult result = icgp::servo::run_servo(scenario, options);
  std::cout << "servo, default scenario with the oracle: " << (result.converged ? "converged" : "did not converge")
            << " in " << result.steps.size() << " steps, " << result.final_t * 1e3 << " mm from the desired pose\n";
  return result.converged && result.final_t < scenario.stop.converged_translation;
}

}  // namespace

int main() {
  const std::filesystem::path work_dir = ICGP_CONSUMER_WORK_DIR;  // for the mesh and the model cache
  const icgp::Mesh cube = make_cube(0.05f);  // a 10 cm cube
  const bool depth_ok = check_rendered_depth(cube);
  const bool tracking_ok = check_tracking(cube, work_dir);
  const bool servo_ok = check_servo();
  return depth_ok && tracking_ok && servo_ok ? 0 : 1;
}
