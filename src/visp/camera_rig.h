// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>
#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>

#include "icgp/tracker/tracker_builder.h"

namespace icgp {

/// The cameras of a vpMbIcgTracker, named and typed as vpMbGenericTracker's: each has
/// tracker-type bits (which cues read it), its parameters, and its pose relative to the
/// reference camera, in whose frame cMo is expressed. Names are kept sorted, as in ViSP's
/// map of trackers, so "the first and the second camera" mean what they mean there.
/// Unknown names and invalid types throw vpException naming the call.
class CameraRig {
 public:
  /// The tracker types a camera may have: vpMbGenericTracker's, as icgp::visp_type's bits.
  static constexpr int kAllTypes = visp_type::kEdge | visp_type::kKlt | visp_type::kDepth;

  struct Camera {
    int types = 0;
    vpCameraParameters parameters;
    bool parameters_set = false;  ///< ViSP silently uses its default camera; icgp refuses to
    vpHomogeneousMatrix camera_M_reference;
    /// ViSP's sampling steps of its dense and normal depth features (setters or XML), for
    /// icgp's dense depth; none: the configuration's.
    std::optional<SamplingStep> dense_step, normal_step;
  };

  /// ViSP's names for n cameras: "Camera" for one, "Camera1" ... "CameraN" otherwise.
  static std::vector<std::string> visp_names(std::size_t n);

  /// Cameras `names` with `types`; the reference camera is the first name in sorted order,
  /// as in ViSP ("Camera" or "Camera1" for its own names).
  CameraRig(const std::vector<std::string>& names, const std::vector<int>& types);

  const std::string& reference() const { return reference_; }
  void set_reference(const std::string& name);
  std::vector<std::string> names() const;
  std::size_t size() const { return cameras_.size(); }
  const std::map<std::string, Camera>& cameras() const { return cameras_; }

  Camera& at(const std::string& name, const std::string& call);
  const Camera& at(const std::string& name, const std::string& call) const;
  Camera& reference_camera() { return cameras_.at(reference_); }
  const Camera& reference_camera() const { return cameras_.at(reference_); }
  /// The names of the first and second camera, for ViSP's two-camera overloads; throws
  /// unless the rig has exactly two.
  std::pair<std::string, std::string> pair(const std::string& call) const;

  void set_types(const std::string& name, int types, const std::string& call);

  /// Each camera with its tracker types, which decide the cues that read it (the cue
  /// registry's visp_types: EDGE → region and edge, KLT → texture and flow, DEPTH_NORMAL or
  /// DEPTH_DENSE → depth, of the selected modalities). A colour camera looks for occlusions
  /// in its own depth when it has a depth type, else in the first depth camera. Dense depth
  /// samples with the camera's dense step when it has DEPTH_DENSE, with its normal step
  /// when it has DEPTH_NORMAL alone.
  std::vector<CameraCues> cues() const;
  /// Has a depth type (its depth may serve for occlusions even if the depth cue is off).
  bool is_depth_camera(const std::string& name) const;

  /// The names as "\"A\", \"B\"", for error messages.
  std::string quoted_names() const;

 private:
  std::map<std::string, Camera> cameras_;
  std::string reference_;
};

}  // namespace icgp
