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
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <visp3/core/vpConfig.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImageConvert.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpPixelMeterConversion.h>

#include <opencv2/imgcodecs.hpp>

#ifndef TRACKER_HEADER
#define TRACKER_HEADER <visp3/mbt/vpMbGenericTracker.h>
#define TRACKER_CLASS vpMbGenericTracker
#endif
#include TRACKER_HEADER

#define VP_STRINGIFY_(x) #x
#define VP_STRINGIFY(x) VP_STRINGIFY_(x)

typedef TRACKER_CLASS Tracker;

namespace
{
std::string numbered(const std::string &format, unsigned int index)
{
  char buffer[FILENAME_MAX];
  snprintf(buffer, sizeof(buffer), format.c_str(), index);
  return std::string(buffer);
}

//! Reads frame `cpt` of the sequence: depth as a depth map and a point cloud in the depth
//! camera's frame (background and depth beyond 2 m: no measurement), ground truth cMo.
bool read_data(unsigned int cpt, const std::string &input_directory, const vpCameraParameters &cam_depth,
               vpImage<float> &I_depth_raw, std::vector<vpColVector> &pointcloud, unsigned int &depth_width,
               unsigned int &depth_height, vpHomogeneousMatrix &cMo_ground_truth)
{
  std::string filename_depth = numbered(input_directory + "/depth/Image%04d.exr", cpt);
  cv::Mat depth_raw = cv::imread(filename_depth, cv::IMREAD_ANYDEPTH | cv::IMREAD_ANYCOLOR);
  if (depth_raw.empty()) {
    std::cerr << "Cannot read: " << filename_depth << std::endl;
    return false;
  }
  depth_width = static_cast<unsigned int>(depth_raw.cols);
  depth_height = static_cast<unsigned int>(depth_raw.rows);
  I_depth_raw.resize(depth_height, depth_width);
  pointcloud.resize(static_cast<size_t>(depth_width) * depth_height);
  for (int i = 0; i < depth_raw.rows; i++) {
    for (int j = 0; j < depth_raw.cols; j++) {
      float z = depth_raw.at<cv::Vec3f>(i, j)[0];
      double Z = (z > 2.0f || !(z > 0.0f)) ? 0.0 : static_cast<double>(z);
      I_depth_raw[i][j] = static_cast<float>(Z);
      double x = 0.0, y = 0.0;
      vpPixelMeterConversion::convertPoint(cam_depth, j, i, x, y);
      vpColVector &point = pointcloud[static_cast<size_t>(i) * depth_width + static_cast<size_t>(j)];
      point.resize(3, false);
      point[0] = x * Z;
      point[1] = y * Z;
      point[2] = Z;
    }
  }

  std::string filename_pose = numbered(input_directory + "/camera_poses/Camera_%03d.txt", cpt);
  std::ifstream f_pose(filename_pose.c_str());
  if (!f_pose.is_open()) {
    std::cerr << "Cannot read: " << filename_pose << std::endl;
    return false;
  }
  cMo_ground_truth.load(f_pose);
  return true;
}

double translation_error_mm(const vpHomogeneousMatrix &cMo, const vpHomogeneousMatrix &cMo_truth)
{
  vpTranslationVector dt = cMo.getTranslationVector() - cMo_truth.getTranslationVector();
  return 1000.0 * dt.frobeniusNorm();
}

double rotation_error_deg(const vpHomogeneousMatrix &cMo, const vpHomogeneousMatrix &cMo_truth)
{
  vpRotationMatrix dR = cMo.getRotationMatrix() * cMo_truth.getRotationMatrix().t();
  vpThetaUVector tu(dR);
  return vpMath::deg(std::sqrt(tu.sumSquare()));
}
} // namespace

int main(int argc, char *argv[])
{
  std::string input_directory = ".";
  std::string errors_file;
  unsigned int first_frame = 1, nb_frames = 30;
  double max_mean_translation_mm = 5.0;

  for (int i = 1; i < argc; i++) {
    if (std::string(argv[i]) == "--input_directory" && i + 1 < argc) {
      input_directory = std::string(argv[++i]);
    } else if (std::string(argv[i]) == "--errors" && i + 1 < argc) {
      errors_file = std::string(argv[++i]);
    } else if (std::string(argv[i]) == "--first_frame" && i + 1 < argc) {
      first_frame = static_cast<unsigned int>(atoi(argv[++i]));
    } else if (std::string(argv[i]) == "--frames" && i + 1 < argc) {
      nb_frames = static_cast<unsigned int>(atoi(argv[++i]));
    } else if (std::string(argv[i]) == "--max_mean_translation_mm" && i + 1 < argc) {
      max_mean_translation_mm = atof(argv[++i]);
    } else if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h") {
      std::cout << "Usage: " << argv[0]
                << " [--input_directory <teabox-blender folder> (default: .)] [--errors <output file>]"
                   " [--first_frame <index> (default: 1)] [--frames <n> (default: 30)]"
                   " [--max_mean_translation_mm <bound> (default: 5)]"
                << std::endl;
      return EXIT_SUCCESS;
    }
  }
  // OpenCV >= 4.2 decodes OpenEXR only when asked to.
  setenv("OPENCV_IO_ENABLE_OPENEXR", "1", 0);

  std::cout << "Tracker: " << VP_STRINGIFY(TRACKER_CLASS) << std::endl;
  std::cout << "input_directory: " << input_directory << std::endl;

  try {
    Tracker tracker(1, Tracker::DEPTH_DENSE_TRACKER);
    tracker.loadConfigFile(input_directory + "/teabox_depth.xml");
    tracker.loadModel(input_directory + "/teabox.cao");

    vpCameraParameters cam_depth;
    tracker.getCameraParameters(cam_depth);
    std::cout << "cam_depth:\n" << cam_depth << std::endl;

    vpHomogeneousMatrix depth_M_color;
    {
      std::ifstream file((input_directory + "/depth_M_color.txt").c_str());
      if (!file.is_open()) {
        std::cerr << "Cannot read: " << input_directory << "/depth_M_color.txt" << std::endl;
        return EXIT_FAILURE;
      }
      depth_M_color.load(file);
    }
    std::cout << "depth_M_color:\n" << depth_M_color << std::endl;

    vpImage<float> I_depth_raw;
    vpImage<unsigned char> I_depth;
    std::vector<vpColVector> pointcloud;
    unsigned int depth_width = 0, depth_height = 0;
    vpHomogeneousMatrix cMo_truth;
    if (!read_data(first_frame, input_directory, cam_depth, I_depth_raw, pointcloud, depth_width, depth_height,
                   cMo_truth)) {
      return EXIT_FAILURE;
    }
    vpImageConvert::createDepthHistogram(I_depth_raw, I_depth);
    tracker.initFromPose(I_depth, depth_M_color * cMo_truth);

    double sum_t = 0.0, sum_r = 0.0, max_t = 0.0, max_r = 0.0;
    unsigned int nb_tracked = 0;
    for (unsigned int frame = first_frame; frame < first_frame + nb_frames; frame++) {
      if (!read_data(frame, input_directory, cam_depth, I_depth_raw, pointcloud, depth_width, depth_height,
                     cMo_truth)) {
        return EXIT_FAILURE;
      }
      std::map<std::string, const vpImage<unsigned char> *> mapOfImages;
      std::map<std::string, const std::vector<vpColVector> *> mapOfPointClouds;
      std::map<std::string, unsigned int> mapOfPointCloudWidths;
      std::map<std::string, unsigned int> mapOfPointCloudHeights;
      mapOfPointClouds["Camera"] = &pointcloud;
      mapOfPointCloudWidths["Camera"] = depth_width;
      mapOfPointCloudHeights["Camera"] = depth_height;
      tracker.track(mapOfImages, mapOfPointClouds, mapOfPointCloudWidths, mapOfPointCloudHeights);

      // The depth camera's pose of the teabox, and its ground truth.
      vpHomogeneousMatrix dMo = tracker.getPose();
      vpHomogeneousMatrix dMo_truth = depth_M_color * cMo_truth;
      double t_err = translation_error_mm(dMo, dMo_truth), r_err = rotation_error_deg(dMo, dMo_truth);
      sum_t += t_err;
      sum_r += r_err;
      max_t = std::max(max_t, t_err);
      max_r = std::max(max_r, r_err);
      nb_tracked++;
      std::cout << "Frame " << frame << ": " << t_err << " mm, " << r_err << " deg, " << tracker.getError().size()
                << " features" << std::endl;
    }

    double mean_t = sum_t / nb_tracked, mean_r = sum_r / nb_tracked;
    std::cout << VP_STRINGIFY(TRACKER_CLASS) << " over " << nb_tracked << " frames: translation mean " << mean_t
              << " mm, max " << max_t << " mm; rotation mean " << mean_r << " deg, max " << max_r << " deg"
              << std::endl;
    if (!errors_file.empty()) {
      std::ofstream f(errors_file.c_str());
      f.precision(9);
      f << "tracker " << VP_STRINGIFY(TRACKER_CLASS) << "\nframes " << nb_tracked << "\nmean_translation_mm " << mean_t
        << "\nmax_translation_mm " << max_t << "\nmean_rotation_deg " << mean_r << "\nmax_rotation_deg " << max_r
        << "\n";
    }
    if (!(mean_t <= max_mean_translation_mm)) {
      std::cerr << "Mean translation error " << mean_t << " mm exceeds the sanity bound of " << max_mean_translation_mm
                << " mm" << std::endl;
      return EXIT_FAILURE;
    }
  } catch (const vpException &e) {
    std::cerr << "Catch a ViSP exception: " << e.what() << std::endl;
    return EXIT_FAILURE;
  } catch (const std::exception &e) {
    std::cerr << "Catch an exception: " << e.what() << std::endl;
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
