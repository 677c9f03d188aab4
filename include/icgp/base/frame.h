// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <mutex>
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
/// which pixels it has converted, and which pixels a frame read, to read them ahead in the
/// next frame.
///
/// A pixel of such an image holds its depth (>= 0: converted), kNotConverted (NaN), or,
/// read ahead and not read yet this frame, its depth negated (kReadAheadZero for 0): one
/// comparison with 0 tells a converted pixel, so reading one costs a load, and the first
/// read of a pixel read ahead makes it converted: at the frame's end, the converted pixels
/// that hold a depth >= 0 are the ones the frame read.
///
/// Several threads may read one image at once: a pixel's depth is loaded and stored
/// atomically, a pixel read ahead is converted by storing its one value (whichever thread
/// does it), and the source itself is asked under a lock. Setting the reader, reading ahead
/// and unconverting happen between frames, on one thread.
class LazyDepthSource {
 public:
  static constexpr float kNotConverted = std::numeric_limits<float>::quiet_NaN();
  /// Reads the measured points of many pixels at once (see set_reader).
  using ManyPointsReader = std::function<void(const std::vector<cv::Point>& pixels, std::vector<Eigen::Vector3f>& points)>;

  /// `read`: the measured depth at (row, col) in metres; 0, negative or not finite: none.
  /// `read_many`, if any: the points of many pixels (their Z is the depth), read in one
  /// pass whose memory reads overlap; with it, the pixels a frame read are read ahead in
  /// the next (read_ahead) and DepthImage::read_soon is worth a cue's while.
  void set_reader(std::function<float(int row, int col)> read, ManyPointsReader read_many = nullptr) {
    read_ = std::move(read);
    read_point_ = nullptr;
    read_many_ = std::move(read_many);
  }
  /// `read`: the measured point at (row, col) in the camera frame, metres; Z 0, negative or
  /// not finite: none. Its ray (X/Z, Y/Z) is written to the `rays` of the image.
  void set_point_reader(std::function<Eigen::Vector3f(int row, int col)> read, ManyPointsReader read_many = nullptr) {
    read_point_ = std::move(read);
    read_ = nullptr;
    read_many_ = std::move(read_many);
  }
  /// Pixels not converted so far read as no measurement from now on.
  void drop_reader() {
    read_ = nullptr;
    read_point_ = nullptr;
    read_many_ = nullptr;
  }

  /// DepthImage::takes_read_soon.
  bool takes_read_soon() const { return static_cast<bool>(read_many_); }
  /// Converts, in one pass of the source, the pixels of `pixels` not converted yet
  /// (DepthImage::read_soon).
  void read_soon(cv::Mat& depth, cv::Mat& rays, const std::vector<cv::Point>& pixels);
  /// With a source that reads many pixels at once, reads ahead the pixels the last frame
  /// of this source read (inside `depth`), in one pass: called once the frame's reader is
  /// set.
  void read_ahead(cv::Mat& depth, cv::Mat& rays);

  /// DepthImage::at of a pixel that holds no converted depth: reads it from the source,
  /// or takes the depth read ahead; either way the frame read it. 0 without a source.
  float resolve(cv::Mat& depth, cv::Mat& rays, int row, int col);
  /// A pixel's value as another thread may be storing it (resolve). Relaxed: a plain load,
  /// left free for the compiler to schedule, on the hot path of every cue that reads depth;
  /// DepthImage::point orders the pixel's ray after it (ordered_after_depth) where there are
  /// rays.
  static float load(const float& held) {
    float z;
    __atomic_load(&held, &z, __ATOMIC_RELAXED);
    return z;
  }
  /// Loads the pixel again, pairing with the store that converted it (a release store after
  /// its ray): what is read after this call sees the pixel's ray.
  static void ordered_after_depth(const float& held) {
    float z;
    __atomic_load(&held, &z, __ATOMIC_ACQUIRE);
  }
  /// Makes the pixels converted so far kNotConverted again, so that the next frame of the
  /// source is read without converting or clearing the whole image.
  void unconvert(cv::Mat& depth);

 private:
  /// Stands for a depth of 0 read ahead: -0 would read as converted.
  static constexpr float kReadAheadZero = std::numeric_limits<float>::min();
  bool has_reader() const { return read_ || read_point_; }
  /// Converts `pixels` (inside the image, not converted) in one pass; `read_ahead`: stored
  /// negated, and recorded as read only when a cue reads them.
  void read_many(cv::Mat& depth, cv::Mat& rays, const std::vector<cv::Point>& pixels, bool read_ahead);
  /// A measured depth as the image holds it: 0 where there is no measurement.
  static float sanitized(float z) { return z > 0.f && std::isfinite(z) ? z : 0.f; }
  /// The depth of measured point P of pixel (row, col) as the image holds it; with a point
  /// reader, its ray goes to `rays`.
  float measured_depth(const Eigen::Vector3f& P, cv::Mat& rays, int row, int col) const;
  static void store(float& held, float z) { __atomic_store(&held, &z, __ATOMIC_RELEASE); }

  /// A mutex that a copy of the source does not share: a copied image converts on its own.
  struct OwnMutex {
    std::mutex mutex;
    OwnMutex() = default;
    OwnMutex(const OwnMutex&) {}
    OwnMutex& operator=(const OwnMutex&) { return *this; }
  };

  std::function<float(int row, int col)> read_;
  std::function<Eigen::Vector3f(int row, int col)> read_point_;
  ManyPointsReader read_many_;
  OwnMutex source_lock_;              ///< held while the source is asked, and for the lists
  std::vector<cv::Point> converted_;  ///< this frame's, to unconvert
  std::vector<cv::Point> read_last_;  ///< pixels the last frame read, read ahead in this one
  std::vector<cv::Point> pending_;    ///< scratch of read_many
  std::vector<Eigen::Vector3f> points_;
};

/// One depth camera's image and calibration. Depth is Z along the optical axis.
///
/// The cues read depth sparsely: a few samples per model point, a few thousand distinct
/// pixels per frame. When a source costs more to convert whole than that (ViSP's organised
/// clouds, one heap-allocated vpColVector per pixel), pixels may hold kNotConverted and
/// `source` gives their depth on first read through at(), on any thread.
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
    const float z = LazyDepthSource::load(depth.ptr<float>(row)[col]);
    return z >= 0.f ? z : source.resolve(const_cast<cv::Mat&>(depth), const_cast<cv::Mat&>(rays), row, col);
  }
  /// Whether read_soon() may help: the depth is converted on read from a source that reads
  /// scattered pixels faster together, so that gathering them is worth a cue's while.
  bool takes_read_soon() const { return source.takes_read_soon(); }
  /// Tells the source that a cue is about to read `pixels` (inside the image), one at a time
  /// between its own computations: a source whose reads wait on memory (ViSP's clouds) reads
  /// them now, together. at() gives the same values either way.
  void read_soon(const std::vector<cv::Point>& pixels) const {
    source.read_soon(const_cast<cv::Mat&>(depth), const_cast<cv::Mat&>(rays), pixels);
  }
  /// The measured point at (row, col), given its depth z = at(row, col) > 0.
  Eigen::Vector3f point(int row, int col, float z) const {
    if (rays.empty())
      return {static_cast<float>((col - intrinsics.pu) / intrinsics.fu) * z,
              static_cast<float>((row - intrinsics.pv) / intrinsics.fv) * z, z};
    LazyDepthSource::ordered_after_depth(depth.ptr<float>(row)[col]);
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
