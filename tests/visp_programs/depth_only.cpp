// SPDX-License-Identifier: GPL-2.0-or-later
//! \example depth_only.cpp
//! Depth-only model-based tracking of ViSP's rendered teabox sequence (teabox-blender):
//! one camera "Camera" with the dense depth features, its parameters from
//! teabox_depth.xml, the depth given as a point cloud (std::vector<vpColVector>, one
//! X, Y, Z per pixel). The tracked pose is the depth camera's: initialised from the
//! ground truth of the first frame moved into the depth frame (depth_M_color * cMo),
//! compared with depth_M_color * cMo of every tracked frame.
//!
//! Written against vpMbGenericTracker's API only: TRACKER_HEADER / TRACKER_CLASS name the
//! tracker class (vpMbGenericTracker or a drop-in replacement) at compile time.
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
//! Reads frame `cpt` of the sequence: depth as a depth map and a point cloud in the depth
//! camera's frame, ground truth cMo.
bool read_data(unsigned int cpt, const std::string &input_directory, const vpCameraParameters &cam_depth,
               vpImage<float> &I_depth_raw, std::vector<vpColVector> &pointcloud, vpHomogeneousMatrix &cMo_ground_truth)
{
  if (!program::read_blender_depth(cpt, input_directory, I_depth_raw))
    return false;
  program::to_point_cloud(
      I_depth_raw.getHeight(), I_depth_raw.getWidth(), cam_depth,
      [&I_depth_raw](unsigned int i, unsigned int j) { return static_cast<double>(I_depth_raw[i][j]); }, pointcloud);
  return program::read_blender_truth(cpt, input_directory, cMo_ground_truth);
}
} // namespace

int main(int argc, char *argv[])
{
  program::TeaboxOptions options;
  if (!options.parse(argc, argv))
    return EXIT_SUCCESS;
  const std::string &input_directory = options.input_directory, &errors_file = options.errors_file;
  const unsigned int first_frame = options.first_frame, nb_frames = options.nb_frames;
  const double max_mean_translation_mm = options.max_mean_translation_mm;

  std::cout << "Tracker: " << VP_STRINGIFY(TRACKER_CLASS) << std::endl;
  std::cout << "input_directory: " << input_directory << std::endl;

  return program::run([&] {
    Tracker tracker(1, Tracker::DEPTH_DENSE_TRACKER);
    tracker.loadConfigFile(input_directory + "/teabox_depth.xml");
    tracker.loadModel(input_directory + "/teabox.cao");

    vpCameraParameters cam_depth;
    tracker.getCameraParameters(cam_depth);
    std::cout << "cam_depth:\n" << cam_depth << std::endl;

    vpHomogeneousMatrix depth_M_color;
    if (!program::read_matrix(input_directory + "/depth_M_color.txt", depth_M_color))
      return EXIT_FAILURE;
    std::cout << "depth_M_color:\n" << depth_M_color << std::endl;

    vpImage<float> I_depth_raw;
    vpImage<unsigned char> I_depth;
    std::vector<vpColVector> pointcloud;
    vpHomogeneousMatrix cMo_truth;
    if (!read_data(first_frame, input_directory, cam_depth, I_depth_raw, pointcloud, cMo_truth)) {
      return EXIT_FAILURE;
    }
    vpImageConvert::createDepthHistogram(I_depth_raw, I_depth);
    tracker.initFromPose(I_depth, depth_M_color * cMo_truth);

    program::PoseErrors errors;
    for (unsigned int frame = first_frame; frame < first_frame + nb_frames; frame++) {
      if (!read_data(frame, input_directory, cam_depth, I_depth_raw, pointcloud, cMo_truth)) {
        return EXIT_FAILURE;
      }
      std::map<std::string, const vpImage<unsigned char> *> mapOfImages;
      std::map<std::string, const std::vector<vpColVector> *> mapOfPointClouds;
      std::map<std::string, unsigned int> mapOfPointCloudWidths;
      std::map<std::string, unsigned int> mapOfPointCloudHeights;
      mapOfPointClouds["Camera"] = &pointcloud;
      mapOfPointCloudWidths["Camera"] = I_depth_raw.getWidth();
      mapOfPointCloudHeights["Camera"] = I_depth_raw.getHeight();
      tracker.track(mapOfImages, mapOfPointClouds, mapOfPointCloudWidths, mapOfPointCloudHeights);

      // The depth camera's pose of the teabox, and its ground truth.
      errors.add(frame, tracker.getPose(), depth_M_color * cMo_truth, tracker.getError().size());
    }
    return errors.report(VP_STRINGIFY(TRACKER_CLASS), errors_file, max_mean_translation_mm);
  });
}
