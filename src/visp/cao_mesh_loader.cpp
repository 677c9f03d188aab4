// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/visp/cao_mesh_loader.h"

#include <cmath>
#include <stdexcept>
#include <visp3/mbt/vpMbEdgeTracker.h>

#include "icgp/io/cao_file_check.h"
#include "icgp/io/file_extension.h"
#include "icgp/io/mesh_loader.h"
#include "icgp/visp/conversions.h"

#include "cao_mesh_builder.h"

namespace icgp {
namespace {

/// Reaches ViSP's .cao parser, which only exists as vpMbTracker::loadModel calling back a
/// tracker with each primitive: a ViSP tracker whose hooks mesh what it parses instead of
/// making its own features. Only loadModel is ever called.
class CaoGeometryCollector final : public vpMbEdgeTracker {
 public:
  explicit CaoGeometryCollector(CaoMeshBuilder& builder) : builder_(builder) {}

 private:
  void initFaceFromCorners(vpMbtPolygon& polygon) override { builder_.add_face(polygon); }
  void initFaceFromLines(vpMbtPolygon& polygon) override { builder_.add_face(polygon); }
  void initCylinder(const vpPoint& p1, const vpPoint& p2, double radius, int, const std::string& name) override {
    builder_.add_cylinder(p1, p2, radius, name);
  }
  void initCircle(const vpPoint& p1, const vpPoint& p2, const vpPoint& p3, double radius, int,
                  const std::string& name) override {
    builder_.add_circle(p1, p2, p3, radius, name);
  }

  CaoMeshBuilder& builder_;
};

/// .cao and .wrl: the formats ViSP's vpMbTracker::loadModel reads (VRML through Coin3D).
bool has_visp_model_extension(const std::string& path) {
  return is_cao_path(path) || lower_extension(path) == ".wrl";
}

}  // namespace

Mesh load_cao_mesh(const std::string& path, const Pose& T, const CaoTessellation& tessellation) {
  if (tessellation.cylinder_segments < 3 || tessellation.circle_segments < 3 ||
      tessellation.cylinder_segments > CaoTessellation::kMaxSegments || tessellation.circle_segments > CaoTessellation::kMaxSegments)
    throw std::invalid_argument("load_cao_mesh: cylinders and circles need 3 to " + std::to_string(CaoTessellation::kMaxSegments) + " segments (got " +
                                std::to_string(tessellation.cylinder_segments) + " and " +
                                std::to_string(tessellation.circle_segments) + ")");
  CaoMeshBuilder builder(path, tessellation);
  CaoGeometryCollector collector(builder);
  Mesh mesh = builder.build([&] { collector.loadModel(path, false, to_homogeneous_matrix(T)); });
  // ViSP applies the model transform to .cao files only ("currently only for .cao").
  if (has_visp_model_extension(path) && !is_cao_path(path)) mesh.transform(T.cast<float>());
  return mesh;
}

Mesh load_any_mesh(const std::string& path, double scale, const Pose& T) {
  if (!(scale > 0.0) || !std::isfinite(scale))
    throw std::invalid_argument("load_any_mesh: scale must be positive and finite (got " + std::to_string(scale) +
                                ") for '" + path + "'");
  Mesh mesh;
  if (has_visp_model_extension(path)) {
    mesh = load_cao_mesh(path);
    for (MeshPart& part : mesh.parts)
      for (Eigen::Vector3f& v : part.vertices) v *= static_cast<float>(scale);
  } else {
    mesh = load_mesh(path, MeshLoadOptions{scale});
  }
  mesh.transform(T.cast<float>());
  return mesh;
}

}  // namespace icgp
