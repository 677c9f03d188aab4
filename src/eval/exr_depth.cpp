// SPDX-License-Identifier: GPL-2.0-or-later
#include "depth_codecs.h"

#include <cstdlib>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "sequence_files.h"

namespace icgp {

void enable_openexr_decoding() { setenv("OPENCV_IO_ENABLE_OPENEXR", "1", /*overwrite=*/0); }

cv::Mat read_exr_depth(const std::filesystem::path& path) {
  require_file(path, "depth image");
  cv::Mat image;
  try {
    image = cv::imread(path.string(), cv::IMREAD_ANYDEPTH | cv::IMREAD_ANYCOLOR);
  } catch (const cv::Exception& e) {
    fail(path, std::string("cannot decode OpenEXR depth: ") + e.what());
  }
  if (image.empty()) {
    const char* flag = std::getenv("OPENCV_IO_ENABLE_OPENEXR");
    fail(path, std::string("cannot decode OpenEXR depth (OpenCV needs OPENCV_IO_ENABLE_OPENEXR=1 before its first "
                           "EXR read; it is ") +
                   (flag ? std::string("'") + flag + "'" : std::string("unset")) + ")");
  }
  cv::Mat z;
  cv::extractChannel(image, z, 0);  // Blender's EXR: channel 0 is Z in metres
  z.convertTo(z, CV_32F);
  return z;
}

}  // namespace icgp
