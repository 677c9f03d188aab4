// SPDX-License-Identifier: GPL-2.0-or-later
// The depth encodings of the built-in sequence layouts, one file each. Each returns Z in
// metres as stored (CV_32FC1, invalid values not yet cleared) and fails naming the file.
#pragma once

#include <filesystem>
#include <opencv2/core.hpp>

namespace icgp {

/// OpenCV 4.6 refuses to decode OpenEXR unless OPENCV_IO_ENABLE_OPENEXR is set when the
/// codec is first used (a security default for untrusted files). Depth sequences need it,
/// so this enables it unless the user decided otherwise; call it before the first read.
void enable_openexr_decoding();
/// Blender's OpenEXR depth: channel 0 is Z in metres (exr_depth.cpp).
cv::Mat read_exr_depth(const std::filesystem::path& path);

/// ViSP's RealSense tutorial depth dump: uint32 height, uint32 width, H*W uint16 in mm,
/// all little-endian (realsense_bin_depth.cpp).
cv::Mat read_realsense_bin_depth(const std::filesystem::path& path);

/// A single-channel 16-bit PNG, Z = value * depth_scale (png_depth.cpp).
cv::Mat read_png_depth(const std::filesystem::path& path, double depth_scale);

}  // namespace icgp
