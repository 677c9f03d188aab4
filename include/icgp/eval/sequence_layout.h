// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"
#include "icgp/geometry/joint.h"

namespace icgp {

struct SequenceOptions;  // icgp/eval/sequence.h

/// An object of a sequence: the name its ground truth is stored under and, when known,
/// the mesh or ViSP model file describing it; for a link of an articulated object, the
/// joint it hangs from its parent (an object listed before it) by.
struct SequenceObject {
  std::string name;
  std::string mesh_path;
  std::optional<Joint> joint;
};

/// Reads the frame files of one sequence layout. Sequence::load checks the image sizes,
/// converts to grey and clears invalid depth, so a layout only finds and decodes files.
class SequenceLayout {
 public:
  virtual ~SequenceLayout() = default;
  virtual std::filesystem::path color_file(int index) const = 0;
  virtual std::filesystem::path depth_file(int index) const = 0;
  /// The second colour camera's image (layouts that have one).
  virtual std::filesystem::path stereo_color_file(int) const { return {}; }
  /// Metres as stored, invalid values not yet cleared; CV_32FC1.
  virtual cv::Mat read_depth(int index) const = 0;
  virtual std::map<std::string, Pose> read_ground_truth(int index) const = 0;
  /// The joint values of each link (layouts that have links).
  virtual std::map<std::string, std::vector<double>> read_joint_truth(int) const { return {}; }
  /// Where the expected image sizes came from, for messages.
  virtual std::string size_origin() const = 0;
};

/// Everything a layout's open learns about a sequence besides how to read its frames: what
/// Sequence's accessors of the same names return (frame_count: size(), stereo:
/// has_stereo()). Sequence::open checks the principal points against the image sizes and
/// that depth_T_color is finite.
struct SequenceDescription {
  int frame_count = 0;
  double frame_rate = 0.0;
  Intrinsics color_intrinsics, depth_intrinsics;
  Pose depth_T_color;
  bool stereo = false;
  Intrinsics stereo_intrinsics;
  Pose stereo_T_color;
  std::vector<SequenceObject> objects;
  bool has_ground_truth = false;
};

/// A layout Sequence::open can detect and read.
struct SequenceLayoutEntry {
  using Opened = std::pair<SequenceDescription, std::shared_ptr<const SequenceLayout>>;

  /// Sequence::layout() of its sequences.
  std::string name;
  /// What `probe` looks for, e.g. "sequence.yaml": the message for a folder no layout
  /// recognises lists it as "looked for <looks_for> (<name>)".
  std::string looks_for;
  /// Whether `folder` has this layout, from the names of its files: once a layout answers
  /// yes, its open reports what is wrong inside rather than another layout being tried.
  std::function<bool(const std::filesystem::path& folder)> probe;
  /// Reads the description and makes the frame reader, checking that every frame's files
  /// are there; throws std::runtime_error naming the file and what was expected.
  std::function<Opened(const std::filesystem::path& folder, const SequenceOptions& options)> open;
};

/// The layouts Sequence::open detects, probed in registry order: the built-in ones ("icgp",
/// "visp-blender", "visp-realsense", in that order; each described in its file,
/// src/eval/icgp_layout.cpp, visp_blender_layout.cpp, visp_realsense_layout.cpp), then
/// those a program adds. Not thread-safe to add while others read: add at start-up.
class SequenceLayouts {
 public:
  /// The process's registry, with the built-in layouts.
  static SequenceLayouts& instance();

  /// Adds `entry` last. Throws std::invalid_argument for an empty or taken name, or no
  /// probe or open.
  void add(SequenceLayoutEntry entry);
  const std::vector<SequenceLayoutEntry>& entries() const { return entries_; }

 private:
  SequenceLayouts();
  std::vector<SequenceLayoutEntry> entries_;
};

}  // namespace icgp
