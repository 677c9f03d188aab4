// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "icgp/base/frame.h"
#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"
#include "icgp/geometry/joint.h"

namespace icgp {

struct SequenceOptions {
  /// ViSP XML files whose <camera> block holds the colour / depth intrinsics (px, py, u0,
  /// v0). Only the ViSP layouts use them. Empty = detect (see Sequence::open). When only
  /// the colour file is given, the depth file defaults to "<stem>_depth.xml" beside it.
  std::string color_intrinsics_file;
  std::string depth_intrinsics_file;
  /// Reads px, py, u0, v0 of such a file's <camera> block into fu, fv, pu, pv (image size
  /// left 0), throwing std::runtime_error naming the file and what is wrong. The ViSP
  /// layouts need it and the core library does not parse ViSP's XML: icgp::visp provides
  /// read_visp_camera_xml (icgp/visp/visp_camera_xml.h, also visp_sequence_options()).
  std::function<Intrinsics(const std::string& xml_path)> read_camera_xml;
  /// Depth beyond this (metres) is treated as no measurement, like NaN and inf: Blender
  /// writes a huge Z on the background and real sensors report far outliers.
  double max_depth = 10.0;
  /// For "visp-blender" sequences: read the XML's principal point as Blender defines it
  /// (pixel-edge coordinates) and subtract 0.5 px to get ViSP's pixel-centre convention.
  /// Off by default: intrinsics are read exactly as the data's files write them, as ViSP
  /// reads them; benchmarks that turn it on give the corrected cameras to every tracker.
  bool blender_principal_point = false;
  /// Frames per second for layouts that do not record it (the ViSP ones).
  double frame_rate = 30.0;
  /// Load frames as a monocular grey camera gives them: the colour image converted to grey
  /// and no depth camera (ViSP's classic model-based set-up, without depth).
  bool grey_without_depth = false;
};

/// An object of a sequence: the name its ground truth is stored under and, when known,
/// the mesh or ViSP model file describing it; for a link of an articulated object, the
/// joint it hangs from its parent (an object listed before it) by.
struct SequenceObject {
  std::string name;
  std::string mesh_path;
  std::optional<Joint> joint;
};

/// An RGB-D image sequence on disk, read frame by frame into icgp::Frame.
///
/// Layouts, detected from the files in the folder (in this order):
///  * "icgp" — `sequence.yaml` (see SequenceWriter): color/%06d.png, depth/%06d.png
///    (uint16, Z = value * depth_scale), ground truth poses/<object>.txt; when the YAML has
///    stereo_camera and stereo_T_color, a second colour camera's color2/%06d.png; links
///    (objects with a parent and a joint, io/joint_yaml.h) whose joint has free
///    directions have their joint values in joints/<object>.txt (Frame::joint_truth).
///  * "visp-blender" — images/%04d.jpg from 0001, depth/Image%04d.exr (channel 0 = Z),
///    ground truth camera_poses/Camera_%03d.txt (cMo, 4x4) named after the single
///    top-level .cao file, depth_M_color.txt.
///  * "visp-realsense" — color_image_%04d.jpg from 0000, depth_image_%04d.bin
///    (little-endian uint32 height, uint32 width, H*W uint16, Z = value * 1 mm),
///    depth_M_color.txt, no ground truth.
///
/// Intrinsics of the ViSP layouts come from the <camera> block of ViSP XML files, read by
/// SequenceOptions::read_camera_xml (without one, open() fails saying so): the explicit
/// SequenceOptions files, else the only `<name>.xml` + `<name>_depth.xml` pair at the top
/// level, else the only such pair in a `models/*/` subfolder. Several candidate
/// pairs are ambiguous (a models/ folder often holds objects filmed with other cameras),
/// so open() then fails listing them rather than guessing. The image size is that of the
/// first colour (depth) image; every frame is checked against it.
///
/// Frames: colour camera "Camera1" (the reference, identity pose), depth camera "Camera2"
/// with camera_T_reference = depth_T_color, depth CV_32F metres with 0 where there is no
/// valid measurement (0, NaN, inf, or > max_depth); in a stereo sequence a second colour
/// camera "Camera3" after "Camera1" in Frame::colors, with camera_T_reference =
/// stereo_T_color (grey too with grey_without_depth). Every bad input throws
/// std::runtime_error naming the file and what was expected.
class Sequence {
 public:
  static Sequence open(const std::string& dir, const SequenceOptions& options = {});

  const std::string& directory() const { return directory_; }
  /// "icgp", "visp-blender" or "visp-realsense".
  const std::string& layout() const { return layout_; }
  int size() const { return frame_count_; }
  double frame_rate() const { return frame_rate_; }
  const Intrinsics& color_intrinsics() const { return color_intrinsics_; }
  const Intrinsics& depth_intrinsics() const { return depth_intrinsics_; }
  /// Colour camera -> depth camera (ViSP depth_M_color).
  const Pose& depth_T_color() const { return depth_T_color_; }
  /// Whether frames have the second colour camera "Camera3" (icgp layout with color2/).
  bool has_stereo() const { return has_stereo_; }
  /// Its calibration and pose (colour camera -> stereo camera, ViSP c3_M_c1); only
  /// meaningful with has_stereo().
  const Intrinsics& stereo_intrinsics() const { return stereo_intrinsics_; }
  const Pose& stereo_T_color() const { return stereo_T_color_; }
  const std::vector<SequenceObject>& objects() const { return objects_; }
  bool has_ground_truth() const { return has_ground_truth_; }

  /// Reads frame `index` in [0, size()). Frame::index is `index`, the timestamp
  /// index / frame_rate().
  Frame load(int index) const;

  /// Reads the files of one layout; defined in sequence.cpp.
  class Layout;

 private:
  Sequence() = default;

  std::string directory_;
  std::string layout_;
  int frame_count_ = 0;
  double frame_rate_ = 0.0;
  double max_depth_ = 0.0;
  bool grey_without_depth_ = false;
  Intrinsics color_intrinsics_;
  Intrinsics depth_intrinsics_;
  Pose depth_T_color_;
  bool has_stereo_ = false;
  Intrinsics stereo_intrinsics_;
  Pose stereo_T_color_;
  std::vector<SequenceObject> objects_;
  bool has_ground_truth_ = false;
  std::shared_ptr<const Layout> files_;
};

/// Reads a 4x4 homogeneous matrix written as 4 lines of 4 numbers (ViSP's cMo and
/// depth_M_color files). Throws std::runtime_error naming the file and line.
Pose read_pose_matrix_file(const std::string& path);

}  // namespace icgp
