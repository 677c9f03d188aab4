// SPDX-License-Identifier: GPL-2.0-or-later
// Renders RGB-D frames of an object in front of a cluttered plane with exact ground truth,
// for tests that need a camera image with a known pose.
#pragma once

#include <opencv2/core.hpp>

#include "icgp/base/frame.h"
#include "icgp/io/mesh_loader.h"
#include "icgp/render/renderer.h"

namespace icgp::test {

/// A flat square at z = 0 (normal +z) of side `size` metres, textured with random
/// coloured blocks (seeded), to stand behind objects as clutter.
inline Mesh make_clutter_plane(float size, unsigned seed = 3) {
  cv::Mat texture(256, 256, CV_8UC3);
  cv::RNG rng(seed);
  for (int by = 0; by < 256; by += 16)
    for (int bx = 0; bx < 256; bx += 16)
      texture(cv::Rect(bx, by, 16, 16)).setTo(cv::Scalar(rng.uniform(0, 256), rng.uniform(0, 256), rng.uniform(0, 256)));
  MeshPart part;
  const float h = size / 2;
  part.vertices = {{-h, -h, 0.f}, {h, -h, 0.f}, {h, h, 0.f}, {-h, h, 0.f}};
  part.texcoords = {{0.f, 0.f}, {4.f, 0.f}, {4.f, 4.f}, {0.f, 4.f}};
  part.triangles = {{0, 1, 2}, {0, 2, 3}};
  part.material.texture_bgr = texture;
  Mesh mesh;
  mesh.source = "clutter plane";
  mesh.parts.push_back(part);
  return mesh;
}

/// A colour camera "Camera1" and a depth camera "Camera2" (depth_T_color apart) looking at
/// `object` at camera_T_object, with a clutter plane `background_distance` metres behind
/// the object's origin (facing the camera).
class SceneRenderer {
 public:
  SceneRenderer(const Mesh& object, Intrinsics color, Intrinsics depth, Pose depth_T_color,
                double background_distance = 0.3)
      : color_(color), depth_(depth), depth_T_color_(depth_T_color), background_distance_(background_distance) {
    object_ = renderer_.add_body(object, 1);
    background_ = renderer_.add_body(make_clutter_plane(3.f), 2);
  }

  Frame render(const Pose& camera_T_object, const std::string& object_name = "object") {
    renderer_.set_body_pose(object_, camera_T_object);
    // The plane faces the camera along the optical axis, behind the object.
    const Eigen::Vector3d behind = camera_T_object.translation() + Eigen::Vector3d(0, 0, background_distance_);
    renderer_.set_body_pose(background_, Pose(Eigen::Matrix3d::Identity(), behind));
    Frame frame;
    frame.colors.push_back({"Camera1", color_, Pose(), renderer_.render(color_, Pose(), kRenderColor).color});
    frame.depths.push_back(
        {"Camera2", depth_, depth_T_color_, renderer_.render(depth_, depth_T_color_, kRenderDepth).depth});
    frame.ground_truth[object_name] = camera_T_object;
    return frame;
  }

  Renderer& renderer() { return renderer_; }

 private:
  Renderer renderer_;
  Renderer::BodyHandle object_, background_;
  Intrinsics color_, depth_;
  Pose depth_T_color_;
  double background_distance_;
};

/// models/textured_box seen by a colour and a depth camera in front of clutter, moving
/// smoothly from `start`: the frames of the cues that follow points and edges over time.
struct MovingTexturedBox {
  Mesh mesh = load_mesh(ICGP_MODELS_DIR "/textured_box/textured_box.obj");
  Intrinsics color_k{650.0, 648.0, 321.3, 238.9, 640, 480};
  Intrinsics depth_k{580.0, 580.0, 318.2, 243.1, 640, 480};
  Pose depth_T_color{Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.05, 0.002, 0.001)};
  Pose start = Pose::from_rotation_vector(Eigen::Vector3d(0.5, -0.6, 0.3), Eigen::Vector3d(0.01, -0.015, 0.45));
  SceneRenderer renderer{mesh, color_k, depth_k, depth_T_color};

  /// The pose of frame i of a smooth motion: 1 mm and 0.6° more per frame.
  Pose at(int i) const {
    const Eigen::Vector3d axis = Eigen::Vector3d(0.2, 0.9, -0.4).normalized();
    const Eigen::Vector3d direction = Eigen::Vector3d(0.7, -0.3, 0.65).normalized();
    return Pose(exp_so3<double>(axis * 0.6 * i * M_PI / 180.0) * start.rotation(),
                start.translation() + direction * 1e-3 * i);
  }
};

}  // namespace icgp::test
