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
#include <fstream>
#include <string>

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
    Tracker tracker;
    tracker.setTrackerType(Tracker::EDGE_TRACKER | Tracker::KLT_TRACKER);
    tracker.loadConfigFile(input_directory + "/teabox.xml");
    tracker.loadModel(input_directory + "/teabox.cao");

    vpCameraParameters cam;
    tracker.getCameraParameters(cam);
    std::cout << "cam:\n" << cam << std::endl;

    vpImage<unsigned char> I;
    vpHomogeneousMatrix cMo_truth;
    if (!program::read_blender_image(first_frame, input_directory, I) ||
        !program::read_blender_truth(first_frame, input_directory, cMo_truth)) {
      return EXIT_FAILURE;
    }
    // The initial pose, as a user would save it: a .pos file beside the results.
    std::string pose_file = (errors_file.empty() ? std::string("teabox") : errors_file) + ".init.pos";
    write_pose_file(pose_file, cMo_truth);
    tracker.initFromPose(I, pose_file);
    vpIoTools::remove(pose_file);

    program::PoseErrors errors;
    for (unsigned int frame = first_frame; frame < first_frame + nb_frames; frame++) {
      if (!program::read_blender_image(frame, input_directory, I) ||
          !program::read_blender_truth(frame, input_directory, cMo_truth)) {
        return EXIT_FAILURE;
      }
      tracker.track(I);

      vpHomogeneousMatrix cMo;
      tracker.getPose(cMo);
      errors.add(frame, cMo, cMo_truth, tracker.getError().size());
    }
    return errors.report(VP_STRINGIFY(TRACKER_CLASS), errors_file, max_mean_translation_mm);
  });
}
