// SPDX-License-Identifier: GPL-2.0-or-later
// What the ViSP-style programs share, apart from their tracker calls: options, reading
// their data, and measuring and reporting pose errors. ViSP and OpenCV only, so the
// vpMbGenericTracker variant of each program still compiles against ViSP alone.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpPixelMeterConversion.h>
#include <visp3/io/vpImageIo.h>

#define VP_STRINGIFY_(x) #x
#define VP_STRINGIFY(x) VP_STRINGIFY_(x)

namespace program
{
//! The "--name value" options of ViSP's examples: each known name sets its variable,
//! unknown arguments are ignored, --help / -h prints the usage.
class Options
{
public:
  Options &add(const std::string &name, std::string &value)
  {
    setters_[name] = [&value](const char *text) { value = text; };
    return *this;
  }
  Options &add(const std::string &name, unsigned int &value)
  {
    setters_[name] = [&value](const char *text) { value = static_cast<unsigned int>(atoi(text)); };
    return *this;
  }
  Options &add(const std::string &name, double &value)
  {
    setters_[name] = [&value](const char *text) { value = atof(text); };
    return *this;
  }
  //! False when the usage was asked for (and printed): the program then ends.
  bool parse(int argc, char *argv[], const std::string &usage) const
  {
    for (int i = 1; i < argc; i++) {
      const std::string name(argv[i]);
      if (name == "--help" || name == "-h") {
        std::cout << "Usage: " << argv[0] << " " << usage << std::endl;
        return false;
      }
      const auto setter = setters_.find(name);
      if (setter != setters_.end() && i + 1 < argc)
        setter->second(argv[++i]);
    }
    return true;
  }

private:
  std::map<std::string, std::function<void(const char *)> > setters_;
};

//! The options of the programs on ViSP's rendered teabox sequence (teabox-blender).
struct TeaboxOptions
{
  std::string input_directory = ".";
  std::string errors_file;
  unsigned int first_frame = 1, nb_frames = 30;
  double max_mean_translation_mm = 5.0;

  //! False when the usage was asked for (and printed).
  bool parse(int argc, char *argv[])
  {
    return Options()
        .add("--input_directory", input_directory)
        .add("--errors", errors_file)
        .add("--first_frame", first_frame)
        .add("--frames", nb_frames)
        .add("--max_mean_translation_mm", max_mean_translation_mm)
        .parse(argc, argv,
               "[--input_directory <teabox-blender folder> (default: .)] [--errors <output file>]"
               " [--first_frame <index> (default: 1)] [--frames <n> (default: 30)]"
               " [--max_mean_translation_mm <bound> (default: 5)]");
  }
};

//! Runs a program's body, reporting an exception as ViSP's examples do.
inline int run(const std::function<int()> &body)
{
  try {
    return body();
  } catch (const vpException &e) {
    std::cerr << "Catch a ViSP exception: " << e.what() << std::endl;
  } catch (const std::exception &e) {
    std::cerr << "Catch an exception: " << e.what() << std::endl;
  }
  return EXIT_FAILURE;
}

inline std::string numbered(const std::string &format, unsigned int index)
{
  char buffer[FILENAME_MAX];
  snprintf(buffer, sizeof(buffer), format.c_str(), index);
  return std::string(buffer);
}

//! A 4x4 matrix file as vpHomogeneousMatrix::load reads it; false (said on stderr) when
//! the file cannot be opened.
inline bool read_matrix(const std::string &filename, vpHomogeneousMatrix &M)
{
  std::ifstream file(filename.c_str());
  if (!file.is_open()) {
    std::cerr << "Cannot read: " << filename << std::endl;
    return false;
  }
  M.load(file);
  return true;
}

//! ViSP's RGB-D rig: colour "Camera1" at the reference, depth "Camera2" placed by the
//! folder's depth_M_color.txt (read into depth_M_color); false (said on stderr) when that
//! file cannot be read.
template <typename Tracker>
bool set_rgbd_transformations(Tracker &tracker, const std::string &input_directory, vpHomogeneousMatrix &depth_M_color)
{
  if (!read_matrix(input_directory + "/depth_M_color.txt", depth_M_color))
    return false;
  std::map<std::string, vpHomogeneousMatrix> mapOfCameraTransformations;
  mapOfCameraTransformations["Camera1"] = vpHomogeneousMatrix();
  mapOfCameraTransformations["Camera2"] = depth_M_color;
  tracker.setCameraTransformationMatrix(mapOfCameraTransformations);
  return true;
}

//! The organised cloud of a depth image, as ViSP's RGB-D examples build it: each pixel
//! back-projected with the camera's parameters at its depth depth_at(i, j) (metres, 0: no
//! measurement), X Y Z in the camera's frame, row major.
template <typename DepthAt>
void to_point_cloud(unsigned int height, unsigned int width, const vpCameraParameters &cam, DepthAt depth_at,
                    std::vector<vpColVector> &pointcloud)
{
  pointcloud.resize(static_cast<size_t>(width) * height);
  for (unsigned int i = 0; i < height; i++) {
    for (unsigned int j = 0; j < width; j++) {
      double Z = depth_at(i, j);
      double x = 0.0, y = 0.0;
      vpPixelMeterConversion::convertPoint(cam, j, i, x, y);
      vpColVector &point = pointcloud[static_cast<size_t>(i) * width + j];
      point.resize(3, false);
      point[0] = x * Z;
      point[1] = y * Z;
      point[2] = Z;
    }
  }
}

//! ViSP's rendered teabox sequence (teabox-blender): frame `cpt`'s grey image.
inline bool read_blender_image(unsigned int cpt, const std::string &input_directory, vpImage<unsigned char> &I)
{
  std::string filename = numbered(input_directory + "/images/%04d.jpg", cpt);
  if (!vpIoTools::checkFilename(filename)) {
    std::cerr << "Cannot read: " << filename << std::endl;
    return false;
  }
  vpImageIo::read(I, filename);
  return true;
}

//! teabox-blender: frame `cpt`'s depth in metres (background and depth beyond 2 m: 0).
inline bool read_blender_depth(unsigned int cpt, const std::string &input_directory, vpImage<float> &depth)
{
  // OpenCV >= 4.2 decodes OpenEXR only when asked to.
  setenv("OPENCV_IO_ENABLE_OPENEXR", "1", 0);
  std::string filename = numbered(input_directory + "/depth/Image%04d.exr", cpt);
  cv::Mat exr = cv::imread(filename, cv::IMREAD_ANYDEPTH | cv::IMREAD_ANYCOLOR);
  if (exr.empty()) {
    std::cerr << "Cannot read: " << filename << std::endl;
    return false;
  }
  depth.resize(static_cast<unsigned int>(exr.rows), static_cast<unsigned int>(exr.cols));
  for (int i = 0; i < exr.rows; i++) {
    for (int j = 0; j < exr.cols; j++) {
      float z = exr.at<cv::Vec3f>(i, j)[0];
      depth[i][j] = (z > 2.0f || !(z > 0.0f)) ? 0.0f : z;
    }
  }
  return true;
}

//! teabox-blender: frame `cpt`'s ground truth cMo.
inline bool read_blender_truth(unsigned int cpt, const std::string &input_directory, vpHomogeneousMatrix &cMo)
{
  return read_matrix(numbered(input_directory + "/camera_poses/Camera_%03d.txt", cpt), cMo);
}

inline double translation_error_mm(const vpHomogeneousMatrix &cMo, const vpHomogeneousMatrix &cMo_truth)
{
  vpTranslationVector dt = cMo.getTranslationVector() - cMo_truth.getTranslationVector();
  return 1000.0 * dt.frobeniusNorm();
}

inline double rotation_error_deg(const vpHomogeneousMatrix &cMo, const vpHomogeneousMatrix &cMo_truth)
{
  vpRotationMatrix dR = cMo.getRotationMatrix() * cMo_truth.getRotationMatrix().t();
  vpThetaUVector tu(dR);
  return vpMath::deg(std::sqrt(tu.sumSquare()));
}

//! The pose errors of a tracked sequence against its ground truth.
class PoseErrors
{
public:
  //! One frame's errors, printed with the number of features and an optional note.
  void add(unsigned int frame, const vpHomogeneousMatrix &cMo, const vpHomogeneousMatrix &cMo_truth,
           unsigned int nb_features, const std::string &note = "")
  {
    double t_err = translation_error_mm(cMo, cMo_truth), r_err = rotation_error_deg(cMo, cMo_truth);
    sum_t_ += t_err;
    sum_r_ += r_err;
    max_t_ = std::max(max_t_, t_err);
    max_r_ = std::max(max_r_, r_err);
    nb_tracked_++;
    std::cout << "Frame " << frame << ": " << t_err << " mm, " << r_err << " deg, " << nb_features << " features"
              << note << std::endl;
  }

  //! Prints the summary, writes it to `errors_file` (if any) for the comparison tests, and
  //! fails unless the mean translation error is within the program's sanity bound.
  int report(const std::string &tracker, const std::string &errors_file, double max_mean_translation_mm) const
  {
    double mean_t = sum_t_ / nb_tracked_, mean_r = sum_r_ / nb_tracked_;
    std::cout << tracker << " over " << nb_tracked_ << " frames: translation mean " << mean_t << " mm, max " << max_t_
              << " mm; rotation mean " << mean_r << " deg, max " << max_r_ << " deg" << std::endl;
    if (!errors_file.empty()) {
      std::ofstream f(errors_file.c_str());
      f.precision(9);
      f << "tracker " << tracker << "\nframes " << nb_tracked_ << "\nmean_translation_mm " << mean_t
        << "\nmax_translation_mm " << max_t_ << "\nmean_rotation_deg " << mean_r << "\nmax_rotation_deg " << max_r_
        << "\n";
    }
    if (!(mean_t <= max_mean_translation_mm)) {
      std::cerr << "Mean translation error " << mean_t << " mm exceeds the sanity bound of " << max_mean_translation_mm
                << " mm" << std::endl;
      return EXIT_FAILURE;
    }
    return EXIT_SUCCESS;
  }

private:
  double sum_t_ = 0.0, sum_r_ = 0.0, max_t_ = 0.0, max_r_ = 0.0;
  unsigned int nb_tracked_ = 0;
};
} // namespace program
