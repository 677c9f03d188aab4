// SPDX-License-Identifier: GPL-2.0-or-later
#include "frame_assembly.h"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <visp3/core/vpException.h>

#include "icgp/visp/conversions.h"

namespace icgp {
namespace {

Intrinsics camera_intrinsics(const std::string& camera, const vpCameraParameters& parameters, unsigned int width,
                             unsigned int height) {
  try {
    return to_intrinsics(parameters, static_cast<int>(width), static_cast<int>(height));
  } catch (const std::exception& e) {
    throw vpException(vpException::badValue, "vpMbIcgTracker: camera \"" + camera + "\": " + e.what());
  }
}

ColorImage& only_color(Frame& frame, const std::string& camera) {
  frame.colors.resize(1);
  frame.colors.front().camera = camera;
  frame.colors.front().camera_T_reference = Pose();
  return frame.colors.front();
}

void require_camera(bool set, const std::string& camera) {
  if (!set)
    throw vpException(vpException::notInitialized,
                      "vpMbIcgTracker: the parameters of camera \"" + camera +
                          "\" were never set (setCameraParameters, or loadConfigFile with a ViSP XML <camera> block)");
}

}  // namespace

void FrameAssembler::set_color(const std::string& camera, const vpImage<unsigned char>& I,
                               const vpCameraParameters& parameters, bool camera_set) {
  require_camera(camera_set, camera);
  ColorImage& c = only_color(frame_, camera);
  c.intrinsics = camera_intrinsics(camera, parameters, I.getWidth(), I.getHeight());
  // vpImage rows are contiguous: the tracker reads the caller's pixels directly.
  c.image = cv::Mat(static_cast<int>(I.getHeight()), static_cast<int>(I.getWidth()), CV_8UC1,
                    const_cast<unsigned char*>(I.bitmap));
  rgba_view_ = cv::Mat();
}

void FrameAssembler::set_color(const std::string& camera, const vpImage<vpRGBa>& I,
                               const vpCameraParameters& parameters, bool camera_set) {
  require_camera(camera_set, camera);
  ColorImage& c = only_color(frame_, camera);
  c.intrinsics = camera_intrinsics(camera, parameters, I.getWidth(), I.getHeight());
  static_assert(sizeof(vpRGBa) == 4, "vpRGBa is R, G, B, A bytes");
  rgba_view_ = cv::Mat(static_cast<int>(I.getHeight()), static_cast<int>(I.getWidth()), CV_8UC4,
                       const_cast<vpRGBa*>(I.bitmap));
  cv::cvtColor(rgba_view_, c.image, cv::COLOR_RGBA2BGR);  // SIMD, unlike a per-pixel loop
}

const vpImage<unsigned char>& FrameAssembler::grey_image() {
  const cv::Mat& image = frame_.colors.at(0).image;
  grey_.resize(static_cast<unsigned int>(image.rows), static_cast<unsigned int>(image.cols));
  cv::Mat grey(image.rows, image.cols, CV_8UC1, grey_.bitmap);
  if (image.channels() == 3)
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  else
    image.copyTo(grey);
  return grey_;
}

void FrameAssembler::set_depth(const std::string& camera, unsigned int width, unsigned int height,
                               const std::optional<vpCameraParameters>& parameters,
                               const vpHomogeneousMatrix& camera_M_color, DepthReader read) {
  require_camera(parameters.has_value(), camera);
  frame_.depths.resize(1);
  DepthImage& d = frame_.depths.front();
  d.camera = camera;
  d.intrinsics = camera_intrinsics(camera, *parameters, width, height);
  d.camera_T_reference = to_pose(camera_M_color);
  const cv::Size size(static_cast<int>(width), static_cast<int>(height));
  if (d.depth.size() != size || d.depth.type() != CV_32FC1) {
    d.depth.create(size, CV_32FC1);
    d.depth.setTo(DepthImage::kNotConverted);
  } else {
    d.source.unconvert(d.depth);
  }
  d.source.set_reader(std::move(read));
}

void FrameAssembler::set_no_depth(const std::string& camera) {
  frame_.depths.resize(1);
  DepthImage& d = frame_.depths.front();
  d.camera = camera;
  d.depth = cv::Mat();
  d.source.drop_reader();
}

void FrameAssembler::end_depth_reads() {
  for (DepthImage& d : frame_.depths) d.source.drop_reader();
}

}  // namespace icgp
