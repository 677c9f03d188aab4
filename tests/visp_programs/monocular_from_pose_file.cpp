// SPDX-License-Identifier: GPL-2.0-or-later
//! \example monocular_from_pose_file.cpp
//! Monocular model-based tracking (edges + KLT on grey images, no depth) of ViSP's
//! rendered teabox sequence (teabox-blender), ViSP's classic set-up: the default tracker
//! given its type, teabox.xml, teabox.cao, and the initial pose read from a .pos file
//! (the ground truth of the first frame, written by this program) with initFromPose().
//! Prints the pose errors against the ground truth of every tracked frame.
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
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpPoseVector.h>
#include <visp3/io/vpImageIo.h>

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

//! Reads frame `cpt` of the sequence: grey image and ground truth cMo.
bool read_data(unsigned int cpt, const std::string &input_directory, vpImage<unsigned char> &I,
               vpHomogeneousMatrix &cMo_ground_truth)
{
  std::string filename_img = numbered(input_directory + "/images/%04d.jpg", cpt);
  if (!vpIoTools::checkFilename(filename_img)) {
    std::cerr << "Cannot read: " << filename_img << std::endl;
    return false;
  }
  vpImageIo::read(I, filename_img);

  std::string filename_pose = numbered(input_directory + "/camera_poses/Camera_%03d.txt", cpt);
  std::ifstream f_pose(filename_pose.c_str());
  if (!f_pose.is_open()) {
    std::cerr << "Cannot read: " << filename_pose << std::endl;
    return false;
  }
  cMo_ground_truth.load(f_pose);
  return true;
}

//! Writes cMo as ViSP's .pos initial pose file: tx ty tz (m) and tux tuy tuz (rad).
void write_pose_file(const std::string &filename, const vpHomogeneousMatrix &cMo)
{
  vpPoseVector pose(cMo);
  std::ofstream f(filename.c_str());
  f.precision(17);
  for (unsigned int i = 0; i < 6; i++) {
    f << pose[i] << std::endl;
  }
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
  std::cout << "Tracker: " << VP_STRINGIFY(TRACKER_CLASS) << std::endl;
  std::cout << "input_directory: " << input_directory << std::endl;

  try {
    Tracker tracker;
    tracker.setTrackerType(Tracker::EDGE_TRACKER | Tracker::KLT_TRACKER);
    tracker.loadConfigFile(input_directory + "/teabox.xml");
    tracker.loadModel(input_directory + "/teabox.cao");

    vpCameraParameters cam;
    tracker.getCameraParameters(cam);
    std::cout << "cam:\n" << cam << std::endl;

    vpImage<unsigned char> I;
    vpHomogeneousMatrix cMo_truth;
    if (!read_data(first_frame, input_directory, I, cMo_truth)) {
      return EXIT_FAILURE;
    }
    // The initial pose, as a user would save it: a .pos file beside the results.
    std::string pose_file = (errors_file.empty() ? std::string("teabox") : errors_file) + ".init.pos";
    write_pose_file(pose_file, cMo_truth);
    tracker.initFromPose(I, pose_file);
    vpIoTools::remove(pose_file);

    double sum_t = 0.0, sum_r = 0.0, max_t = 0.0, max_r = 0.0;
    unsigned int nb_tracked = 0;
    for (unsigned int frame = first_frame; frame < first_frame + nb_frames; frame++) {
      if (!read_data(frame, input_directory, I, cMo_truth)) {
        return EXIT_FAILURE;
      }
      tracker.track(I);

      vpHomogeneousMatrix cMo;
      tracker.getPose(cMo);
      double t_err = translation_error_mm(cMo, cMo_truth), r_err = rotation_error_deg(cMo, cMo_truth);
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
