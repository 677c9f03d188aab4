// SPDX-License-Identifier: GPL-2.0-or-later
#include "depth_codecs.h"

#include <opencv2/imgcodecs.hpp>

#include "sequence_files.h"

namespace icgp {

cv::Mat read_png_depth(const std::filesystem::path& path, double depth_scale) {
  require_file(path, "depth image");
  const cv::Mat raw = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
  if (raw.empty()) fail(path, "cannot decode depth image");
  if (raw.type() != CV_16UC1) fail(path, "depth image must be single-channel 16-bit");
  cv::Mat z;
  raw.convertTo(z, CV_32F, depth_scale);
  return z;
}

}  // namespace icgp
