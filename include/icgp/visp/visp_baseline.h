// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "icgp/base/frame.h"
#include "icgp/base/pose.h"
#include "icgp/eval/sequence_run.h"

class vpMbGenericTracker;

namespace icgp {

/// Which of its features ViSP's vpMbGenericTracker combines: moving edges and KLT points
/// on the colour camera, dense depth on the depth camera.
struct VispTrackerConfiguration {
  std::string name;  ///< e.g. "edge + dense depth"
  bool edge = false;
  bool klt = false;
  bool dense_depth = false;
};

/// The configurations of ViSP's own results in tests/data/README.md, in its table order:
/// edge + dense depth, KLT + dense depth, edge + KLT + dense depth, edge + KLT (no depth).
std::vector<VispTrackerConfiguration> visp_reference_configurations();
/// The one of visp_reference_configurations() called `name` (e.g. "edge + dense depth");
/// throws std::invalid_argument naming it when there is none.
VispTrackerConfiguration visp_reference_configuration(const std::string& name);

/// A ViSP model and the tracker settings that go with it.
struct VispModelFiles {
  std::string model;         ///< .cao
  std::string color_config;  ///< ViSP XML of the colour camera (moving edges, KLT, faces, camera)
  std::string depth_config;  ///< ViSP XML of the depth camera (dense depth sampling, faces, camera)

  /// `<stem>.xml` and `<stem>_depth.xml` beside `<stem>.cao`: how ViSP's tutorials and both
  /// data sets arrange them. Throws std::runtime_error naming a missing file.
  static VispModelFiles beside_model(const std::string& cao_path);
  /// For an object known only as a mesh (any format load_any_mesh reads): `dir`/model.cao
  /// written from it (write_cao) and ViSP settings for edges, KLT and dense depth (those of
  /// ViSP's teabox tutorial, for objects of 5-20 cm at about half a metre) as model.xml and
  /// model_depth.xml. `dir` is created; its earlier files are replaced. Throws
  /// std::runtime_error naming a file that cannot be read or written.
  static VispModelFiles written_for_mesh(const std::string& mesh_path, const std::string& dir);
};

/// vpMbGenericTracker set up for `configuration` as a ViSP user does before giving it a
/// model: colour camera "Camera1" with edges and/or KLT and, with dense depth, depth camera
/// "Camera2", each with its settings from `files`' XML. Throws std::invalid_argument for a
/// configuration without any feature or without a colour feature (the colour camera is the
/// reference camera), and whatever ViSP throws (vpException) for unreadable files.
std::unique_ptr<vpMbGenericTracker> make_visp_tracker(const VispTrackerConfiguration& configuration,
                                                      const VispModelFiles& files);

/// ViSP's vpMbGenericTracker run exactly as a ViSP user runs it on RGB-D data: colour camera
/// "Camera1" (edges and/or KLT on the grey image), depth camera "Camera2" (dense depth on an
/// organised point cloud), settings from the model's two XML files, the .cao for both
/// cameras, depth_M_color as Camera2's transformation. The calibration of the frames
/// overrides the XML's camera blocks, so ViSP sees the same cameras as icgp.
class VispRgbdTracker {
 public:
  /// Loads the settings and the model. Throws std::invalid_argument for a configuration
  /// without any feature, and whatever ViSP throws (vpException) for unreadable files.
  VispRgbdTracker(const VispTrackerConfiguration& configuration, const VispModelFiles& files);
  ~VispRgbdTracker();
  VispRgbdTracker(const VispRgbdTracker&) = delete;
  VispRgbdTracker& operator=(const VispRgbdTracker&) = delete;

  /// Takes the cameras from `frame` (colours[0] and, with depth, depths[0]) and initialises
  /// at `reference_T_body` (cMo) with vpMbGenericTracker::initFromPose.
  void start(const Frame& frame, const Pose& reference_T_body);
  /// Tracks one frame and returns cMo. `track_ms` receives the duration of
  /// vpMbGenericTracker::track alone: image conversion and the point cloud are excluded.
  Pose track(const Frame& frame, double* track_ms = nullptr);

  /// This tracker as run_sequence drives it. ViSP throws when it cannot track (too few
  /// features): that frame is lost and keeps the last pose.
  RunTracker as_run_tracker();

 private:
  void convert(const Frame& frame);

  struct Buffers;
  VispTrackerConfiguration configuration_;
  std::unique_ptr<vpMbGenericTracker> tracker_;
  std::unique_ptr<Buffers> buffers_;
  Pose last_;  ///< the pose a frame ViSP could not track keeps
};

}  // namespace icgp
