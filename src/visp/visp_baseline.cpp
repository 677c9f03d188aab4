// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/visp/visp_baseline.h"

#include <chrono>
#include <filesystem>
#include <iostream>
#include <map>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImage.h>
#include <visp3/mbt/vpMbGenericTracker.h>

#include "icgp/visp/conversions.h"

namespace icgp {

namespace {

const std::string kColorCamera = "Camera1";
const std::string kDepthCamera = "Camera2";

int color_tracker_types(const VispTrackerConfiguration& c) {
  return (c.edge ? vpMbGenericTracker::EDGE_TRACKER : 0) | (c.klt ? vpMbGenericTracker::KLT_TRACKER : 0);
}

void require_cameras(const Frame& frame, bool depth) {
  if (frame.colors.empty()) throw std::invalid_argument("frame " + std::to_string(frame.index) + " has no colour image");
  if (depth && frame.depths.empty())
    throw std::invalid_argument("frame " + std::to_string(frame.index) + " has no depth image");
}

/// Drops what is written to std::cout while alive: ViSP's .cao parser lists the counts of
/// what it read there even when not asked to be verbose, which would interleave with the
/// caller's output once per tracker. Its errors still arrive as exceptions and on std::cerr.
class StdoutSilencer {
 public:
  StdoutSilencer() : previous_(std::cout.rdbuf(nullptr)) {}
  ~StdoutSilencer() { std::cout.rdbuf(previous_); }
  StdoutSilencer(const StdoutSilencer&) = delete;
  StdoutSilencer& operator=(const StdoutSilencer&) = delete;

 private:
  std::streambuf* previous_;
};

}  // namespace

std::vector<VispTrackerConfiguration> visp_reference_configurations() {
  return {{"edge + dense depth", true, false, true},
          {"KLT + dense depth", false, true, true},
          {"edge + KLT + dense depth", true, true, true},
          {"edge + KLT (no depth)", true, true, false}};
}

VispModelFiles VispModelFiles::beside_model(const std::string& cao_path) {
  namespace fs = std::filesystem;
  const fs::path model(cao_path);
  const fs::path stem = model.parent_path() / model.stem();
  VispModelFiles files{cao_path, stem.string() + ".xml", stem.string() + "_depth.xml"};
  for (const std::string* file : {&files.model, &files.color_config, &files.depth_config})
    if (!fs::is_regular_file(*file)) throw std::runtime_error(*file + ": missing ViSP model or tracker settings file");
  return files;
}

/// The frame in the shapes vpMbGenericTracker takes, reused from frame to frame.
struct VispRgbdTracker::Buffers {
  cv::Mat gray;
  vpImage<unsigned char> color_image;
  /// Depth-camera-sized image: vpMbGenericTracker wants an image per camera at
  /// initialisation, and the dense depth tracker only takes its size.
  vpImage<unsigned char> depth_image;
  std::vector<vpColVector> point_cloud;  ///< w*h, row-major, X Y Z in the depth frame, 0 = none
  unsigned int depth_width = 0, depth_height = 0;
};

VispRgbdTracker::VispRgbdTracker(const VispTrackerConfiguration& configuration, const VispModelFiles& files)
    : configuration_(configuration), buffers_(std::make_unique<Buffers>()) {
  if (!configuration.edge && !configuration.klt && !configuration.dense_depth)
    throw std::invalid_argument("ViSP configuration '" + configuration.name + "' uses no feature");
  if (!configuration.edge && !configuration.klt)
    throw std::invalid_argument("ViSP configuration '" + configuration.name +
                                "' has no colour feature: the colour camera is the reference camera");

  std::vector<std::string> cameras = {kColorCamera};
  std::vector<int> types = {color_tracker_types(configuration)};
  std::map<std::string, std::string> settings = {{kColorCamera, files.color_config}};
  std::map<std::string, std::string> models = {{kColorCamera, files.model}};
  if (configuration.dense_depth) {
    cameras.push_back(kDepthCamera);
    types.push_back(vpMbGenericTracker::DEPTH_DENSE_TRACKER);
    settings[kDepthCamera] = files.depth_config;
    models[kDepthCamera] = files.model;
  }
  tracker_ = std::make_unique<vpMbGenericTracker>(cameras, types);
  tracker_->loadConfigFile(settings, false);
  const StdoutSilencer quiet_parser;
  tracker_->loadModel(models);
}

VispRgbdTracker::~VispRgbdTracker() = default;

void VispRgbdTracker::convert(const Frame& frame) {
  require_cameras(frame, configuration_.dense_depth);
  const cv::Mat& color = frame.colors[0].image;
  if (color.channels() == 1) {
    to_vp_image(color, buffers_->color_image);
  } else {
    cv::cvtColor(color, buffers_->gray, cv::COLOR_BGR2GRAY);
    to_vp_image(buffers_->gray, buffers_->color_image);
  }
  if (!configuration_.dense_depth) return;

  const DepthImage& depth = frame.depths[0];
  Buffers& b = *buffers_;
  b.depth_width = static_cast<unsigned int>(depth.depth.cols);
  b.depth_height = static_cast<unsigned int>(depth.depth.rows);
  b.depth_image.resize(b.depth_height, b.depth_width, 0);
  b.point_cloud.resize(static_cast<std::size_t>(b.depth_width) * b.depth_height, vpColVector(3, 0.0));
  for (int i = 0; i < depth.depth.rows; ++i) {
    const float* row = depth.depth.ptr<float>(i);
    for (int j = 0; j < depth.depth.cols; ++j) {
      vpColVector& point = b.point_cloud[static_cast<std::size_t>(i) * b.depth_width + j];
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

void VispRgbdTracker::start(const Frame& frame, const Pose& reference_T_body) {
  convert(frame);
  std::map<std::string, vpCameraParameters> cameras = {{kColorCamera, to_camera_parameters(frame.colors[0].intrinsics)}};
  std::map<std::string, const vpImage<unsigned char>*> images = {{kColorCamera, &buffers_->color_image}};
  if (configuration_.dense_depth) {
    const DepthImage& depth = frame.depths[0];
    cameras[kDepthCamera] = to_camera_parameters(depth.intrinsics);
    images[kDepthCamera] = &buffers_->depth_image;
    // Camera2's pose is derived by ViSP from the reference pose and this, as for a user.
    tracker_->setCameraTransformationMatrix(kDepthCamera, to_homogeneous_matrix(depth.camera_T_reference));
  }
  tracker_->setCameraParameters(cameras);
  tracker_->initFromPose(images, std::map<std::string, vpHomogeneousMatrix>{
                                     {kColorCamera, to_homogeneous_matrix(reference_T_body)}});
}

Pose VispRgbdTracker::track(const Frame& frame, double* track_ms) {
  convert(frame);
  std::map<std::string, const vpImage<unsigned char>*> images = {{kColorCamera, &buffers_->color_image}};
  std::map<std::string, const std::vector<vpColVector>*> clouds;
  std::map<std::string, unsigned int> widths, heights;
  if (configuration_.dense_depth) {
    clouds[kDepthCamera] = &buffers_->point_cloud;
    widths[kDepthCamera] = buffers_->depth_width;
    heights[kDepthCamera] = buffers_->depth_height;
  }
  const auto begin = std::chrono::steady_clock::now();
  tracker_->track(images, clouds, widths, heights);
  const auto end = std::chrono::steady_clock::now();
  if (track_ms) *track_ms = std::chrono::duration<double, std::milli>(end - begin).count();
  return to_pose(tracker_->getPose());
}

VispBaselineRun run_visp_baseline(const std::vector<Frame>& frames, const VispTrackerConfiguration& configuration,
                                  const VispModelFiles& files, const Pose& reference_T_body) {
  VispBaselineRun run;
  if (frames.empty()) return run;
  VispRgbdTracker tracker(configuration, files);
  tracker.start(frames.front(), reference_T_body);
  for (const Frame& frame : frames) {
    double ms = 0.0;
    run.poses.push_back(tracker.track(frame, &ms));
    run.ms.push_back(ms);
  }
  return run;
}

}  // namespace icgp
