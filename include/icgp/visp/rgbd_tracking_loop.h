// SPDX-License-Identifier: GPL-2.0-or-later
// One RGB-D tracking loop written against ViSP's API alone, for any tracker that has
// vpMbGenericTracker's two-camera calls. vpMbGenericTracker and vpMbIcgTracker run through
// literally the same code, so whatever differs in their results comes from the trackers:
// this is what "drop-in replacement" means in numbers.
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

/// A run of track_rgbd_sequence, one entry per frame.
struct RgbdRun {
  std::vector<Pose> poses;         ///< cMo (getPose) after the frame
  std::vector<double> track_ms;    ///< the track() call alone
  std::vector<double> convert_ms;  ///< building the grey image and the point cloud
};

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

/// Tracks `frames` as a ViSP program of the cameras `types` does, using only calls that
/// vpMbGenericTracker and vpMbIcgTracker share with identical signatures: the model for each
/// camera, the cameras of the first frame (the depth camera at depth_M_color), initFromPose
/// at `cMo0` (the colour camera's pose) on the first frame's grey image, then per frame
/// track() with the colour camera's grey image (`colour`: its RGBa image) and the depth
/// camera's organised point cloud, and getPose(). The poses returned are the colour
/// camera's, whichever camera is the reference.
///
/// The tracker's own parameters are the caller's business and must be set before (a ViSP
/// XML with loadConfigFile, icgp's YAML or setTrackerConfig): the cameras set here override
/// the camera blocks of those files, so both trackers see the calibration of the frames.
/// Both trackers run OpenMP / OpenCV loops: limit threads around this call for timings
/// comparable with a single-threaded tracker.
template <class TrackerT>
RgbdRun track_visp_sequence(TrackerT& tracker, const std::vector<Frame>& frames, const VispModelFiles& files,
                            const vpHomogeneousMatrix& cMo0, const VispCameraTypes& types, bool colour = false) {
  using Clock = std::chrono::steady_clock;
  const auto ms_between = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };

  RgbdRun run;
  if (frames.empty()) return run;
  const bool with_depth = types.depth != 0;
  VispRgbdFrame input;
  input.convert(frames.front(), with_depth);
  // The depth camera's pose from the colour camera's, and back: a tracker without the
  // colour camera gives and takes the depth camera's.
  const vpHomogeneousMatrix depth_M_color =
      with_depth ? to_homogeneous_matrix(frames.front().depths.front().camera_T_reference) : vpHomogeneousMatrix();
  const vpHomogeneousMatrix reference_M_color = types.color ? vpHomogeneousMatrix() : depth_M_color;
  std::map<std::string, std::string> models;
  std::map<std::string, vpCameraParameters> cameras;
  std::map<std::string, vpHomogeneousMatrix> camera_M_reference;
  if (types.color) {
    models[kColorCamera] = files.model;
    cameras[kColorCamera] = to_camera_parameters(frames.front().colors.front().intrinsics);
    camera_M_reference[kColorCamera] = vpHomogeneousMatrix();
  }
  if (with_depth) {
    models[kDepthCamera] = files.model;
    cameras[kDepthCamera] = to_camera_parameters(frames.front().depths.front().intrinsics);
    camera_M_reference[kDepthCamera] = depth_M_color * reference_M_color.inverse();
  }
  {
    const detail::StdoutSilencer quiet_parser;
    tracker.loadModel(models);
  }
  tracker.setCameraParameters(cameras);
  tracker.setCameraTransformationMatrix(camera_M_reference);
  // A depth camera alone still takes an image of its size: its depth features read only that.
  vpImage<unsigned char> depth_sized;
  if (!types.color)
    depth_sized.resize(static_cast<unsigned int>(frames.front().depths.front().depth.rows),
                       static_cast<unsigned int>(frames.front().depths.front().depth.cols), 0);
  const vpImage<unsigned char>& reference_image = types.color ? input.grey : depth_sized;
  tracker.initFromPose(reference_image, reference_M_color * cMo0);

  vpImage<vpRGBa> rgba;
  cv::Mat bgr;
  std::map<std::string, const vpImage<unsigned char>*> images = {
      {types.color ? kColorCamera : kDepthCamera, &reference_image}};
  std::map<std::string, const vpImage<vpRGBa>*> colour_images = {{kColorCamera, &rgba}};
  std::map<std::string, const std::vector<vpColVector>*> clouds = {{kDepthCamera, &input.point_cloud}};
  std::map<std::string, unsigned int> widths, heights;
  vpHomogeneousMatrix cMo;
  // The first frame is tracked too, as ViSP's tutorials do after initFromPose.
  for (const Frame& frame : frames) {
    const auto begin = Clock::now();
    input.convert(frame, with_depth);
    widths[kDepthCamera] = input.depth_width;
    heights[kDepthCamera] = input.depth_height;
    const bool track_colour = colour && types.color;
    if (track_colour) {
      const cv::Mat& image = frame.colors.front().image;
      if (image.channels() == 1) cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
      to_vp_image(image.channels() == 1 ? bgr : image, rgba);
    }
    const auto converted = Clock::now();
    if (track_colour && with_depth)
      tracker.track(colour_images, clouds, widths, heights);
    else if (track_colour)
      tracker.track(colour_images);
    else if (with_depth)
      tracker.track(images, clouds, widths, heights);
    else
      tracker.track(images);
    const auto tracked = Clock::now();
    tracker.getPose(cMo);
    run.poses.push_back(to_pose(reference_M_color.inverse() * cMo));
    run.convert_ms.push_back(ms_between(begin, converted));
    run.track_ms.push_back(ms_between(converted, tracked));
  }
  return run;
}

/// Tracks `frames` as a ViSP RGB-D program does (track_visp_sequence with kRgbdTrackerTypes):
/// colour camera "Camera1" as reference with its grey image, depth camera "Camera2" with
/// its organised point cloud.
template <class TrackerT>
RgbdRun track_rgbd_sequence(TrackerT& tracker, const std::vector<Frame>& frames, const VispModelFiles& files,
                            const vpHomogeneousMatrix& cMo0) {
  return track_visp_sequence(tracker, frames, files, cMo0, VispCameraTypes{kRgbdTrackerTypes[0], kRgbdTrackerTypes[1]});
}

}  // namespace icgp
