// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>
#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpRGBa.h>

#include "icgp/eval/frame.h"

namespace icgp {

/// Builds the icgp::Frame a tracker reads from what ViSP users hold: vpImage colour or grey
/// images, organised point clouds, raw depth images. Buffers are reused from frame to
/// frame, and a grey vpImage is wrapped without a copy. Camera problems throw vpException
/// naming the camera.
class FrameAssembler {
 public:
  /// `camera_set` false: the user never gave the parameters (ViSP would silently use its
  /// defaults; icgp refuses).
  void set_color(const std::string& camera, const vpImage<unsigned char>& I, const vpCameraParameters& parameters,
                 bool camera_set);
  void set_color(const std::string& camera, const vpImage<vpRGBa>& I, const vpCameraParameters& parameters,
                 bool camera_set);
  /// Where a depth pixel comes from: metres at (row, col); 0, negative or not finite
  /// means no measurement.
  using DepthReader = std::function<float(int row, int col)>;
  /// The frame's depth image, converted from `read` on first read of each pixel (see
  /// DepthImage::source): the cues read a few thousand pixels, and reading a whole cloud
  /// of ViSP's vpColVectors would cost as much as tracking. `read` is used until
  /// end_depth_reads().
  void set_depth(const std::string& camera, unsigned int width, unsigned int height,
                 const std::optional<vpCameraParameters>& parameters, const vpHomogeneousMatrix& camera_M_color,
                 DepthReader read);
  /// The depth camera delivered nothing this frame (DepthImage::delivered).
  void set_no_depth(const std::string& camera);
  /// Drops the reader of set_depth (which usually refers to the caller's cloud): pixels
  /// not read so far read as "no measurement" from now on.
  void end_depth_reads();

  const Frame& frame() const { return frame_; }
  /// The last colour image as ViSP grey, for ViSP's projection error.
  const vpImage<unsigned char>& grey_image();

 private:
  Frame frame_;
  cv::Mat rgba_view_;
  vpImage<unsigned char> grey_;
};

}  // namespace icgp
