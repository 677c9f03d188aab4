// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/render/visualization.h"

#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace icgp {

cv::Mat depth_to_bgr(const cv::Mat& depth) {
  CV_Assert(depth.type() == CV_32FC1);
  const cv::Mat valid = depth > 0.f;
  double lo = 0.0, hi = 0.0;
  cv::minMaxLoc(depth, &lo, &hi, nullptr, nullptr, valid);
  cv::Mat scaled;
  const double range = std::max(hi - lo, 1e-6);
  depth.convertTo(scaled, CV_8U, -230.0 / range, 240.0 + 230.0 * lo / range);  // near bright, far dark
  cv::Mat bgr;
  cv::applyColorMap(scaled, bgr, cv::COLORMAP_TURBO);
  bgr.setTo(cv::Scalar::all(0), ~valid);
  return bgr;
}

cv::Mat normals_to_bgr(const cv::Mat& normals) {
  CV_Assert(normals.type() == CV_32FC3);
  cv::Mat rgb;
  normals.convertTo(rgb, CV_8UC3, 127.5, 127.5);
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  std::vector<cv::Mat> channels;
  cv::split(normals, channels);
  const cv::Mat empty = (channels[0] == 0.f) & (channels[1] == 0.f) & (channels[2] == 0.f);
  bgr.setTo(cv::Scalar::all(0), empty);
  return bgr;
}

cv::Mat ids_to_bgr(const cv::Mat& ids) {
  CV_Assert(ids.type() == CV_8UC1);
  cv::Mat lut(1, 256, CV_8UC3);
  for (int id = 0; id < 256; ++id) {
    // Golden-angle hues keep consecutive ids far apart in colour.
    const int hue = static_cast<int>(id * 137.508) % 180;
    lut.at<cv::Vec3b>(id) = cv::Vec3b(static_cast<uchar>(hue), 200, 255);
  }
  cv::cvtColor(lut, lut, cv::COLOR_HSV2BGR);
  lut.at<cv::Vec3b>(0) = cv::Vec3b(0, 0, 0);
  cv::Mat ids3, bgr;
  cv::cvtColor(ids, ids3, cv::COLOR_GRAY2BGR);
  cv::LUT(ids3, lut, bgr);
  return bgr;
}

cv::Mat tile(const std::vector<cv::Mat>& images, int columns) {
  if (images.empty() || columns <= 0) throw std::invalid_argument("tile: need images and a positive column count");
  const cv::Size size = images.front().size();
  const int rows = (static_cast<int>(images.size()) + columns - 1) / columns;
  cv::Mat out = cv::Mat::zeros(rows * size.height, columns * size.width, CV_8UC3);
  for (std::size_t i = 0; i < images.size(); ++i) {
    if (images[i].size() != size || images[i].type() != CV_8UC3)
      throw std::invalid_argument("tile: all images must be CV_8UC3 of the same size");
    const int r = static_cast<int>(i) / columns, c = static_cast<int>(i) % columns;
    images[i].copyTo(out(cv::Rect(c * size.width, r * size.height, size.width, size.height)));
  }
  return out;
}

}  // namespace icgp
