// SPDX-License-Identifier: GPL-2.0-or-later
// A ViSP RGB-D program written against ViSP's API alone (VispProgram), for any tracker that
// has vpMbGenericTracker's two-camera calls, run over a sequence by icgp's one sequence
// runner. vpMbGenericTracker and vpMbIcgTracker run through literally the same code, so
// whatever differs in their results comes from the trackers: this is what "drop-in
// replacement" means in numbers.
#pragma once

#include <chrono>
#include <iostream>
#include <map>
#include <opencv2/core/mat.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>
#include <vector>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/mbt/vpMbGenericTracker.h>

#include "icgp/base/camera_names.h"
#include "icgp/base/frame.h"
#include "icgp/base/pose.h"
#include "icgp/visp/conversions.h"
#include "icgp/base/standard_stream_capture.h"
#include "icgp/eval/sequence_run.h"
#include "icgp/visp/visp_baseline.h"

namespace icgp {

/// The tracker types of vpMbGenericTracker's colour camera (kColorCamera, the reference:
/// cMo is relative to it) and depth camera (kDepthCamera), as ViSP's RGB-D programs
/// construct them: the colour camera's edges and KLT points (icgp: region and texture), the
/// depth camera's dense depth.
inline const std::vector<int> kRgbdTrackerTypes = {vpMbGenericTracker::EDGE_TRACKER | vpMbGenericTracker::KLT_TRACKER,
                                                   vpMbGenericTracker::DEPTH_DENSE_TRACKER};

/// A frame in the shapes ViSP's RGB-D track() takes. Kept from frame to frame so that
/// converting a sequence reuses the same buffers instead of allocating a cloud per frame.
struct VispRgbdFrame {
  /// The colour camera's image in grey levels.
  vpImage<unsigned char> grey;
  /// The depth camera's organised cloud: depth_width * depth_height points, row-major,
  /// X Y Z in metres in the depth camera's frame, 0 0 0 where there is no measurement.
  std::vector<vpColVector> point_cloud;
  unsigned int depth_width = 0, depth_height = 0;

  /// Fills `grey` from frame.colors[0] and, when `with_depth`, the point cloud from
  /// frame.depths[0]. Throws std::invalid_argument when the frame lacks one of them.
  void convert(const Frame& frame, bool with_depth = true) {
    if (frame.colors.empty())
      throw std::invalid_argument("frame " + std::to_string(frame.index) + " has no colour image");
    const cv::Mat& color = frame.colors.front().image;
    if (color.channels() == 1) {
      to_vp_image(color, grey);
    } else {
      cv::cvtColor(color, grey_mat_, cv::COLOR_BGR2GRAY);
      to_vp_image(grey_mat_, grey);
    }
    if (!with_depth) return;
    if (frame.depths.empty())
      throw std::invalid_argument("frame " + std::to_string(frame.index) + " has no depth image");
    convert_depth(frame.depths.front());
  }

 private:
  /// Back-projects every pixel with the depth camera's intrinsics, as ViSP's RGB-D
  /// tutorials build the cloud from a depth sensor.
  void convert_depth(const DepthImage& depth) {
    depth_width = static_cast<unsigned int>(depth.depth.cols);
    depth_height = static_cast<unsigned int>(depth.depth.rows);
    point_cloud.resize(static_cast<std::size_t>(depth_width) * depth_height, vpColVector(3, 0.0));
    for (int i = 0; i < depth.depth.rows; ++i) {
      const float* row = depth.depth.ptr<float>(i);
      for (int j = 0; j < depth.depth.cols; ++j) {
        vpColVector& point = point_cloud[static_cast<std::size_t>(i) * depth_width + j];
        const double Z = row[j];
        if (Z > 0.0) {
          const Eigen::Vector3d X = depth.intrinsics.back_project<double>(j, i, Z);
          point[0] = X.x();
          point[1] = X.y();
          point[2] = X.z();
        } else {
          point = 0.0;
        }
      }
    }
  }

  cv::Mat grey_mat_;
};

namespace detail {

/// Drops what is written to std::cout while alive: ViSP's .cao parser lists the counts of
/// what it read there even when not asked to be verbose, which would interleave with the
/// caller's output once per tracker. Its errors still arrive as exceptions and on std::cerr.
class StdoutSilencer {
 private:
  StandardStreamCapture dropped_{std::cout};
};

}  // namespace detail

/// Which of ViSP's tracker types a program gives its colour camera (kColorCamera, with
/// EDGE_TRACKER and/or KLT_TRACKER) and its depth camera (kDepthCamera, with
/// DEPTH_DENSE_TRACKER and/or DEPTH_NORMAL_TRACKER); 0 leaves that camera out. The colour
/// camera is the reference camera when it is used, else the depth camera.
struct VispCameraTypes {
  int color = 0;
  int depth = 0;

  /// The cameras and their types, in the form vpMbGenericTracker's constructor takes.
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    if (color) out.push_back(kColorCamera);
    if (depth) out.push_back(kDepthCamera);
    return out;
  }
  std::vector<int> types() const {
    std::vector<int> out;
    if (color) out.push_back(color);
    if (depth) out.push_back(depth);
    return out;
  }
};

/// A tracker driven as a ViSP program of the cameras `types` drives it, using only calls that
/// vpMbGenericTracker and vpMbIcgTracker share with identical signatures: start() loads the
/// model for each camera, sets the cameras of the first frame (the depth camera at
/// depth_M_color) and calls initFromPose at the colour camera's pose on the first frame's
/// grey image; track() calls track() with the colour camera's grey image (`colour`: its
/// RGBa image) and the depth camera's organised point cloud, then getPose(). Poses given
/// and returned are the colour camera's, whichever camera is the reference.
///
/// The tracker's own parameters are the caller's business and must be set before (a ViSP
/// XML with loadConfigFile, icgp's YAML or setTrackerConfig): the cameras set here override
/// the camera blocks of those files, so both trackers see the calibration of the frames.
/// Both trackers run OpenMP / OpenCV loops: limit threads around a run for timings
/// comparable with a single-threaded tracker.
template <class TrackerT>
class VispProgram {
 public:
  VispProgram(TrackerT& tracker, const VispModelFiles& files, const VispCameraTypes& types, bool colour = false)
      : tracker_(tracker), files_(files), types_(types), colour_(colour && types.color) {}
  // track() hands ViSP pointers into this object's own buffers.
  VispProgram(const VispProgram&) = delete;
  VispProgram& operator=(const VispProgram&) = delete;

  void start(const Frame& first, const Pose& color_T_body) {
    const bool with_depth = types_.depth != 0;
    input_.convert(first, with_depth);
    // The depth camera's pose from the colour camera's, and back: a tracker without the
    // colour camera gives and takes the depth camera's.
    const vpHomogeneousMatrix depth_M_color =
        with_depth ? to_homogeneous_matrix(first.depths.front().camera_T_reference) : vpHomogeneousMatrix();
    reference_M_color_ = types_.color ? vpHomogeneousMatrix() : depth_M_color;
    std::map<std::string, std::string> models;
    std::map<std::string, vpCameraParameters> cameras;
    std::map<std::string, vpHomogeneousMatrix> camera_M_reference;
    if (types_.color) {
      models[kColorCamera] = files_.model;
      cameras[kColorCamera] = to_camera_parameters(first.colors.front().intrinsics);
      camera_M_reference[kColorCamera] = vpHomogeneousMatrix();
    }
    if (with_depth) {
      models[kDepthCamera] = files_.model;
      cameras[kDepthCamera] = to_camera_parameters(first.depths.front().intrinsics);
      camera_M_reference[kDepthCamera] = depth_M_color * reference_M_color_.inverse();
    }
    {
      const detail::StdoutSilencer quiet_parser;
      tracker_.loadModel(models);
    }
    tracker_.setCameraParameters(cameras);
    tracker_.setCameraTransformationMatrix(camera_M_reference);
    // A depth camera alone still takes an image of its size: its depth features read only that.
    if (!types_.color)
      depth_sized_.resize(static_cast<unsigned int>(first.depths.front().depth.rows),
                          static_cast<unsigned int>(first.depths.front().depth.cols), 0);
    tracker_.initFromPose(reference_image(), reference_M_color_ * to_homogeneous_matrix(color_T_body));
    images_ = {{types_.color ? kColorCamera : kDepthCamera, &reference_image()}};
  }

  TrackedFrame track(const Frame& frame) {
    using Clock = std::chrono::steady_clock;
    const auto ms_between = [](Clock::time_point a, Clock::time_point b) {
      return std::chrono::duration<double, std::milli>(b - a).count();
    };
    const bool with_depth = types_.depth != 0;
    const auto begin = Clock::now();
    input_.convert(frame, with_depth);
    widths_[kDepthCamera] = input_.depth_width;
    heights_[kDepthCamera] = input_.depth_height;
    if (colour_) {
      const cv::Mat& image = frame.colors.front().image;
      if (image.channels() == 1) cv::cvtColor(image, bgr_, cv::COLOR_GRAY2BGR);
      to_vp_image(image.channels() == 1 ? bgr_ : image, rgba_);
    }
    const auto converted = Clock::now();
    if (colour_ && with_depth)
      tracker_.track(colour_images_, clouds_, widths_, heights_);
    else if (colour_)
      tracker_.track(colour_images_);
    else if (with_depth)
      tracker_.track(images_, clouds_, widths_, heights_);
    else
      tracker_.track(images_);
    const auto tracked = Clock::now();
    vpHomogeneousMatrix cMo;
    tracker_.getPose(cMo);
    convert_ms_.push_back(ms_between(begin, converted));
    TrackedFrame outcome;
    outcome.reference_T_body = to_pose(reference_M_color_.inverse() * cMo);
    outcome.ms = ms_between(converted, tracked);
    return outcome;
  }

  /// This program as run_sequence drives it.
  RunTracker as_run_tracker() {
    return {[this](const Frame& first, const Pose& pose) { start(first, pose); },
            [this](const Frame& frame) { return track(frame); }};
  }

  /// Building the grey image and the point cloud (the RGBa image too), per frame tracked.
  const std::vector<double>& convert_ms() const { return convert_ms_; }

 private:
  const vpImage<unsigned char>& reference_image() const { return types_.color ? input_.grey : depth_sized_; }

  TrackerT& tracker_;
  VispModelFiles files_;
  VispCameraTypes types_;
  bool colour_;
  VispRgbdFrame input_;
  vpHomogeneousMatrix reference_M_color_;
  vpImage<unsigned char> depth_sized_;
  vpImage<vpRGBa> rgba_;
  cv::Mat bgr_;
  // What track() is given, in ViSP's shapes, kept from frame to frame.
  std::map<std::string, const vpImage<unsigned char>*> images_;
  std::map<std::string, const vpImage<vpRGBa>*> colour_images_{{kColorCamera, &rgba_}};
  std::map<std::string, const std::vector<vpColVector>*> clouds_{{kDepthCamera, &input_.point_cloud}};
  std::map<std::string, unsigned int> widths_, heights_;
  std::vector<double> convert_ms_;
};

/// A run of track_visp_sequence, one entry per frame.
struct RgbdRun {
  std::vector<Pose> poses;         ///< cMo (getPose) after the frame
  std::vector<double> track_ms;    ///< the track() call alone
  std::vector<double> convert_ms;  ///< building the grey image and the point cloud
};

/// Runs `frames` through VispProgram from the colour camera's pose `cMo0` on the first
/// frame (run_sequence), keeping every frame's pose and times.
template <class TrackerT>
RgbdRun track_visp_sequence(TrackerT& tracker, const std::vector<Frame>& frames, const VispModelFiles& files,
                            const vpHomogeneousMatrix& cMo0, const VispCameraTypes& types, bool colour = false) {
  VispProgram<TrackerT> program(tracker, files, types, colour);
  RgbdRun run;
  run_sequence(FrameSource::of(frames), program.as_run_tracker(), to_pose(cMo0),
               [&](const Frame&, const TrackedFrame& outcome) {
                 run.poses.push_back(outcome.reference_T_body);
                 run.track_ms.push_back(outcome.ms);
               });
  run.convert_ms = program.convert_ms();
  return run;
}

/// The cameras of ViSP's RGB-D programs (kRgbdTrackerTypes).
inline const VispCameraTypes kRgbdCameraTypes{kRgbdTrackerTypes[0], kRgbdTrackerTypes[1]};

/// Tracks `frames` as a ViSP RGB-D program does (track_visp_sequence with kRgbdCameraTypes):
/// colour camera "Camera1" as reference with its grey image, depth camera "Camera2" with
/// its organised point cloud.
template <class TrackerT>
RgbdRun track_rgbd_sequence(TrackerT& tracker, const std::vector<Frame>& frames, const VispModelFiles& files,
                            const vpHomogeneousMatrix& cMo0) {
  return track_visp_sequence(tracker, frames, files, cMo0, kRgbdCameraTypes);
}

}  // namespace icgp
