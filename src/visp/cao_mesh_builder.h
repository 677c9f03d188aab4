// SPDX-License-Identifier: GPL-2.0-or-later
// The icgp mesh of what ViSP's .cao / .wrl parser reads, for icgp::load_cao_mesh and for
// vpMbIcgTracker, whose own parse of the model is the only one.
#pragma once

#include <functional>
#include <string>

#include "icgp/base/mesh.h"
#include "icgp/base/pose.h"
#include "icgp/visp/cao_mesh_loader.h"

class vpMbtPolygon;
class vpPoint;

namespace icgp {

/// ViSP's parser only exists as vpMbTracker::loadModel calling back the tracker's init* hooks
/// with each primitive, its points in the model frame (load() transforms applied, and for
/// .cao files loadModel's T). A tracker forwards its hooks here (initFaceFromCorners and
/// initFaceFromLines to add_face, initCylinder, initCircle) and runs its loadModel call
/// through build(), which returns one MeshPart triangulated as load_cao_mesh describes.
class CaoMeshBuilder {
 public:
  /// `path` names the model in messages. `undo` is taken off every point called back before
  /// it is meshed (X = undo^-1 P): the model transform ViSP applied when the caller wants the
  /// mesh made in the file's frame and placed afterwards. Identity meshes the points as called
  /// back. Curved primitives are faceted in the frame they are meshed in.
  CaoMeshBuilder(std::string path, const CaoTessellation& tessellation, const Pose& undo = Pose());

  void add_face(vpMbtPolygon& polygon);
  void add_cylinder(const vpPoint& p1, const vpPoint& p2, double radius, const std::string& name);
  void add_circle(const vpPoint& p1, const vpPoint& p2, const vpPoint& p3, double radius, const std::string& name);

  /// Runs `parse` (the loadModel call whose hooks reach this builder; called once) and
  /// returns what was meshed, with `path` as its source. ViSP reports parse details on
  /// std::cerr, which is captured during the call (other threads should not write to it
  /// meanwhile) and written out again after a successful parse. Throws std::runtime_error
  /// "cannot load ViSP model '<path>': ..." when ViSP throws (with what it reported), when a
  /// primitive cannot be meshed (the first one, named by kind, ordinal and name) or when
  /// nothing was meshed.
  Mesh build(const std::function<void()>& parse);

 private:
  Eigen::Vector3d meshed(const vpPoint& p) const;
  /// Runs `add`, keeping the first error: exceptions must not cross ViSP's parser, which
  /// would replace them with its generic "cannot read line".
  template <typename Add>
  void collect(const std::string& kind, int ordinal, const std::string& name, Add&& add);

  std::string path_;
  CaoTessellation tessellation_;
  Pose undo_;
  Mesh mesh_;
  int faces_ = 0, cylinders_ = 0, circles_ = 0;
  std::string first_error_;
};

}  // namespace icgp
