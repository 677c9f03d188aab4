// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/visp/visp_baseline.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpImage.h>
#include <visp3/mbt/vpMbGenericTracker.h>

#include "icgp/base/camera_names.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/cao_writer.h"
#include "icgp/visp/conversions.h"
#include "icgp/visp/rgbd_tracking_loop.h"

namespace icgp {

namespace {

namespace fs = std::filesystem;

int color_tracker_types(const VispTrackerConfiguration& c) {
  return (c.edge ? vpMbGenericTracker::EDGE_TRACKER : 0) | (c.klt ? vpMbGenericTracker::KLT_TRACKER : 0);
}

/// ViSP's settings for the edge, KLT and dense-depth features: those of its teabox
/// tutorial, which suit objects of 5-20 cm at half a metre. The cameras come from the
/// frames or the caller, not from these files.
std::string visp_settings(const std::string& features) {
  return "<?xml version=\"1.0\"?>\n<conf>\n" + features +
         "  <face>\n"
         "    <angle_appear>70</angle_appear><angle_disappear>80</angle_disappear>\n"
         "    <near_clipping>0.1</near_clipping><far_clipping>100</far_clipping><fov_clipping>1</fov_clipping>\n"
         "  </face>\n</conf>\n";
}
const std::string kColorFeatures = R"(  <ecm>
    <mask><size>5</size><nb_mask>180</nb_mask></mask>
    <range><tracking>8</tracking></range>
    <contrast><edge_threshold>10000</edge_threshold><mu1>0.5</mu1><mu2>0.5</mu2></contrast>
    <sample><step>4</step></sample>
  </ecm>
  <klt>
    <mask_border>5</mask_border><max_features>300</max_features><window_size>5</window_size>
    <quality>0.015</quality><min_distance>8</min_distance><harris>0.01</harris>
    <size_block>3</size_block><pyramid_lvl>3</pyramid_lvl>
  </klt>
)";
const std::string kDepthFeatures =
    "  <depth_dense><sampling_step><step_X>4</step_X><step_Y>4</step_Y></sampling_step></depth_dense>\n";

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error(path.string() + ": cannot write ViSP's tracker settings");
}

}  // namespace

std::vector<VispTrackerConfiguration> visp_reference_configurations() {
  return {{"edge + dense depth", true, false, true},
          {"KLT + dense depth", false, true, true},
          {"edge + KLT + dense depth", true, true, true},
          {"edge + KLT (no depth)", true, true, false}};
}

VispTrackerConfiguration visp_reference_configuration(const std::string& name) {
  for (const VispTrackerConfiguration& configuration : visp_reference_configurations())
    if (configuration.name == name) return configuration;
  throw std::invalid_argument("no ViSP reference configuration is called '" + name + "'");
}

VispModelFiles VispModelFiles::beside_model(const std::string& cao_path) {
  const fs::path model(cao_path);
  const fs::path stem = model.parent_path() / model.stem();
  VispModelFiles files{cao_path, stem.string() + ".xml", stem.string() + "_depth.xml"};
  for (const std::string* file : {&files.model, &files.color_config, &files.depth_config})
    if (!fs::is_regular_file(*file)) throw std::runtime_error(*file + ": missing ViSP model or tracker settings file");
  return files;
}

VispModelFiles VispModelFiles::written_for_mesh(const std::string& mesh_path, const std::string& dir) {
  fs::create_directories(dir);
  const fs::path folder(dir);
  VispModelFiles files{(folder / "model.cao").string(), (folder / "model.xml").string(),
                       (folder / "model_depth.xml").string()};
  write_cao(load_any_mesh(mesh_path), files.model);
  write_text(files.color_config, visp_settings(kColorFeatures));
  write_text(files.depth_config, visp_settings(kDepthFeatures));
  return files;
}

std::unique_ptr<vpMbGenericTracker> make_visp_tracker(const VispTrackerConfiguration& configuration,
                                                      const VispModelFiles& files) {
  if (!configuration.edge && !configuration.klt && !configuration.dense_depth)
    throw std::invalid_argument("ViSP configuration '" + configuration.name + "' uses no feature");
  if (!configuration.edge && !configuration.klt)
    throw std::invalid_argument("ViSP configuration '" + configuration.name +
                                "' has no colour feature: the colour camera is the reference camera");

  std::vector<std::string> cameras = {kColorCamera};
  std::vector<int> types = {color_tracker_types(configuration)};
  std::map<std::string, std::string> settings = {{kColorCamera, files.color_config}};
  if (configuration.dense_depth) {
    cameras.push_back(kDepthCamera);
    types.push_back(vpMbGenericTracker::DEPTH_DENSE_TRACKER);
    settings[kDepthCamera] = files.depth_config;
  }
  auto tracker = std::make_unique<vpMbGenericTracker>(cameras, types);
  tracker->loadConfigFile(settings, false);
  return tracker;
}

/// The frame in the shapes vpMbGenericTracker takes, reused from frame to frame.
struct VispRgbdTracker::Buffers {
  VispRgbdFrame frame;
  /// Depth-camera-sized image: vpMbGenericTracker wants an image per camera at
  /// initialisation, and the dense depth tracker only takes its size.
  vpImage<unsigned char> depth_image;
};

VispRgbdTracker::VispRgbdTracker(const VispTrackerConfiguration& configuration, const VispModelFiles& files)
    : configuration_(configuration),
      tracker_(make_visp_tracker(configuration, files)),
      buffers_(std::make_unique<Buffers>()) {
  std::map<std::string, std::string> models = {{kColorCamera, files.model}};
  if (configuration.dense_depth) models[kDepthCamera] = files.model;
  const detail::StdoutSilencer quiet_parser;
  tracker_->loadModel(models);
}

VispRgbdTracker::~VispRgbdTracker() = default;

void VispRgbdTracker::convert(const Frame& frame) { buffers_->frame.convert(frame, configuration_.dense_depth); }

void VispRgbdTracker::start(const Frame& frame, const Pose& reference_T_body) {
  convert(frame);
  std::map<std::string, vpCameraParameters> cameras = {
      {kColorCamera, to_camera_parameters(frame.colors[0].intrinsics)}};
  std::map<std::string, const vpImage<unsigned char>*> images = {{kColorCamera, &buffers_->frame.grey}};
  if (configuration_.dense_depth) {
    const DepthImage& depth = frame.depths[0];
    cameras[kDepthCamera] = to_camera_parameters(depth.intrinsics);
    buffers_->depth_image.resize(buffers_->frame.depth_height, buffers_->frame.depth_width, 0);
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
  std::map<std::string, const vpImage<unsigned char>*> images = {{kColorCamera, &buffers_->frame.grey}};
  std::map<std::string, const std::vector<vpColVector>*> clouds;
  std::map<std::string, unsigned int> widths, heights;
  if (configuration_.dense_depth) {
    clouds[kDepthCamera] = &buffers_->frame.point_cloud;
    widths[kDepthCamera] = buffers_->frame.depth_width;
    heights[kDepthCamera] = buffers_->frame.depth_height;
  }
  const auto begin = std::chrono::steady_clock::now();
  tracker_->track(images, clouds, widths, heights);
  const auto end = std::chrono::steady_clock::now();
  if (track_ms) *track_ms = std::chrono::duration<double, std::milli>(end - begin).count();
  return to_pose(tracker_->getPose());
}

RunTracker VispRgbdTracker::as_run_tracker() {
  return {[this](const Frame& frame, const Pose& pose) {
            start(frame, pose);
            last_ = pose;
          },
          [this](const Frame& frame) {
            TrackedFrame outcome;
            const auto begin = std::chrono::steady_clock::now();
            try {
              last_ = track(frame, &outcome.ms);
            } catch (const vpException&) {
              outcome.tracked = false;
              outcome.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
            }
            outcome.reference_T_body = last_;
            return outcome;
          }};
}

}  // namespace icgp
