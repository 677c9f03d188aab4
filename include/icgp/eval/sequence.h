// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "icgp/base/frame.h"
#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"
#include "icgp/eval/sequence_layout.h"

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

/// An RGB-D image sequence on disk, read frame by frame into icgp::Frame.
///
/// Layouts: open() asks the layouts of the registry, SequenceLayouts
/// (icgp/eval/sequence_layout.h), in their order, and the first that recognises the folder
/// reads it. A program may add its own; the built-in ones, each described in its file:
///  * "icgp" (src/eval/icgp_layout.cpp) — `sequence.yaml` (see SequenceWriter), PNG colour
///    and 16-bit PNG depth, ground truth poses and joint values, optionally a stereo camera.
///  * "visp-blender" (src/eval/visp_blender_layout.cpp) — images/ + depth/ folders: JPEG
///    colour, OpenEXR depth, ground truth camera_poses/ for the single top-level .cao file.
///  * "visp-realsense" (src/eval/visp_realsense_layout.cpp) — color_image_0000.jpg: JPEG
///    colour, RealSense .bin depth, no ground truth.
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
  /// The name of its layout (SequenceLayoutEntry::name): "icgp", "visp-blender",
  /// "visp-realsense" or one a program registered.
  const std::string& layout() const { return layout_; }
  int size() const { return description_.frame_count; }
  double frame_rate() const { return description_.frame_rate; }
  const Intrinsics& color_intrinsics() const { return description_.color_intrinsics; }
  const Intrinsics& depth_intrinsics() const { return description_.depth_intrinsics; }
  /// Colour camera -> depth camera (ViSP depth_M_color).
  const Pose& depth_T_color() const { return description_.depth_T_color; }
  /// Whether frames have the second colour camera "Camera3" (icgp layout with color2/).
  bool has_stereo() const { return description_.stereo; }
  /// Its calibration and pose (colour camera -> stereo camera, ViSP c3_M_c1); only
  /// meaningful with has_stereo().
  const Intrinsics& stereo_intrinsics() const { return description_.stereo_intrinsics; }
  const Pose& stereo_T_color() const { return description_.stereo_T_color; }
  const std::vector<SequenceObject>& objects() const { return description_.objects; }
  bool has_ground_truth() const { return description_.has_ground_truth; }

  /// Reads frame `index` in [0, size()). Frame::index is `index`, the timestamp
  /// index / frame_rate().
  Frame load(int index) const;

 private:
  Sequence() = default;

  std::string directory_;
  std::string layout_;
  SequenceDescription description_;
  double max_depth_ = 0.0;
  bool grey_without_depth_ = false;
  std::shared_ptr<const SequenceLayout> files_;
};

/// Reads a 4x4 homogeneous matrix written as 4 lines of 4 numbers (ViSP's cMo and
/// depth_M_color files). Throws std::runtime_error naming the file and line.
Pose read_pose_matrix_file(const std::string& path);

}  // namespace icgp
