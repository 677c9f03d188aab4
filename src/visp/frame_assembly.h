// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <cstdint>
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
  /// A depth image in metres for the caller to fill inside `region`; everything else is 0
  /// ("no measurement"). Only the previous frame's region is cleared, not the whole image.
  cv::Mat& depth_to_fill(const std::string& camera, unsigned int width, unsigned int height,
                         const std::optional<vpCameraParameters>& parameters, const vpHomogeneousMatrix& camera_M_color,
                         const cv::Rect& region);
  void clear_depth() { frame_.depths.clear(); }

  const Frame& frame() const { return frame_; }
  /// The last colour image as ViSP grey, for ViSP's projection error.
  const vpImage<unsigned char>& grey_image();

 private:
  Frame frame_;
  cv::Rect filled_;  ///< where the depth image may hold non-zero values
  cv::Mat rgba_view_;
  vpImage<unsigned char> grey_;
};

}  // namespace icgp
