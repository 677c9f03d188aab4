// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <cmath>
#include <functional>
#include <map>
#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>
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

/// Where the not yet converted pixels of a depth image get their depth (see DepthImage),
/// and which pixels it has converted.
class LazyDepthSource {
 public:
  static constexpr float kNotConverted = -1.f;

  /// `read`: the measured depth at (row, col) in metres; 0, negative or not finite: none.
  void set_reader(std::function<float(int row, int col)> read) { read_ = std::move(read); }
  /// Pixels not converted so far read as no measurement from now on.
  void drop_reader() { read_ = nullptr; }

  /// The depth of kNotConverted pixel (row, col) of `depth`, which is written there.
  float convert(cv::Mat& depth, int row, int col) {
    if (!read_) return 0.f;
    float z = read_(row, col);
    if (!(z > 0.f) || !std::isfinite(z)) z = 0.f;
    depth.ptr<float>(row)[col] = z;
    converted_.emplace_back(col, row);
    return z;
  }
  /// Makes the pixels converted so far kNotConverted again, so that the next frame of the
  /// source is read without converting or clearing the whole image.
  void unconvert(cv::Mat& depth) {
    for (const cv::Point& p : converted_) depth.ptr<float>(p.y)[p.x] = kNotConverted;
    converted_.clear();
  }

 private:
  std::function<float(int row, int col)> read_;
  std::vector<cv::Point> converted_;
};

/// One depth camera's image and calibration. Depth is Z along the optical axis.
///
/// The cues read depth sparsely: a few samples per model point, a few thousand distinct
/// pixels per frame. When a source costs more to convert whole than that (ViSP's organised
/// clouds, one heap-allocated vpColVector per pixel), pixels may hold kNotConverted and
/// `source` gives their depth on first read through at(). Such a frame must not be read
/// from several threads at once.
struct DepthImage {
  static constexpr float kNotConverted = LazyDepthSource::kNotConverted;

  std::string camera;  ///< e.g. "Camera2"
  Intrinsics intrinsics;
  Pose camera_T_reference;  ///< for a ViSP sequence this is depth_M_color
  cv::Mat depth;            ///< CV_32FC1, metres, 0 where there is no measurement
  /// Converting on read keeps the image logically constant: a pixel only ever takes the
  /// one value its source gives.
  mutable LazyDepthSource source;

  /// False for a frame in which the camera delivered no depth at all (ViSP: a point cloud
  /// of width and height 0): the cues that read it sit that frame out.
  bool delivered() const { return !depth.empty(); }
  /// The depth at (row, col), inside the image: metres, 0 where there is no measurement.
  float at(int row, int col) const {
    const float z = depth.ptr<float>(row)[col];
    return z != kNotConverted ? z : source.convert(const_cast<cv::Mat&>(depth), row, col);
  }
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
