// SPDX-License-Identifier: GPL-2.0-or-later
#include "frame_assembly.h"

#include <cmath>
#include <iostream>
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

void require_camera(bool set, const std::string& camera) {
  if (!set)
    throw vpException(vpException::notInitialized,
                      "vpMbIcgTracker: the parameters of camera \"" + camera +
                          "\" were never set (setCameraParameters, or loadConfigFile with a ViSP XML <camera> block)");
}

}  // namespace

void require_image_size(const std::string& call, const std::function<std::string()>& what, unsigned int width,
                        unsigned int height) {
  if (width == 0 || height == 0 || width > kMaxImageSide || height > kMaxImageSide)
    throw vpException(vpException::badValue, "vpMbIcgTracker::" + call + ": " + what() + " is " +
                                                 std::to_string(width) + " x " + std::to_string(height) +
                                                 " pixels; width and height must be in [1, " +
                                                 std::to_string(kMaxImageSide) + "]");
}

void FrameAssembler::begin_frame() {
  frame_.colors.clear();
  for (DepthImage& d : frame_.depths) {
    if (d.delivered()) d.source.unconvert(d.depth);
    d.source.drop_reader();
    d.depth = cv::Mat();
    d.rays = cv::Mat();
  }
}

cv::Mat FrameAssembler::mask_for(const std::string& camera, int width, int height) {
  if (mask_.empty() || (mask_.cols == width && mask_.rows == height)) return mask_;
  // ViSP applies one mask to every camera; one of another size cannot use it.
  if (cameras_without_mask_.insert(camera).second)
    std::cerr << "vpMbIcgTracker::setMask: the mask is " << mask_.cols << "x" << mask_.rows << " but camera \""
              << camera << "\" delivers " << width << "x" << height << " images; that camera uses every pixel\n";
  return cv::Mat();
}

void FrameAssembler::set_mask(const vpImage<bool>& mask) {
  if (mask.getSize() == 0) {
    mask_ = cv::Mat();
    return;
  }
  mask_.create(static_cast<int>(mask.getHeight()), static_cast<int>(mask.getWidth()), CV_8UC1);
  for (unsigned int r = 0; r < mask.getHeight(); ++r)
    for (unsigned int c = 0; c < mask.getWidth(); ++c) mask_.ptr<std::uint8_t>(r)[c] = mask[r][c] ? 1 : 0;
}

ColorImage& FrameAssembler::color_slot(const std::string& camera, const vpCameraParameters& parameters,
                                       bool camera_set, const vpHomogeneousMatrix& camera_M_reference,
                                       unsigned int width, unsigned int height) {
  require_camera(camera_set, camera);
  ColorImage& c = color_slots_[camera];
  c.camera = camera;
  c.intrinsics = camera_intrinsics(camera, parameters, width, height);
  c.camera_T_reference = to_pose(camera_M_reference);
  c.mask.mask = mask_for(camera, static_cast<int>(width), static_cast<int>(height));
  return c;
}

void FrameAssembler::set_color(const std::string& camera, const vpImage<unsigned char>& I,
                               const vpCameraParameters& parameters, bool camera_set,
                               const vpHomogeneousMatrix& camera_M_reference) {
  ColorImage& c = color_slot(camera, parameters, camera_set, camera_M_reference, I.getWidth(), I.getHeight());
  // vpImage rows are contiguous: the tracker reads the caller's pixels directly.
  c.image = cv::Mat(static_cast<int>(I.getHeight()), static_cast<int>(I.getWidth()), CV_8UC1,
                    const_cast<unsigned char*>(I.bitmap));
  frame_.colors.push_back(c);
  c.image = cv::Mat();  // the slot must not outlive the caller's pixels
}

void FrameAssembler::set_color(const std::string& camera, const vpImage<vpRGBa>& I,
                               const vpCameraParameters& parameters, bool camera_set,
                               const vpHomogeneousMatrix& camera_M_reference) {
  ColorImage& c = color_slot(camera, parameters, camera_set, camera_M_reference, I.getWidth(), I.getHeight());
  static_assert(sizeof(vpRGBa) == 4, "vpRGBa is R, G, B, A bytes");
  const cv::Mat rgba(static_cast<int>(I.getHeight()), static_cast<int>(I.getWidth()), CV_8UC4,
                     const_cast<vpRGBa*>(I.bitmap));
  cv::cvtColor(rgba, c.image, cv::COLOR_RGBA2BGR);  // SIMD, unlike a per-pixel loop; reuses the slot's buffer
  frame_.colors.push_back(c);
}

const vpImage<unsigned char>* FrameAssembler::grey_image(const std::string& camera) {
  const ColorImage* color = frame_.find_color(camera);
  if (!color) return nullptr;
  const cv::Mat& image = color->image;
  grey_.resize(static_cast<unsigned int>(image.rows), static_cast<unsigned int>(image.cols));
  cv::Mat grey(image.rows, image.cols, CV_8UC1, grey_.bitmap);
  if (image.channels() == 3)
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  else
    image.copyTo(grey);
  return &grey_;
}

DepthImage& FrameAssembler::depth_slot(const std::string& camera, const vpCameraParameters& parameters,
                                       bool camera_set, const vpHomogeneousMatrix& camera_M_reference,
                                       unsigned int width, unsigned int height) {
  require_camera(camera_set, camera);
  DepthImage* slot = nullptr;
  for (DepthImage& d : frame_.depths)
    if (d.camera == camera) slot = &d;
  if (!slot) {
    slot = &frame_.depths.emplace_back();
    slot->camera = camera;
  }
  DepthImage& d = *slot;
  d.intrinsics = camera_intrinsics(camera, parameters, width, height);
  d.camera_T_reference = to_pose(camera_M_reference);
  d.mask.mask = mask_for(camera, static_cast<int>(width), static_cast<int>(height));
  // begin_frame() left every buffer unconverted: only a new size needs clearing.
  cv::Mat& buffer = depth_buffers_[camera];
  const cv::Size size(static_cast<int>(width), static_cast<int>(height));
  if (buffer.size() != size || buffer.type() != CV_32FC1) {
    buffer.create(size, CV_32FC1);
    buffer.setTo(DepthImage::kNotConverted);
  }
  d.depth = buffer;
  return d;
}

void FrameAssembler::set_depth(const std::string& camera, unsigned int width, unsigned int height,
                               const vpCameraParameters& parameters, bool camera_set,
                               const vpHomogeneousMatrix& camera_M_reference, DepthReader read,
                               ManyPointsReader read_many) {
  DepthImage& d = depth_slot(camera, parameters, camera_set, camera_M_reference, width, height);
  d.source.set_reader(std::move(read), std::move(read_many));
  d.source.read_ahead(d.depth, d.rays);
}

void FrameAssembler::set_depth_points(const std::string& camera, unsigned int width, unsigned int height,
                                      const vpCameraParameters& parameters, bool camera_set,
                                      const vpHomogeneousMatrix& camera_M_reference, PointReader read,
                                      ManyPointsReader read_many) {
  DepthImage& d = depth_slot(camera, parameters, camera_set, camera_M_reference, width, height);
  cv::Mat& rays = ray_buffers_[camera];
  rays.create(d.depth.size(), CV_32FC2);  // read only where the depth is converted
  d.rays = rays;
  d.source.set_point_reader(std::move(read), std::move(read_many));
  d.source.read_ahead(d.depth, d.rays);
}

void FrameAssembler::set_no_depth(const std::string& camera) {
  for (const DepthImage& d : frame_.depths)
    if (d.camera == camera) return;  // begin_frame() left it undelivered
  frame_.depths.emplace_back().camera = camera;
}

void FrameAssembler::end_depth_reads() {
  for (DepthImage& d : frame_.depths) d.source.drop_reader();
}

}  // namespace icgp
