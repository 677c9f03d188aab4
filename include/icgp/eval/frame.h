// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <map>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "icgp/geometry/intrinsics.h"
#include "icgp/geometry/pose.h"

namespace icgp {

/// One colour camera's image and calibration. The reference frame of a Frame is its first
/// colour camera, so that camera has camera_T_reference = identity.
struct ColorImage {
  std::string camera;  ///< e.g. "Camera1"
  Intrinsics intrinsics;
  Pose camera_T_reference;
  cv::Mat image;  ///< CV_8UC3 (BGR, OpenCV order) or CV_8UC1 (grey)
};

/// One depth camera's image and calibration. Depth is Z along the optical axis.
struct DepthImage {
  std::string camera;  ///< e.g. "Camera2"
  Intrinsics intrinsics;
  Pose camera_T_reference;  ///< for a ViSP sequence this is depth_M_color
  cv::Mat depth;            ///< CV_32FC1, metres, 0 where there is no measurement
};

/// Everything a tracker sees at one instant: the images of every camera with their
/// calibration, and the ground truth when the sequence has it.
struct Frame {
  int index = 0;
  double timestamp = 0.0;  ///< seconds
  std::vector<ColorImage> colors;
  std::vector<DepthImage> depths;
  /// Ground-truth reference_T_object (ViSP cMo) per object name.
  std::map<std::string, Pose> ground_truth;

  /// The colour / depth image of the named camera; nullptr when the frame has none.
  const ColorImage* find_color(const std::string& camera) const {
    for (const auto& c : colors)
      if (c.camera == camera) return &c;
    return nullptr;
  }
  const DepthImage* find_depth(const std::string& camera) const {
    for (const auto& d : depths)
      if (d.camera == camera) return &d;
    return nullptr;
  }

  /// The ground truth of `object`, or of the only object when `object` is empty;
  /// nullptr when there is none.
  const Pose* truth(const std::string& object = "") const {
    if (object.empty()) return ground_truth.size() == 1 ? &ground_truth.begin()->second : nullptr;
    const auto it = ground_truth.find(object);
    return it == ground_truth.end() ? nullptr : &it->second;
  }
};

}  // namespace icgp
