// SPDX-License-Identifier: GPL-2.0-or-later
//! \example castle_tracker_types.cpp
//! One tracker type against ground truth on ViSP's synthetic castle sequence
//! (visp-images-data: mbt-depth/Castle-simu, 40 frames, grey images and depth), set up as
//! ViSP's own regression test of the generic tracker sets it up: a colour camera "Camera1" of
//! the type given and a dense-depth camera "Camera2" 5 cm beside it, chateau.xml and
//! chateau_depth.xml, the castle as .wrl (Coin3D) and .cao plus a cube loaded beside it with a
//! transformation, initFromPose at the first frame's truth. Without --depth 1 the depth
//! camera gets empty clouds. --mask 1 sets ViSP's test's tracking mask (-m there: the middle
//! five sevenths of the image in both directions), whose frames ViSP checks for accuracy only
//! without the mask; this program checks them with it too. --tracker 0 is ViSP's depth-only test instead: one camera
//! "Camera" with DEPTH_DENSE_TRACKER alone, chateau_depth.xml, the castle as .cao plus the
//! cube, its pose the depth camera's. The error of a frame is ViSP's test's: the norms of the
//! differences of the translation and theta-u vectors. Fails when a frame's error exceeds
//! the bounds given (ViSP's CI thresholds for the type), and writes the errors' statistics.
//!
//! Written against vpMbGenericTracker's API only: TRACKER_HEADER / TRACKER_CLASS name the
//! tracker class (vpMbGenericTracker or a drop-in replacement) at compile time.
#include <algorithm>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <visp3/core/vpPoseVector.h>

#include "program_support.h"

#ifndef TRACKER_HEADER
#define TRACKER_HEADER <visp3/mbt/vpMbGenericTracker.h>
#define TRACKER_CLASS vpMbGenericTracker
#endif
#include TRACKER_HEADER

typedef TRACKER_CLASS Tracker;

namespace
{
//! Frame `cpt` (from 1): the grey image, the depth (uint32 height, uint32 width, then
//! uint16 values of about 1/32768 m, little endian) as a cloud in the depth camera's frame, and
//! the ground truth cMo (4x4 text).
bool read_frame(const std::string &input_directory, unsigned int cpt, const vpCameraParameters &cam_depth,
                vpImage<unsigned char> &I, unsigned int &depth_width, unsigned int &depth_height,
                std::vector<vpColVector> &pointcloud, vpHomogeneousMatrix &cMo_truth)
{
  const std::string image_file = program::numbered(input_directory + "/Images/Image_%04d.pgm", cpt);
  const std::string depth_file = program::numbered(input_directory + "/Depth/Depth_%04d.bin", cpt);
  char pose_name[64];
  snprintf(pose_name, sizeof(pose_name), "/CameraPose/Camera_%03u.txt", cpt);
  const std::string pose_file = input_directory + pose_name;
  if (!vpIoTools::checkFilename(image_file) || !vpIoTools::checkFilename(depth_file) ||
      !vpIoTools::checkFilename(pose_file))
    return false;
  vpImageIo::read(I, image_file);

  std::ifstream depth(depth_file.c_str(), std::ios::in | std::ios::binary);
  vpIoTools::readBinaryValueLE(depth, depth_height);
  vpIoTools::readBinaryValueLE(depth, depth_width);
  std::vector<uint16_t> raw(static_cast<size_t>(depth_height) * depth_width);
  for (size_t i = 0; i < raw.size(); i++)
    vpIoTools::readBinaryValueLE(depth, raw[i]);
  if (!depth) {
    std::cerr << "Truncated depth file: " << depth_file << std::endl;
    return false;
  }
  const double depth_scale = 0.000030518; // ViSP test data scale: about 1/32768 m
  program::to_point_cloud(
      depth_height, depth_width, cam_depth,
      [&](unsigned int i, unsigned int j) { return raw[static_cast<size_t>(i) * depth_width + j] * depth_scale; },
      pointcloud);

  std::ifstream pose(pose_file.c_str());
  for (unsigned int i = 0; i < 4; i++)
    for (unsigned int j = 0; j < 4; j++)
      pose >> cMo_truth[i][j];
  return static_cast<bool>(pose);
}
} // namespace

int main(int argc, char *argv[])
{
  std::string input_directory = "/usr/share/visp-images-data/ViSP-images/mbt-depth/Castle-simu";
  std::string errors_file;
  unsigned int tracker_type = Tracker::EDGE_TRACKER, use_depth = 0, use_mask = 0;
  double max_translation_mm = 1e9, max_rotation_deg = 1e9;

  if (!program::Options()
           .add("--input_directory", input_directory)
           .add("--tracker", tracker_type)
           .add("--depth", use_depth)
           .add("--mask", use_mask)
           .add("--max_translation_mm", max_translation_mm)
           .add("--max_rotation_deg", max_rotation_deg)
           .add("--errors", errors_file)
           .parse(argc, argv,
                  "[--input_directory <Castle-simu folder>] [--tracker <0: none (depth alone), 1: EDGE, 2: KLT, 3: EDGE+KLT>]"
                  " [--depth <0|1: dense depth too>] [--mask <0|1: ViSP's tracking mask>] [--max_translation_mm <bound>] [--max_rotation_deg <bound>]"
                  " [--errors <output file>]"))
    return EXIT_SUCCESS;

  std::cout << "Tracker: " << VP_STRINGIFY(TRACKER_CLASS) << ", type " << tracker_type << (use_depth ? " + depth" : "")
            << std::endl;

  return program::run([&] {
    const bool depth_alone = tracker_type == 0;
    std::vector<int> types;
    if (!depth_alone)
      types.push_back(static_cast<int>(tracker_type));
    types.push_back(Tracker::DEPTH_DENSE_TRACKER);
    Tracker tracker(types);
    if (depth_alone) {
      tracker.loadConfigFile(input_directory + "/Config/chateau_depth.xml");
      tracker.loadModel(input_directory + "/Models/chateau.cao");
    } else {
      tracker.loadConfigFile(input_directory + "/Config/chateau.xml", input_directory + "/Config/chateau_depth.xml");
      tracker.loadModel(input_directory + "/Models/chateau.wrl", input_directory + "/Models/chateau.cao");
    }
    // The cube beside the castle, as ViSP's test places it.
    vpHomogeneousMatrix T;
    T[0][0] = -1;
    T[0][3] = -0.2;
    T[1][1] = 0;
    T[1][2] = 1;
    T[1][3] = 0.12;
    T[2][1] = 1;
    T[2][2] = 0;
    T[2][3] = -0.15;
    tracker.loadModel(input_directory + "/Models/cube.cao", false, T);
    vpCameraParameters cam_color, cam_depth;
    if (depth_alone)
      tracker.getCameraParameters(cam_depth);
    else
      tracker.getCameraParameters(cam_color, cam_depth);
    vpHomogeneousMatrix depth_M_color;
    depth_M_color[0][3] = -0.05;
    if (!depth_alone)
      tracker.setCameraTransformationMatrix("Camera2", depth_M_color);
    // The pose the tracker estimates: the colour camera's, or the depth camera's alone.
    const vpHomogeneousMatrix tracked_M_color = depth_alone ? depth_M_color : vpHomogeneousMatrix();

    vpImage<unsigned char> I;
    std::vector<vpColVector> pointcloud;
    unsigned int width = 0, height = 0;
    vpHomogeneousMatrix cMo_truth;
    if (!read_frame(input_directory, 1, cam_depth, I, width, height, pointcloud, cMo_truth)) {
      std::cerr << "Cannot read the first frame in " << input_directory << " (Debian package visp-images-data)"
                << std::endl;
      return EXIT_FAILURE;
    }
    // ViSP's tracking mask: the image's middle five sevenths in both directions. ViSP keeps
    // a pointer to it: it lives as long as the tracker tracks.
    vpImage<bool> mask(I.getHeight(), I.getWidth(), false);
    if (use_mask) {
      for (unsigned int i = I.getRows() / 7; i < I.getRows() * 6 / 7; i++)
        for (unsigned int j = I.getCols() / 7; j < I.getCols() * 6 / 7; j++)
          mask[i][j] = true;
      tracker.setMask(mask);
    }
    tracker.initFromPose(I, tracked_M_color * cMo_truth);

    std::vector<double> errors_t, errors_r, times;
    bool within_bounds = true;
    for (unsigned int frame = 1; read_frame(input_directory, frame, cam_depth, I, width, height, pointcloud, cMo_truth);
         frame++) {
      std::map<std::string, const vpImage<unsigned char> *> images;
      std::map<std::string, const std::vector<vpColVector> *> clouds;
      std::map<std::string, unsigned int> widths, heights;
      const std::string depth_camera = depth_alone ? "Camera" : "Camera2";
      if (!depth_alone)
        images["Camera1"] = &I;
      clouds[depth_camera] = &pointcloud;
      widths[depth_camera] = use_depth || depth_alone ? width : 0;
      heights[depth_camera] = use_depth || depth_alone ? height : 0;
      const double t0 = vpTime::measureTimeMs();
      tracker.track(images, clouds, widths, heights);
      const vpHomogeneousMatrix cMo = tracker.getPose();
      times.push_back(vpTime::measureTimeMs() - t0);

      const vpPoseVector estimate(cMo), truth(tracked_M_color * cMo_truth);
      double t2 = 0.0, r2 = 0.0;
      for (unsigned int i = 0; i < 3; i++) {
        t2 += vpMath::sqr(estimate[i] - truth[i]);
        r2 += vpMath::sqr(estimate[i + 3] - truth[i + 3]);
      }
      errors_t.push_back(1000.0 * std::sqrt(t2));
      errors_r.push_back(vpMath::deg(std::sqrt(r2)));
      std::cout << "Frame " << frame << ": " << errors_t.back() << " mm, " << errors_r.back() << " deg" << std::endl;
      if (errors_t.back() > max_translation_mm || errors_r.back() > max_rotation_deg) {
        std::cout << "  exceeds the bounds " << max_translation_mm << " mm, " << max_rotation_deg << " deg"
                  << std::endl;
        within_bounds = false;
      }
    }
    if (errors_t.empty()) {
      std::cerr << "No frame tracked" << std::endl;
      return EXIT_FAILURE;
    }
    const double mean_t = vpMath::getMean(errors_t), mean_r = vpMath::getMean(errors_r);
    const double max_t = *std::max_element(errors_t.begin(), errors_t.end());
    const double max_r = *std::max_element(errors_r.begin(), errors_r.end());
    std::cout << VP_STRINGIFY(TRACKER_CLASS) << " over " << errors_t.size() << " frames: mean " << mean_t << " mm, "
              << mean_r << " deg; max " << max_t << " mm, " << max_r << " deg; median "
              << vpMath::getMedian(times) << " ms" << std::endl;
    if (!errors_file.empty()) {
      std::ofstream f(errors_file.c_str());
      f << "mean_translation_mm " << mean_t << "\nmean_rotation_deg " << mean_r << "\nmax_translation_mm " << max_t
        << "\nmax_rotation_deg " << max_r << "\nmedian_ms " << vpMath::getMedian(times) << std::endl;
    }
    if (!within_bounds) {
      std::cout << "FAIL: a frame's error exceeds the bounds" << std::endl;
      return EXIT_FAILURE;
    }
    return EXIT_SUCCESS;
  });
}
