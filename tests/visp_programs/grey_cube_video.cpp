// SPDX-License-Identifier: GPL-2.0-or-later
//! \example grey_cube_video.cpp
//! Monocular model-based tracking of ViSP's real grey video of a many-coloured cube moved
//! by hand on a bright sheet (visp-images-data: mbt/cube/image%04d.pgm, 218 frames), as
//! ViSP's mbtGenericTracking example does: the tracker type given (default EDGE_TRACKER),
//! cube.xml, cube.cao, the initial pose from cube.0.pos with initFromPose(). There is no
//! ground truth: prints every frame's pose, and saves the poses (one line per frame: frame,
//! then the 12 first entries of cMo row by row) and the final cMo (4x4) for comparison.
//!
//! Written against vpMbGenericTracker's API only: TRACKER_HEADER / TRACKER_CLASS name the
//! tracker class (vpMbGenericTracker or a drop-in replacement) at compile time.
#include <fstream>
#include <string>

#include "program_support.h"

#ifndef TRACKER_HEADER
#define TRACKER_HEADER <visp3/mbt/vpMbGenericTracker.h>
#define TRACKER_CLASS vpMbGenericTracker
#endif
#include TRACKER_HEADER

typedef TRACKER_CLASS Tracker;

int main(int argc, char *argv[])
{
  std::string input_directory = "/usr/share/visp-images-data/ViSP-images/mbt";
  std::string poses_file, final_pose_file;
  unsigned int tracker_type = Tracker::EDGE_TRACKER, nb_frames = 0; // 0: to the end of the video

  if (!program::Options()
           .add("--input_directory", input_directory)
           .add("--tracker", tracker_type)
           .add("--frames", nb_frames)
           .add("--poses", poses_file)
           .add("--final_pose", final_pose_file)
           .parse(argc, argv,
                  "[--input_directory <folder of cube/image%04d.pgm, cube.xml, cube.cao, cube.0.pos>]"
                  " [--tracker <1: EDGE, 2: KLT, 3: EDGE+KLT>] [--frames <n> (default: all)]"
                  " [--poses <output file>] [--final_pose <output file>]"))
    return EXIT_SUCCESS;

  std::cout << "Tracker: " << VP_STRINGIFY(TRACKER_CLASS) << ", type " << tracker_type << std::endl;
  std::cout << "input_directory: " << input_directory << std::endl;

  return program::run([&] {
    Tracker tracker;
    tracker.setTrackerType(static_cast<int>(tracker_type));
    tracker.loadConfigFile(input_directory + "/cube.xml");
    tracker.loadModel(input_directory + "/cube.cao");

    vpImage<unsigned char> I;
    const std::string first = program::numbered(input_directory + "/cube/image%04d.pgm", 0);
    if (!vpIoTools::checkFilename(first)) {
      std::cerr << "Cannot read " << first << " (Debian package visp-images-data)" << std::endl;
      return EXIT_FAILURE;
    }
    vpImageIo::read(I, first);
    tracker.initFromPose(I, input_directory + "/cube.0.pos");

    std::ofstream poses;
    if (!poses_file.empty())
      poses.open(poses_file.c_str());
    poses.precision(10);
    vpHomogeneousMatrix cMo;
    unsigned int frame = 0;
    for (; nb_frames == 0 || frame < nb_frames; frame++) {
      const std::string filename = program::numbered(input_directory + "/cube/image%04d.pgm", frame);
      if (!vpIoTools::checkFilename(filename))
        break;
      vpImageIo::read(I, filename);
      tracker.track(I);
      tracker.getPose(cMo);
      std::cout << "Frame " << frame << ": t = " << cMo.getTranslationVector().t() << " m, tu = "
                << vpThetaUVector(cMo.getRotationMatrix()).t() << " rad" << std::endl;
      if (poses.is_open()) {
        poses << frame;
        for (unsigned int i = 0; i < 3; i++)
          for (unsigned int j = 0; j < 4; j++)
            poses << " " << cMo[i][j];
        poses << std::endl;
      }
    }
    if (frame == 0) {
      std::cerr << "No frame tracked" << std::endl;
      return EXIT_FAILURE;
    }
    std::cout << VP_STRINGIFY(TRACKER_CLASS) << " tracked " << frame << " frames; final cMo:\n" << cMo << std::endl;
    if (!final_pose_file.empty()) {
      std::ofstream f(final_pose_file.c_str());
      f.precision(12);
      cMo.save(f);
    }
    return EXIT_SUCCESS;
  });
}
