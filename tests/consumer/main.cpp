// SPDX-License-Identifier: GPL-2.0-or-later
// Renders a cube of known size at a ViSP pose through the installed icgp package and
// checks the depth at the image centre against the analytic distance to its front face.
#include <icgp/render/renderer.h>
#include <icgp/visp/conversions.h>
#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>

#include <cmath>
#include <iostream>

int main() {
  icgp::MeshPart part;
  const float h = 0.05f;  // a 10 cm cube
  for (int i = 0; i < 8; ++i) part.vertices.emplace_back((i & 1) ? h : -h, (i & 2) ? h : -h, (i & 4) ? h : -h);
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    part.triangles.emplace_back(q[0], q[1], q[2]);
    part.triangles.emplace_back(q[0], q[2], q[3]);
  }
  icgp::Mesh cube;
  cube.parts.push_back(part);

  const vpCameraParameters cam(600, 600, 319.5, 239.5);
  const vpHomogeneousMatrix cMo(0, 0, 0.5, 0, 0, 0);
  icgp::Renderer renderer;
  const auto body = renderer.add_body(cube, 1);
  renderer.set_body_pose(body, icgp::to_pose(cMo));
  const cv::Mat depth = renderer.render(icgp::to_intrinsics(cam, 640, 480), icgp::Pose(), icgp::kRenderDepth).depth;
  const float centre = depth.at<float>(240, 320);
  std::cout << "depth at the image centre: " << centre << " m (expected 0.45)\n";
  return std::abs(centre - 0.45f) < 1e-5f ? 0 : 1;
}
