// SPDX-License-Identifier: GPL-2.0-or-later
//! \example stereo_two_cameras.cpp
//! Stereo model-based tracking (edges + KLT in two grey cameras, no depth) of a rendered
//! stereo sequence written by `icgp make-sequence --stereo-baseline`: left camera
//! "Camera1" (color/%06d.png), right camera "Camera2" (color2/%06d.png) placed with
//! setCameraTransformationMatrix, both calibrations and c2_M_c1 read from sequence.yaml,
//! initialised with both cameras' ground-truth poses of the first frame; track(I1, I2),
//! getPose(c1Mo, c2Mo). Prints the pose errors against the ground truth of every frame.
//!
//! Written against vpMbGenericTracker's API only: TRACKER_HEADER / TRACKER_CLASS name the
//! tracker class (vpMbGenericTracker or a drop-in replacement) at compile time.
#include <algorithm>
#include <fstream>
#include <sstream>
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
//! The text after "key:" on the line of sequence.yaml that starts with it ("" if none).
std::string yaml_value(const std::string &yaml_file, const std::string &key)
{
  std::ifstream f(yaml_file.c_str());
  std::string line;
  while (std::getline(f, line)) {
    size_t start = line.find_first_not_of(' ');
    if (start != std::string::npos && line.compare(start, key.size() + 1, key + ":") == 0) {
      std::string value = line.substr(start + key.size() + 1);
      size_t first = value.find_first_not_of(' ');
      return first == std::string::npos ? std::string() : value.substr(first);
    }
  }
  return std::string();
}

//! A number of a flow mapping such as "{name: Camera1, width: 640, fu: 600, ...}".
double flow_number(const std::string &mapping, const std::string &key)
{
  size_t pos = mapping.find(" " + key + ":");
  if (pos == std::string::npos)
    pos = mapping.find("{" + key + ":");
  if (pos == std::string::npos)
    throw vpException(vpException::ioError, "sequence.yaml: no " + key + " in " + mapping);
  return atof(mapping.c_str() + pos + key.size() + 2);
}

vpCameraParameters camera_of(const std::string &mapping)
{
  vpCameraParameters cam;
  cam.initPersProjWithoutDistortion(flow_number(mapping, "fu"), flow_number(mapping, "fv"), flow_number(mapping, "pu"),
                                    flow_number(mapping, "pv"));
  return cam;
}

//! A 4x4 matrix written as 16 numbers, row major, separated by spaces, commas or brackets.
vpHomogeneousMatrix matrix_of(std::string text)
{
  std::replace(text.begin(), text.end(), ',', ' ');
  std::replace(text.begin(), text.end(), '[', ' ');
  std::replace(text.begin(), text.end(), ']', ' ');
  std::istringstream ss(text);
  vpHomogeneousMatrix M;
  for (unsigned int i = 0; i < 4; i++) {
    for (unsigned int j = 0; j < 4; j++) {
      if (!(ss >> M[i][j]))
        throw vpException(vpException::ioError, "not a 4x4 matrix: " + text);
    }
  }
  return M;
}
} // namespace

int main(int argc, char *argv[])
{
  std::string input_directory = ".";
  std::string config_file = "textured_box.xml", model_file = "textured_box.cao";
  std::string errors_file;
  unsigned int nb_frames = 30;
  double max_mean_translation_mm = 5.0;

  if (!program::Options()
           .add("--input_directory", input_directory)
           .add("--config", config_file)
           .add("--model", model_file)
           .add("--errors", errors_file)
           .add("--frames", nb_frames)
           .add("--max_mean_translation_mm", max_mean_translation_mm)
           .parse(argc, argv,
                  "[--input_directory <stereo sequence of icgp make-sequence --stereo-baseline>]"
                  " [--config <tracker .xml>] [--model <object .cao>] [--errors <output file>]"
                  " [--frames <n> (default: 30)] [--max_mean_translation_mm <bound> (default: 5)]"))
    return EXIT_SUCCESS;

  std::cout << "Tracker: " << VP_STRINGIFY(TRACKER_CLASS) << std::endl;
  std::cout << "input_directory: " << input_directory << std::endl;

  return program::run([&] {
    // The stereo rig and the object's ground truth, as the sequence records them.
    const std::string yaml = input_directory + "/sequence.yaml";
    if (!vpIoTools::checkFilename(yaml)) {
      std::cerr << "Cannot read: " << yaml << std::endl;
      return EXIT_FAILURE;
    }
    const std::string left = yaml_value(yaml, "color_camera"), right = yaml_value(yaml, "stereo_camera");
    const std::string c2_M_c1_text = yaml_value(yaml, "stereo_T_color");
    if (right.empty() || c2_M_c1_text.empty()) {
      std::cerr << yaml << " describes no stereo camera (stereo_camera, stereo_T_color)" << std::endl;
      return EXIT_FAILURE;
    }
    const vpCameraParameters cam1 = camera_of(left), cam2 = camera_of(right);
    const vpHomogeneousMatrix c2_M_c1 = matrix_of(c2_M_c1_text);
    const std::string object_name = yaml_value(yaml, "- name");
    std::vector<vpHomogeneousMatrix> c1Mo_truth;
    {
      std::ifstream f((input_directory + "/poses/" + object_name + ".txt").c_str());
      std::string line;
      while (std::getline(f, line)) {
        if (!line.empty())
          c1Mo_truth.push_back(matrix_of(line));
      }
    }
    if (c1Mo_truth.empty()) {
      std::cerr << "Cannot read: " << input_directory << "/poses/" << object_name << ".txt" << std::endl;
      return EXIT_FAILURE;
    }
    nb_frames = std::min(nb_frames, static_cast<unsigned int>(c1Mo_truth.size()));

    Tracker tracker(2, Tracker::EDGE_TRACKER | Tracker::KLT_TRACKER);
    tracker.loadConfigFile(config_file, config_file);
    tracker.setCameraParameters(cam1, cam2);
    tracker.loadModel(model_file, model_file);
    tracker.setCameraTransformationMatrix("Camera2", c2_M_c1);
    std::cout << "cam1:\n" << cam1 << "\ncam2:\n" << cam2 << "\nc2_M_c1:\n" << c2_M_c1 << std::endl;

    vpImage<unsigned char> I1, I2;
    vpImageIo::read(I1, program::numbered(input_directory + "/color/%06d.png", 0));
    vpImageIo::read(I2, program::numbered(input_directory + "/color2/%06d.png", 0));
    tracker.initFromPose(I1, I2, c1Mo_truth[0], c2_M_c1 * c1Mo_truth[0]);

    program::PoseErrors errors;
    for (unsigned int frame = 0; frame < nb_frames; frame++) {
      vpImageIo::read(I1, program::numbered(input_directory + "/color/%06d.png", frame));
      vpImageIo::read(I2, program::numbered(input_directory + "/color2/%06d.png", frame));
      tracker.track(I1, I2);

      vpHomogeneousMatrix c1Mo, c2Mo;
      tracker.getPose(c1Mo, c2Mo);
      const double rig_err = program::translation_error_mm(c2Mo, c2_M_c1 * c1Mo);
      errors.add(frame, c1Mo, c1Mo_truth[frame], tracker.getError().size(),
                 rig_err > 1e-6 ? " (c2Mo is not c2_M_c1 * c1Mo)" : "");
    }
    return errors.report(VP_STRINGIFY(TRACKER_CLASS), errors_file, max_mean_translation_mm);
  });
}
