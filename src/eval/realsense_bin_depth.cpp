// SPDX-License-Identifier: GPL-2.0-or-later
#include "depth_codecs.h"

#include <cstdint>
#include <string>

#include "sequence_files.h"

namespace icgp {
namespace {

std::uint32_t little_endian_u32(const unsigned char* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}

}  // namespace

cv::Mat read_realsense_bin_depth(const std::filesystem::path& path) {
  require_file(path, "depth file");
  const std::string bytes = read_text_file(path);
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  if (bytes.size() < 8)
    fail(path, "truncated: " + std::to_string(bytes.size()) + " bytes, expected at least the 8-byte header");
  const std::uint32_t height = little_endian_u32(data);
  const std::uint32_t width = little_endian_u32(data + 4);
  constexpr std::uint32_t kMaxSide = 1u << 15;  // rejects garbage headers before allocating
  if (height == 0 || width == 0 || height > kMaxSide || width > kMaxSide)
    fail(path, "implausible depth image size " + std::to_string(width) + "x" + std::to_string(height) + " in header");
  const std::size_t expected = 8 + std::size_t(2) * height * width;
  if (bytes.size() != expected)
    fail(path, std::string(bytes.size() < expected ? "truncated" : "too long") + ": " + std::to_string(bytes.size()) +
                   " bytes, expected " + std::to_string(expected) + " for a " +
                   size_text(int(width), int(height)) + " depth image");
  cv::Mat z(int(height), int(width), CV_32F);
  const unsigned char* p = data + 8;
  for (int r = 0; r < z.rows; ++r) {
    auto* row = z.ptr<float>(r);
    for (int c = 0; c < z.cols; ++c, p += 2) row[c] = float((p[0] | p[1] << 8) * 0.001);
  }
  return z;
}

}  // namespace icgp
