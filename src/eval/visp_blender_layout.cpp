// SPDX-License-Identifier: GPL-2.0-or-later
// The "visp-blender" layout, ViSP's Blender-rendered tutorial sequences (teabox): found by
// its images/ + depth/ folders. images/%04d.jpg from 0001, depth/Image%04d.exr (channel 0
// = Z), ground truth camera_poses/Camera_%03d.txt (cMo, 4x4) named after the single
// top-level .cao file, depth_M_color.txt; intrinsics from ViSP XML files (visp_layout.h).
#include "built_in_layouts.h"

#include <map>
#include <memory>

#include "depth_codecs.h"
#include "sequence_files.h"
#include "visp_layout.h"

namespace icgp {

namespace fs = std::filesystem;

namespace {

const char* const kName = "visp-blender";

class VispBlenderLayout : public VispLayout {
 public:
  explicit VispBlenderLayout(fs::path dir) : VispLayout(std::move(dir)) { enable_openexr_decoding(); }
  fs::path color_file(int i) const override { return dir_ / "images" / numbered("", i + 1, 4, ".jpg"); }
  fs::path depth_file(int i) const override { return dir_ / "depth" / numbered("Image", i + 1, 4, ".exr"); }
  fs::path pose_file(int i) const { return dir_ / "camera_poses" / numbered("Camera_", i + 1, 3, ".txt"); }
  cv::Mat read_depth(int i) const override { return read_exr_depth(depth_file(i)); }
  std::map<std::string, Pose> read_ground_truth(int i) const override {
    if (object_.empty()) return {};
    return {{object_, read_pose_matrix_file(pose_file(i).string())}};
  }

  static SequenceLayoutEntry::Opened open(const fs::path& dir, const SequenceOptions& options) {
    SequenceDescription d;
    d.frame_count = count_numbered_files(dir / "images", "", 4, ".jpg", 1);
    d.has_ground_truth = fs::is_directory(dir / "camera_poses");
    auto layout = std::make_shared<VispBlenderLayout>(dir);
    layout->describe_calibration(kName, options, d);
    if (options.blender_principal_point) {
      // Blender puts the principal point at the sensor's centre, the pixel-edge coordinate
      // (W/2, H/2); in ViSP's convention (pixel centres at integers) that is
      // ((W-1)/2, (H-1)/2), half a pixel left of and above the XML's W/2, H/2. Rendering the
      // ground truth shows it: the depth images match to 0.01 mm with the shift and are off
      // by 0.2-0.35 mm without (docs/accuracy.md).
      for (Intrinsics* k : {&d.color_intrinsics, &d.depth_intrinsics}) {
        k->pu -= 0.5;
        k->pv -= 0.5;
      }
    }
    if (d.has_ground_truth) {
      if (d.objects.size() != 1)
        fail(dir, "camera_poses/ holds the ground truth of one object, named after the top-level .cao file, but "
                  "found " + std::to_string(d.objects.size()) + " .cao files");
      layout->object_ = d.objects.front().name;
    }
    for (int i = 0; i < d.frame_count; ++i) {
      require_file(layout->depth_file(i), "depth image of frame " + std::to_string(i));
      if (d.has_ground_truth) require_file(layout->pose_file(i), "ground-truth pose of frame " + std::to_string(i));
    }
    return {d, layout};
  }

 private:
  std::string object_;
};

}  // namespace

SequenceLayoutEntry visp_blender_layout() {
  return {kName, "images/ + depth/ folders",
          [](const fs::path& dir) { return fs::is_directory(dir / "images") && fs::is_directory(dir / "depth"); },
          VispBlenderLayout::open};
}

}  // namespace icgp
