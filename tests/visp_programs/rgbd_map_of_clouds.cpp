// SPDX-License-Identifier: GPL-2.0-or-later
//! \example rgbd_map_of_clouds.cpp
//! RGB-D model-based tracking of ViSP's rendered teabox sequence (teabox-blender) with a
//! colour camera "Camera1" (edges + KLT) and a depth camera "Camera2" (dense depth), the
//! depth given as a point cloud (std::vector<vpColVector>, one X, Y, Z per pixel).
//! Initialised from the ground truth of the first frame; prints the pose errors against
//! the ground truth of every tracked frame.
//!
//! Written against vpMbGenericTracker's API only: TRACKER_HEADER / TRACKER_CLASS name the
//! tracker class (vpMbGenericTracker or a drop-in replacement) at compile time.
#include <map>
#include <string>
#include <vector>

#include "program_support.h"

#ifndef TRACKER_HEADER
#define TRACKER_HEADER <visp3/mbt/vpMbGenericTracker.h>
#define TRACKER_CLASS vpMbGenericTracker
#endif
#include TRACKER_HEADER

typedef TRACKER_CLASS Tracker;

namespace
{
//! Reads frame `cpt` of the sequence: grey image, depth as a point cloud in the depth
//! camera's frame, ground truth cMo.
bool read_data(unsigned int cpt, const std::string &input_directory, const vpCameraParameters &cam_depth,
               vpImage<unsigned char> &I, std::vector<vpColVector> &pointcloud, unsigned int &depth_width,
               unsigned int &depth_height, vpHomogeneousMatrix &cMo_ground_truth)
{
  vpImage<float> depth;
  if (!program::read_blender_image(cpt, input_directory, I) || !program::read_blender_depth(cpt, input_directory, depth))
    return false;
  depth_width = depth.getWidth();
  depth_height = depth.getHeight();
  program::to_point_cloud(depth_height, depth_width, cam_depth,
                          [&depth](unsigned int i, unsigned int j) { return static_cast<double>(depth[i][j]); },
                          pointcloud);
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
    std::vector<int> trackerTypes;
    trackerTypes.push_back(Tracker::EDGE_TRACKER | Tracker::KLT_TRACKER);
    trackerTypes.push_back(Tracker::DEPTH_DENSE_TRACKER);
    Tracker tracker(trackerTypes);

    tracker.loadConfigFile(input_directory + "/teabox.xml", input_directory + "/teabox_depth.xml");
    tracker.loadModel(input_directory + "/teabox.cao", input_directory + "/teabox.cao");

    vpCameraParameters cam_color, cam_depth;
    tracker.getCameraParameters(cam_color, cam_depth);
    std::cout << "cam_color:\n" << cam_color << std::endl;
    std::cout << "cam_depth:\n" << cam_depth << std::endl;

    vpHomogeneousMatrix depth_M_color;
    if (!program::set_rgbd_transformations(tracker, input_directory, depth_M_color))
      return EXIT_FAILURE;
    std::cout << "depth_M_color:\n" << depth_M_color << std::endl;

    vpImage<unsigned char> I;
    std::vector<vpColVector> pointcloud;
    unsigned int depth_width = 0, depth_height = 0;
    vpHomogeneousMatrix cMo_truth;
    if (!read_data(first_frame, input_directory, cam_depth, I, pointcloud, depth_width, depth_height, cMo_truth)) {
      return EXIT_FAILURE;
    }
    tracker.initFromPose(I, cMo_truth);

    program::PoseErrors errors;
    for (unsigned int frame = first_frame; frame < first_frame + nb_frames; frame++) {
      if (!read_data(frame, input_directory, cam_depth, I, pointcloud, depth_width, depth_height, cMo_truth)) {
        return EXIT_FAILURE;
      }
      std::map<std::string, const vpImage<unsigned char> *> mapOfImages;
      std::map<std::string, const std::vector<vpColVector> *> mapOfPointClouds;
      std::map<std::string, unsigned int> mapOfPointCloudWidths;
      std::map<std::string, unsigned int> mapOfPointCloudHeights;
      mapOfImages["Camera1"] = &I;
      mapOfPointClouds["Camera2"] = &pointcloud;
      mapOfPointCloudWidths["Camera2"] = depth_width;
      mapOfPointCloudHeights["Camera2"] = depth_height;
      tracker.track(mapOfImages, mapOfPointClouds, mapOfPointCloudWidths, mapOfPointCloudHeights);

      errors.add(frame, tracker.getPose(), cMo_truth, tracker.getError().size());
    }
    return errors.report(VP_STRINGIFY(TRACKER_CLASS), errors_file, max_mean_translation_mm);
  });
}
