// SPDX-License-Identifier: GPL-2.0-or-later
#include "overlay_video.h"

#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

namespace icgp::app {

OverlayVideo::OverlayVideo(const std::string& path, const Mesh& mesh, double frames_per_second)
    : path_(path), frames_per_second_(frames_per_second), body_(renderer_.add_body(mesh, 1)) {
  const std::filesystem::path file(path);
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
}

void OverlayVideo::write(const ColorImage& color, const Pose& estimate, const Pose* truth, const std::string& caption) {
  cv::Mat canvas;
  if (color.image.channels() == 1)
    cv::cvtColor(color.image, canvas, cv::COLOR_GRAY2BGR);
  else
    canvas = color.image.clone();
  if (truth) draw_outline(canvas, color, *truth, cv::Scalar(0, 200, 0));
  draw_outline(canvas, color, estimate, cv::Scalar(0, 0, 255));
  cv::putText(canvas, caption, cv::Point(10, 24), cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(255, 255, 255), 2,
              cv::LINE_AA);

  // Opened on the first image: the video takes its size.
  if (!writer_.isOpened()) {
    writer_.open(path_, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), frames_per_second_, canvas.size());
    if (!writer_.isOpened()) throw std::runtime_error("cannot open video file '" + path_ + "' for writing");
  }
  writer_.write(canvas);
}

void OverlayVideo::draw_outline(cv::Mat& canvas, const ColorImage& color, const Pose& reference_T_body,
                                const cv::Scalar& bgr) {
  renderer_.set_body_pose(body_, reference_T_body);
  const cv::Mat ids = renderer_.render(color.intrinsics, color.camera_T_reference, kRenderIds).ids;
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(ids, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  cv::drawContours(canvas, contours, -1, bgr, 2, cv::LINE_AA);
}

}  // namespace icgp::app
