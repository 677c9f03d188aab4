// SPDX-License-Identifier: GPL-2.0-or-later
// A video of a tracking run: each colour image with the model's outline where the tracker
// puts it and where the ground truth does.
#pragma once

#include <opencv2/videoio.hpp>
#include <string>

#include "icgp/base/frame.h"
#include "icgp/render/renderer.h"

namespace icgp::app {

class OverlayVideo {
 public:
  /// Opens an MJPEG .avi at `path` (its folder is created). Creates a headless renderer,
  /// so EGL must be available. Throws std::runtime_error when the file cannot be opened.
  OverlayVideo(const std::string& path, const Mesh& mesh, double frames_per_second);

  /// Appends `color` with the silhouette outline of the body at `estimate` (red) and, when
  /// given, at `truth` (green), and `caption` in the top-left corner. Poses are
  /// reference_T_body. Every image must have the size of the first.
  void write(const ColorImage& color, const Pose& estimate, const Pose* truth, const std::string& caption);

 private:
  void draw_outline(cv::Mat& canvas, const ColorImage& color, const Pose& reference_T_body, const cv::Scalar& bgr);

  std::string path_;
  double frames_per_second_;
  Renderer renderer_;
  Renderer::BodyHandle body_;
  cv::VideoWriter writer_;
};

}  // namespace icgp::app
