// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>
#include <string>
#include <vector>

#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"

namespace icgp {

/// Which pixels of an image the cues may use (ViSP's setMask): CV_8UC1 of the image's
/// size, 0 where a pixel must be ignored. Empty: every pixel.
struct PixelMask {
  cv::Mat mask;

  bool all_pixels() const { return mask.empty(); }
  /// False for a pixel the mask excludes; pixels outside the image are left to the caller.
  bool usable(int row, int col) const {
    return mask.empty() || row < 0 || col < 0 || row >= mask.rows || col >= mask.cols ||
           mask.ptr<std::uint8_t>(row)[col] != 0;
  }
  bool usable(const Eigen::Vector2f& pixel) const {
    return usable(static_cast<int>(std::lround(pixel.y())), static_cast<int>(std::lround(pixel.x())));
  }
};

/// One colour camera's image and calibration. The reference frame of a Frame is its first
/// colour camera, so that camera has camera_T_reference = identity.
struct ColorImage {
  std::string camera;  ///< e.g. "Camera1"
  Intrinsics intrinsics;
  Pose camera_T_reference;
  cv::Mat image;  ///< CV_8UC3 (BGR, OpenCV order) or CV_8UC1 (grey)
  PixelMask mask;
};

/// Where the not yet converted pixels of a depth image get their depth (see DepthImage),
/// and which pixels it has converted.
class LazyDepthSource {
 public:
  static constexpr float kNotConverted = -1.f;
  /// Told the pixels the cues are about to read (DepthImage::read_soon).
  using ReadSoon = std::function<void(const std::vector<cv::Point>& pixels)>;

  /// `read`: the measured depth at (row, col) in metres; 0, negative or not finite: none.
  /// `read_soon`, if any: see DepthImage::read_soon.
  void set_reader(std::function<float(int row, int col)> read, ReadSoon read_soon = nullptr) {
    read_ = std::move(read);
    read_point_ = nullptr;
    read_soon_ = std::move(read_soon);
  }
  /// `read`: the measured point at (row, col) in the camera frame, metres; Z 0, negative or
  /// not finite: none. Its ray (X/Z, Y/Z) is written to the `rays` of convert().
  void set_point_reader(std::function<Eigen::Vector3f(int row, int col)> read, ReadSoon read_soon = nullptr) {
    read_point_ = std::move(read);
    read_ = nullptr;
    read_soon_ = std::move(read_soon);
  }
  /// Pixels not converted so far read as no measurement from now on.
  void drop_reader() {
    read_ = nullptr;
    read_point_ = nullptr;
    read_soon_ = nullptr;
  }

  /// DepthImage::takes_read_soon and DepthImage::read_soon.
  bool takes_read_soon() const { return static_cast<bool>(read_soon_); }
  void read_soon(const std::vector<cv::Point>& pixels) const {
    if (read_soon_) read_soon_(pixels);
  }

  /// The depth of kNotConverted pixel (row, col) of `depth`, which is written there (and
  /// the point's ray to `rays` when the source gives points).
  float convert(cv::Mat& depth, cv::Mat& rays, int row, int col) {
    float z = 0.f;
    if (read_point_) {
      const Eigen::Vector3f P = read_point_(row, col);
      z = P.z();
      if (z > 0.f && std::isfinite(z)) rays.ptr<cv::Vec2f>(row)[col] = cv::Vec2f(P.x() / z, P.y() / z);
    } else if (read_) {
      z = read_(row, col);
    } else {
      return 0.f;
    }
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
  std::function<Eigen::Vector3f(int row, int col)> read_point_;
  ReadSoon read_soon_;
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
  /// CV_32FC2 (X/Z, Y/Z) of each measured pixel when the points do not lie on the
  /// intrinsics' pinhole rays (a cloud de-projected with the sensor's distortion); empty:
  /// a pixel's point is its pinhole ray times its depth.
  cv::Mat rays;
  PixelMask mask;
  /// Converting on read keeps the image logically constant: a pixel only ever takes the
  /// one value its source gives.
  mutable LazyDepthSource source;

  /// False for a frame in which the camera delivered no depth at all (ViSP: a point cloud
  /// of width and height 0): the cues that read it sit that frame out.
  bool delivered() const { return !depth.empty(); }
  /// The depth at (row, col), inside the image: metres, 0 where there is no measurement.
  float at(int row, int col) const {
    const float z = depth.ptr<float>(row)[col];
    return z != kNotConverted ? z : source.convert(const_cast<cv::Mat&>(depth), const_cast<cv::Mat&>(rays), row, col);
  }
  /// Whether read_soon() may help: the depth is converted on read from a source that reads
  /// scattered pixels faster together, so that gathering them is worth a cue's while.
  bool takes_read_soon() const { return source.takes_read_soon(); }
  /// Tells the source that a cue is about to read `pixels` (inside the image), one at a time
  /// between its own computations: a source whose reads wait on memory (ViSP's clouds) reads
  /// them now, together. at() gives the same values either way.
  void read_soon(const std::vector<cv::Point>& pixels) const { source.read_soon(pixels); }
  /// The measured point at (row, col), given its depth z = at(row, col) > 0.
  Eigen::Vector3f point(int row, int col, float z) const {
    if (rays.empty())
      return {static_cast<float>((col - intrinsics.pu) / intrinsics.fu) * z,
              static_cast<float>((row - intrinsics.pv) / intrinsics.fv) * z, z};
    const cv::Vec2f& r = rays.ptr<cv::Vec2f>(row)[col];
    return {r[0] * z, r[1] * z, z};
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
  /// Ground-truth joint values (radians / metres, in the joint's order) per link name.
  std::map<std::string, std::vector<double>> joint_ground_truth;

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
  /// The ground-truth joint values of link `object`; nullptr when there are none.
  const std::vector<double>* joint_truth(const std::string& object) const {
    const auto it = joint_ground_truth.find(object);
    return it == joint_ground_truth.end() ? nullptr : &it->second;
  }
};

}  // namespace icgp
