// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/eval/sequence.h"

#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "icgp/base/camera_names.h"
#include "icgp/eval/sequence_layout.h"
#include "sequence_files.h"

namespace icgp {

namespace fs = std::filesystem;

namespace {

/// Depth in place: 0 wherever there is no trustworthy measurement.
void clear_invalid_depth(cv::Mat& depth, double max_depth) {
  const float max_z = static_cast<float>(max_depth);
  depth.forEach<float>([max_z](float& z, const int*) {
    if (!(z > 0.f && z <= max_z)) z = 0.f;  // also catches NaN
  });
}

void check_size(const cv::Mat& image, const Intrinsics& expected, const fs::path& file, const std::string& what,
                const std::string& origin) {
  if (image.cols != expected.width || image.rows != expected.height)
    fail(file, what + " is " + size_text(image.cols, image.rows) + " but expected " +
                   size_text(expected.width, expected.height) + " (" + origin + ")");
}

/// A principal point outside the image means the images are not the size the intrinsics
/// were calibrated for (depth frames of half the size, say).
void check_principal_point(const fs::path& dir, const Intrinsics& k, const std::string& what) {
  if (!(k.pu >= -0.5 && k.pu <= k.width - 0.5 && k.pv >= -0.5 && k.pv <= k.height - 0.5))
    fail(dir, what + " intrinsics put the principal point at (" + std::to_string(k.pu) + ", " + std::to_string(k.pv) +
                  "), outside the " + size_text(k.width, k.height) + " " + what +
                  " images (expected images of the size the intrinsics were calibrated for)");
}

/// The first registered layout whose probe recognises `dir`.
const SequenceLayoutEntry& detect_layout(const fs::path& dir) {
  const std::vector<SequenceLayoutEntry>& layouts = SequenceLayouts::instance().entries();
  for (const SequenceLayoutEntry& layout : layouts)
    if (layout.probe(dir)) return layout;
  std::string looked_for;  // "a (x), b (y) and c (z)"
  for (std::size_t i = 0; i < layouts.size(); ++i)
    looked_for += std::string(i == 0 ? "" : i + 1 == layouts.size() ? " and " : ", ") + layouts[i].looks_for + " (" +
                  layouts[i].name + ")";
  fail(dir, "unknown sequence layout: looked for " + looked_for);
}

}  // namespace

Sequence Sequence::open(const std::string& dir_name, const SequenceOptions& options) {
  const fs::path dir(dir_name);
  if (!fs::exists(dir)) fail(dir, "sequence folder does not exist");
  if (!fs::is_directory(dir)) fail(dir, "not a folder");
  if (!(options.max_depth > 0.0)) fail(dir, "SequenceOptions::max_depth must be positive");
  if (!(options.frame_rate > 0.0)) fail(dir, "SequenceOptions::frame_rate must be positive");

  const SequenceLayoutEntry& layout = detect_layout(dir);
  const auto [d, files] = layout.open(dir, options);
  check_principal_point(dir, d.color_intrinsics, "colour");
  if (!options.grey_without_depth) check_principal_point(dir, d.depth_intrinsics, "depth");
  if (d.stereo) check_principal_point(dir, d.stereo_intrinsics, "stereo colour");
  if (!d.depth_T_color.matrix().allFinite()) fail(dir, "the colour-to-depth transform is not finite");
  Sequence s;
  s.directory_ = dir.string();
  s.layout_ = layout.name;
  s.description_ = d;
  s.max_depth_ = options.max_depth;
  s.grey_without_depth_ = options.grey_without_depth;
  s.files_ = files;
  return s;
}

Frame Sequence::load(int index) const {
  if (index < 0 || index >= size())
    throw std::out_of_range(directory_ + ": frame " + std::to_string(index) + " out of range [0, " +
                            std::to_string(size()) + ")");
  Frame frame;
  frame.index = index;
  frame.timestamp = index / frame_rate();

  const auto add_color = [&](const char* camera, const Intrinsics& intrinsics, const Pose& camera_T_color,
                              const fs::path& file, const char* what) {
    ColorImage color;
    color.camera = camera;
    color.intrinsics = intrinsics;
    color.camera_T_reference = camera_T_color;
    color.image = read_color_image(file);
    check_size(color.image, intrinsics, file, what, files_->size_origin());
    if (grey_without_depth_) cv::cvtColor(color.image, color.image, cv::COLOR_BGR2GRAY);
    frame.colors.push_back(std::move(color));
  };
  add_color(kColorCamera, color_intrinsics(), Pose(), files_->color_file(index), "colour image");
  if (has_stereo())
    add_color(kStereoCamera, stereo_intrinsics(), stereo_T_color(), files_->stereo_color_file(index),
              "stereo colour image");
  frame.ground_truth = files_->read_ground_truth(index);
  frame.joint_ground_truth = files_->read_joint_truth(index);
  if (grey_without_depth_) return frame;

  DepthImage depth;
  depth.camera = kDepthCamera;
  depth.intrinsics = depth_intrinsics();
  depth.camera_T_reference = depth_T_color();
  depth.depth = files_->read_depth(index);
  check_size(depth.depth, depth_intrinsics(), files_->depth_file(index), "depth image", files_->size_origin());
  clear_invalid_depth(depth.depth, max_depth_);
  frame.depths.push_back(std::move(depth));
  return frame;
}

}  // namespace icgp
