// SPDX-License-Identifier: GPL-2.0-or-later
//! \example realsense_cube.cpp
//! RGB-D model-based tracking of real Intel RealSense frames (ViSP's generic-rgbd tutorial
//! data: color_image_%04d.jpg, depth_image_%04d.bin) of a 42 mm cube: colour camera
//! "Camera1" (edges + KLT) and depth camera "Camera2" (dense depth), settings from the
//! tutorial's .xml files, the model loaded as .wrl for the colour camera and .cao for the
//! depth camera, initialised from a saved pose, testTracking() after every frame. There is
//! no ground truth: prints the final pose and saves it (4x4) for comparison.
//!
//! Written against vpMbGenericTracker's API only: TRACKER_HEADER / TRACKER_CLASS name the
//! tracker class (vpMbGenericTracker or a drop-in replacement) at compile time.
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <visp3/core/vpImageConvert.h>

#include "program_support.h"

#ifndef TRACKER_HEADER
#define TRACKER_HEADER <visp3/mbt/vpMbGenericTracker.h>
#define TRACKER_CLASS vpMbGenericTracker
#endif
#include TRACKER_HEADER

typedef TRACKER_CLASS Tracker;

namespace
{
//! Reads frame `cpt`: the colour image converted to grey, and the raw depth (uint32 height,
//! uint32 width, then height x width uint16 in mm, little endian) as a point cloud in the
//! depth camera's frame (0: no measurement).
bool read_data(unsigned int cpt, const std::string &input_directory, const vpCameraParameters &cam_depth,
               vpImage<unsigned char> &I, vpImage<uint16_t> &I_depth_raw, std::vector<vpColVector> &pointcloud)
{
  std::string filename_color = program::numbered(input_directory + "/color_image_%04d.jpg", cpt);
  if (!vpIoTools::checkFilename(filename_color)) {
    return false;
  }
  vpImage<vpRGBa> I_color;
  vpImageIo::read(I_color, filename_color);
  vpImageConvert::convert(I_color, I);

  std::string filename_depth = program::numbered(input_directory + "/depth_image_%04d.bin", cpt);
  std::ifstream file_depth(filename_depth.c_str(), std::ios::in | std::ios::binary);
  if (!file_depth.is_open()) {
    std::cerr << "Cannot read: " << filename_depth << std::endl;
    return false;
  }
  unsigned int height = 0, width = 0;
  vpIoTools::readBinaryValueLE(file_depth, height);
  vpIoTools::readBinaryValueLE(file_depth, width);
  I_depth_raw.resize(height, width);
  uint16_t depth_value = 0;
  for (unsigned int i = 0; i < height; i++) {
    for (unsigned int j = 0; j < width; j++) {
      vpIoTools::readBinaryValueLE(file_depth, depth_value);
      I_depth_raw[i][j] = depth_value;
    }
  }
  if (!file_depth) {
    std::cerr << "Truncated depth file: " << filename_depth << std::endl;
    return false;
  }

  const double depth_scale = 0.001;
  program::to_point_cloud(
      height, width, cam_depth,
      [&I_depth_raw, depth_scale](unsigned int i, unsigned int j) { return I_depth_raw[i][j] * depth_scale; },
      pointcloud);
  return true;
}
} // namespace

int main(int argc, char *argv[])
{
  std::string input_directory = ".";
  std::string config_color = "model/cube/cube.xml", config_depth = "model/cube/cube_depth.xml";
  std::string model_color = "model/cube/cube.wrl", model_depth = "model/cube/cube.cao";
  std::string init_pose_file = "cube_init_cMo.txt";
  std::string final_pose_file;
  unsigned int first_frame = 0, nb_frames = 0; // 0: to the end of the sequence
  // As ViSP's RealSense tutorial (tutorial-mb-generic-tracker-rgbd-realsense): which features
  // the colour camera tracks, and whether the depth camera is used at all.
  unsigned int use_edges = 1, use_klt = 1, use_depth = 1;
  unsigned int min_klt_points = 0; // fail on a frame with fewer KLT points (getNbFeaturesKlt() / 2)

  if (!program::Options()
           .add("--input_directory", input_directory)
           .add("--config_color", config_color)
           .add("--config_depth", config_depth)
           .add("--model_color", model_color)
           .add("--model_depth", model_depth)
           .add("--init_pose", init_pose_file)
           .add("--final_pose", final_pose_file)
           .add("--frames", nb_frames)
           .add("--use_edges", use_edges)
           .add("--use_klt", use_klt)
           .add("--use_depth", use_depth)
           .add("--min_klt_points", min_klt_points)
           .parse(argc, argv,
                  "[--input_directory <folder of color_image_%04d.jpg, depth_image_%04d.bin, depth_M_color.txt>]"
                  " [--config_color <cube.xml>] [--config_depth <cube_depth.xml>]"
                  " [--model_color <cube.wrl>] [--model_depth <cube.cao>] [--init_pose <cMo 4x4 file>]"
                  " [--frames <n> (default: all)] [--final_pose <output file>]"
                  " [--use_edges <0|1>] [--use_klt <0|1>] [--use_depth <0|1>] [--min_klt_points <n>]"))
    return EXIT_SUCCESS;

  std::cout << "Tracker: " << VP_STRINGIFY(TRACKER_CLASS) << std::endl;
  std::cout << "input_directory: " << input_directory << std::endl;
  std::cout << "config: " << config_color << ", " << config_depth << std::endl;
  std::cout << "model: " << model_color << ", " << model_depth << std::endl;

  if (!use_edges && !use_klt) {
    std::cerr << "The colour camera needs edges or KLT (--use_edges 1 or --use_klt 1)" << std::endl;
    return EXIT_FAILURE;
  }
  return program::run([&] {
    std::vector<int> trackerTypes;
    trackerTypes.push_back((use_edges ? Tracker::EDGE_TRACKER : 0) | (use_klt ? Tracker::KLT_TRACKER : 0));
    if (use_depth)
      trackerTypes.push_back(Tracker::DEPTH_DENSE_TRACKER);
    Tracker tracker(trackerTypes);
    if (use_depth) {
      tracker.loadConfigFile(config_color, config_depth);
      tracker.loadModel(model_color, model_depth);
    } else {
      tracker.loadConfigFile(config_color);
      tracker.loadModel(model_color);
    }
    std::cout << "Model: " << tracker.getNbPolygon() << " faces" << std::endl;

    vpCameraParameters cam_color, cam_depth;
    if (use_depth) {
      tracker.getCameraParameters(cam_color, cam_depth);
      vpHomogeneousMatrix depth_M_color;
      if (!program::set_rgbd_transformations(tracker, input_directory, depth_M_color))
        return EXIT_FAILURE;
    } else {
      tracker.getCameraParameters(cam_color);
      cam_depth = cam_color; // the frames' clouds are read, and not used
    }
    std::cout << "cam_color:\n" << cam_color << std::endl;
    std::cout << "cam_depth:\n" << cam_depth << std::endl;

    vpHomogeneousMatrix cMo_init;
    if (!program::read_matrix(init_pose_file, cMo_init))
      return EXIT_FAILURE;

    vpImage<unsigned char> I;
    vpImage<uint16_t> I_depth_raw;
    std::vector<vpColVector> pointcloud;
    if (!read_data(first_frame, input_directory, cam_depth, I, I_depth_raw, pointcloud)) {
      std::cerr << "Cannot read the first frame in " << input_directory << std::endl;
      return EXIT_FAILURE;
    }
    tracker.initFromPose(I, cMo_init);

    vpHomogeneousMatrix cMo;
    unsigned int nb_tracked = 0;
    for (unsigned int frame = first_frame; nb_frames == 0 || frame < first_frame + nb_frames; frame++) {
      if (!read_data(frame, input_directory, cam_depth, I, I_depth_raw, pointcloud)) {
        break;
      }
      std::map<std::string, const vpImage<unsigned char> *> mapOfImages;
      std::map<std::string, const std::vector<vpColVector> *> mapOfPointClouds;
      std::map<std::string, unsigned int> mapOfPointCloudWidths;
      std::map<std::string, unsigned int> mapOfPointCloudHeights;
      if (use_depth) {
        mapOfImages["Camera1"] = &I;
        mapOfPointClouds["Camera2"] = &pointcloud;
        mapOfPointCloudWidths["Camera2"] = I_depth_raw.getWidth();
        mapOfPointCloudHeights["Camera2"] = I_depth_raw.getHeight();
        tracker.track(mapOfImages, mapOfPointClouds, mapOfPointCloudWidths, mapOfPointCloudHeights);
      } else {
        tracker.track(I);
      }
      tracker.testTracking();

      tracker.getPose(cMo);
      nb_tracked++;
      std::cout << "Frame " << frame << ": t = " << cMo.getTranslationVector().t() << " m, tu = "
                << vpThetaUVector(cMo.getRotationMatrix()).t() << " rad; features: edge "
                << tracker.getNbFeaturesEdge() << ", klt " << tracker.getNbFeaturesKlt() << ", depth "
                << tracker.getNbFeaturesDepthDense() << std::endl;
      if (use_klt && tracker.getNbFeaturesKlt() / 2 < min_klt_points) {
        std::cerr << "Frame " << frame << ": " << tracker.getNbFeaturesKlt() / 2 << " KLT points, fewer than "
                  << min_klt_points << std::endl;
        return EXIT_FAILURE;
      }
    }
    if (nb_tracked == 0) {
      std::cerr << "No frame tracked" << std::endl;
      return EXIT_FAILURE;
    }

    std::cout << VP_STRINGIFY(TRACKER_CLASS) << " tracked " << nb_tracked << " frames; final cMo:\n"
              << cMo << std::endl;
    if (!final_pose_file.empty()) {
      std::ofstream f(final_pose_file.c_str());
      f.precision(12);
      cMo.save(f);
    }
    return EXIT_SUCCESS;
  });
}
