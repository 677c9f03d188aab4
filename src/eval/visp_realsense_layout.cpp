// SPDX-License-Identifier: GPL-2.0-or-later
// The "visp-realsense" layout, what ViSP's RealSense tutorial records: found by its
// color_image_0000.jpg. color_image_%04d.jpg from 0000, depth_image_%04d.bin (little-endian
// uint32 height, uint32 width, H*W uint16, Z = value * 1 mm), depth_M_color.txt, no ground
// truth; intrinsics from ViSP XML files (visp_layout.h).
#include "built_in_layouts.h"

#include <map>
#include <memory>

#include "depth_codecs.h"
#include "sequence_files.h"
#include "visp_layout.h"

namespace icgp {

namespace fs = std::filesystem;

namespace {

const char* const kName = "visp-realsense";

class VispRealsenseLayout : public VispLayout {
 public:
  using VispLayout::VispLayout;
  fs::path color_file(int i) const override { return dir_ / numbered("color_image_", i, 4, ".jpg"); }
  fs::path depth_file(int i) const override { return dir_ / numbered("depth_image_", i, 4, ".bin"); }
  cv::Mat read_depth(int i) const override { return read_realsense_bin_depth(depth_file(i)); }
  std::map<std::string, Pose> read_ground_truth(int) const override { return {}; }

  static SequenceLayoutEntry::Opened open(const fs::path& dir, const SequenceOptions& options) {
    SequenceDescription d;
    d.frame_count = count_numbered_files(dir, "color_image_", 4, ".jpg", 0);
    auto layout = std::make_shared<VispRealsenseLayout>(dir);
    layout->describe_calibration(kName, options, d);
    for (int i = 0; i < d.frame_count; ++i)
      require_file(layout->depth_file(i), "depth file of frame " + std::to_string(i));
    return {d, layout};
  }
};

}  // namespace

SequenceLayoutEntry visp_realsense_layout() {
  return {kName, "color_image_0000.jpg",
          [](const fs::path& dir) { return fs::is_regular_file(dir / "color_image_0000.jpg"); },
          VispRealsenseLayout::open};
}

}  // namespace icgp
