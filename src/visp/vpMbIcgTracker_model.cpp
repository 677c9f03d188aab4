// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker's model: loading a model file (ViSP's .cao / .wrl through ViSP's own parser
// and its init* hooks, other meshes through assimp), taking back a parse whose file does not
// load, reInitModel, and ViSP's faces of the model.
#include <algorithm>
#include <functional>
#include <iostream>
#include <new>

#include "icgp/io/file_extension.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/conversions.h"

#include "cao_mesh_builder.h"
#include "vpMbIcgTracker_impl.h"

using icgp::visp_detail::guarded;
using icgp::visp_detail::require_file;
using icgp::visp_detail::require_known_cameras;

namespace {

/// .cao and .wrl: the files ViSP's own parser reads (vpMbTracker::loadModel).
bool is_visp_model(const std::string& path) {
  const std::string extension = icgp::lower_extension(path);
  return extension == ".cao" || extension == ".wrl";
}

/// The mesh of a model file, T X for its points X, as icgp::load_any_mesh makes it. Given
/// `visp_parse`, a .cao or .wrl file is parsed by it instead: a vpMbTracker::loadModel(path,
/// verbose, T) call of a tracker whose init* hooks feed the builder it is handed.
icgp::Mesh load_model_file(const std::string& path, const vpHomogeneousMatrix& T,
                           const std::function<void(icgp::CaoMeshBuilder&)>& visp_parse = {}) {
  require_file(path, "model file");
  try {
    if (!visp_parse || !is_visp_model(path)) return icgp::load_any_mesh(path, 1.0, icgp::to_pose(T));
    // As load_any_mesh: meshed in the file's frame, then placed with T. ViSP has already
    // applied T to the points of a .cao file (not of a .wrl), so the builder takes it off.
    const icgp::Pose pose = icgp::to_pose(T);
    icgp::CaoMeshBuilder builder(path, {}, icgp::lower_extension(path) == ".cao" ? pose : icgp::Pose());
    icgp::Mesh mesh = builder.build([&] { visp_parse(builder); });
    mesh.transform(pose.cast<float>());
    return mesh;
  } catch (const std::bad_alloc&) {
    throw;  // the file is too large, not wrong: guarded says out of memory
  } catch (const std::exception& e) {
    throw vpException(vpException::badValue, "vpMbIcgTracker::loadModel: cannot load '" + path +
                                                 "' (.cao, .wrl, or a mesh format assimp reads): " + e.what());
  }
}

/// ViSP's model in a vpMbTracker as it stands (the faces, and the faces, lines, cylinders and
/// circles of its projection-error model), so that restore() can take back what a model
/// file's parse added when that file turns out not to load.
class VispModelMark {
 public:
  VispModelMark(vpMbHiddenFaces<vpMbtPolygon>& faces, vpMbHiddenFaces<vpMbtPolygon>& error_faces,
                std::vector<vpMbtDistanceLine*>& error_lines, std::vector<vpMbtDistanceCylinder*>& error_cylinders,
                std::vector<vpMbtDistanceCircle*>& error_circles, bool& model_initialised, std::string& model_file)
      : faces_(faces.getPolygon()),
        error_faces_(error_faces.getPolygon()),
        error_lines_(error_lines),
        error_cylinders_(error_cylinders),
        error_circles_(error_circles),
        model_initialised_(model_initialised),
        model_file_(model_file),
        n_faces_(faces_.size()),
        n_error_faces_(error_faces_.size()),
        n_error_cylinders_(error_cylinders.size()),
        n_error_circles_(error_circles.size()),
        was_initialised_(model_initialised),
        previous_file_(model_file) {
    // A new face sharing an edge with an earlier one adds its index to that edge's line.
    for (const vpMbtDistanceLine* line : error_lines) line_polygons_.push_back(line->Lindex_polygon.size());
  }

  void restore() const {
    truncate(faces_, n_faces_);
    truncate(error_faces_, n_error_faces_);
    truncate(error_lines_, line_polygons_.size());
    for (std::size_t i = 0; i < line_polygons_.size(); ++i) {
      vpMbtDistanceLine& line = *error_lines_[i];
      line.Lindex_polygon.resize(line_polygons_[i]);
      line.Lindex_polygon_tracked.resize(line_polygons_[i]);
    }
    truncate(error_cylinders_, n_error_cylinders_);
    truncate(error_circles_, n_error_circles_);
    model_initialised_ = was_initialised_;
    model_file_ = previous_file_;
  }

 private:
  template <typename T>
  static void truncate(std::vector<T*>& owned, std::size_t size) {
    for (std::size_t i = size; i < owned.size(); ++i) delete owned[i];
    owned.resize(size);
  }

  std::vector<vpMbtPolygon*>& faces_;
  std::vector<vpMbtPolygon*>& error_faces_;
  std::vector<vpMbtDistanceLine*>& error_lines_;
  std::vector<vpMbtDistanceCylinder*>& error_cylinders_;
  std::vector<vpMbtDistanceCircle*>& error_circles_;
  bool& model_initialised_;
  std::string& model_file_;
  std::size_t n_faces_, n_error_faces_, n_error_cylinders_, n_error_circles_;
  std::vector<std::size_t> line_polygons_;  ///< polygons of each line there was
  bool was_initialised_;
  std::string previous_file_;
};

/// One object is tracked by every camera, with the reference camera's model. Another
/// camera's file should describe the same object (ViSP's programs give a .wrl and a .cao
/// of it); when the bounding boxes differ by more than 1 % of the object's size, that is
/// said on std::cerr: ViSP would track a different model in that camera.
void check_same_object(const icgp::Mesh& reference, const std::string& reference_file, const icgp::Mesh& other,
                       const std::string& other_file) {
  Eigen::Vector3f lo_a, hi_a, lo_b, hi_b;
  reference.bounds(lo_a, hi_a);
  other.bounds(lo_b, hi_b);
  const float size = (hi_a - lo_a).norm();
  const float gap = std::max((lo_a - lo_b).cwiseAbs().maxCoeff(), (hi_a - hi_b).cwiseAbs().maxCoeff());
  if (!(gap <= 0.01f * size))
    std::cerr << "vpMbIcgTracker::loadModel: '" << other_file << "' does not describe the object of '"
              << reference_file << "' (their bounding boxes differ by " << gap << " m, more than 1 % of the object's "
              << "size " << size << " m); one rigid object is tracked by every camera, with '" << reference_file
              << "'\n";
}


}  // namespace

// --------------------------------------------------------------------------------- model

void vpMbIcgTracker::loadModel(const std::string& modelFile, bool verbose, const vpHomogeneousMatrix& T) {
  const std::string& camera = impl_->rig.reference();
  loadModel(std::map<std::string, std::string>{{camera, modelFile}}, verbose,
            std::map<std::string, vpHomogeneousMatrix>{{camera, T}});
}

void vpMbIcgTracker::loadModel(const std::string& modelFile1, const std::string& modelFile2, bool verbose,
                               const vpHomogeneousMatrix& T1, const vpHomogeneousMatrix& T2) {
  const auto [first, second] = impl_->rig.pair("loadModel");
  loadModel(std::map<std::string, std::string>{{first, modelFile1}, {second, modelFile2}}, verbose,
            std::map<std::string, vpHomogeneousMatrix>{{first, T1}, {second, T2}});
}

void vpMbIcgTracker::loadModel(const std::map<std::string, std::string>& mapOfModelFiles, bool verbose,
                               const std::map<std::string, vpHomogeneousMatrix>& mapOfT) {
  guarded("loadModel", [&] {
    const icgp::CameraRig& rig = impl_->rig;
    for (const auto& [camera, file] : mapOfModelFiles) rig.at(camera, "loadModel");
    for (const auto& [camera, T] : mapOfT) rig.at(camera, "loadModel");
    if (mapOfModelFiles.empty())
      throw vpException(vpException::badValue, "vpMbIcgTracker::loadModel: no model file given");
    // The reference camera's file is the object; any other camera's must be the same object.
    const auto transform = [&](const std::string& camera) {
      const auto it = mapOfT.find(camera);
      return it == mapOfT.end() ? vpHomogeneousMatrix() : it->second;
    };
    const auto main = mapOfModelFiles.count(rig.reference()) ? mapOfModelFiles.find(rig.reference())
                                                             : mapOfModelFiles.begin();
    const std::string& modelFile = main->second;
    Impl& d = *impl_;

    // A .cao or .wrl file is parsed once, by ViSP's parser in this tracker: vpMbTracker fills
    // `faces` and the projection-error model (so that getPolygonFaces and
    // computeCurrentProjectionError mean what they mean for ViSP's trackers) and calls the init*
    // hooks with each primitive, which d.cao_builder meshes.
    const VispModelMark visp_model(faces, m_projectionErrorFaces, m_projectionErrorLines, m_projectionErrorCylinders,
                                   m_projectionErrorCircles, modelInitialised, modelFileName);
    const auto parse_here = [&](icgp::CaoMeshBuilder& builder) {
      // The hooks feed `builder` for this parse only, whether it returns or throws.
      d.cao_builder = &builder;
      struct Unhook {
        icgp::CaoMeshBuilder*& hooks;
        ~Unhook() { hooks = nullptr; }
      } const unhook{d.cao_builder};
      vpMbTracker::loadModel(modelFile, verbose, transform(main->first));
    };
    icgp::Mesh part;
    try {
      part = load_model_file(modelFile, transform(main->first), parse_here);
      for (const auto& [camera, file] : mapOfModelFiles) {
        if (camera == main->first || file.empty()) continue;
        if (file == modelFile && transform(camera) == transform(main->first)) continue;
        check_same_object(part, modelFile, load_model_file(file, transform(camera)), file);
      }
    } catch (...) {
      visp_model.restore();  // the object is as it was
      throw;
    }

    if (is_visp_model(modelFile)) d.has_visp_model_part = true;
    d.mesh.source = d.mesh.source.empty() ? modelFile : d.mesh.source + "+" + modelFile;
    for (icgp::MeshPart& p : part.parts) d.mesh.parts.push_back(std::move(p));
    d.model_changed();
    modelInitialised = true;
    if (verbose) {
      std::size_t triangles = 0;
      for (const icgp::MeshPart& p : d.mesh.parts) triangles += p.triangles.size();
      std::cout << "vpMbIcgTracker: model " << modelFile << " loaded; the object has " << d.mesh.parts.size()
                << " part(s), " << triangles << " triangles\n";
    }
  });
}

namespace {

template <typename T>
void delete_all(std::vector<T*>& owned) {
  for (T* p : owned) delete p;
  owned.clear();
}

}  // namespace

void vpMbIcgTracker::clear_model() {
  impl_->mesh = icgp::Mesh();
  impl_->has_visp_model_part = false;
  impl_->model_changed();
  faces.reset();
  // vpMbTracker owns the projection-error model its parser filled, and only its destructor
  // deletes it: a model loaded next would otherwise add to the old one's edges.
  m_projectionErrorFaces.reset();
  delete_all(m_projectionErrorLines);
  delete_all(m_projectionErrorCylinders);
  delete_all(m_projectionErrorCircles);
}

void vpMbIcgTracker::reInitModel(const vpImage<unsigned char>& I, const std::string& cad_name,
                                 const vpHomogeneousMatrix& cMo, bool verbose, const vpHomogeneousMatrix& T) {
  clear_model();
  loadModel(cad_name, verbose, T);
  initFromPose(I, cMo);
}

void vpMbIcgTracker::reInitModel(const vpImage<vpRGBa>& I_color, const std::string& cad_name,
                                 const vpHomogeneousMatrix& cMo, bool verbose, const vpHomogeneousMatrix& T) {
  clear_model();
  loadModel(cad_name, verbose, T);
  initFromPose(I_color, cMo);
}

void vpMbIcgTracker::reInitModel(const vpImage<unsigned char>& I1, const vpImage<unsigned char>& I2,
                                 const std::string& cad_name1, const std::string& cad_name2,
                                 const vpHomogeneousMatrix& c1Mo, const vpHomogeneousMatrix& c2Mo, bool verbose,
                                 const vpHomogeneousMatrix& T1, const vpHomogeneousMatrix& T2) {
  const auto [first, second] = impl_->rig.pair("reInitModel");
  reInitModel(std::map<std::string, const vpImage<unsigned char>*>{{first, &I1}, {second, &I2}},
              {{first, cad_name1}, {second, cad_name2}}, {{first, c1Mo}, {second, c2Mo}}, verbose,
              {{first, T1}, {second, T2}});
}

void vpMbIcgTracker::reInitModel(const vpImage<vpRGBa>& I_color1, const vpImage<vpRGBa>& I_color2,
                                 const std::string& cad_name1, const std::string& cad_name2,
                                 const vpHomogeneousMatrix& c1Mo, const vpHomogeneousMatrix& c2Mo, bool verbose,
                                 const vpHomogeneousMatrix& T1, const vpHomogeneousMatrix& T2) {
  const auto [first, second] = impl_->rig.pair("reInitModel");
  reInitModel(std::map<std::string, const vpImage<vpRGBa>*>{{first, &I_color1}, {second, &I_color2}},
              {{first, cad_name1}, {second, cad_name2}}, {{first, c1Mo}, {second, c2Mo}}, verbose,
              {{first, T1}, {second, T2}});
}

void vpMbIcgTracker::reInitModel(const std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                                 const std::map<std::string, std::string>& mapOfModelFiles,
                                 const std::map<std::string, vpHomogeneousMatrix>& mapOfCameraPoses, bool verbose,
                                 const std::map<std::string, vpHomogeneousMatrix>& mapOfT) {
  require_known_cameras(impl_->rig, "reInitModel", mapOfImages, mapOfModelFiles, mapOfCameraPoses, mapOfT);
  clear_model();
  loadModel(mapOfModelFiles, verbose, mapOfT);
  initFromPose(mapOfImages, mapOfCameraPoses);
}

void vpMbIcgTracker::reInitModel(const std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
                                 const std::map<std::string, std::string>& mapOfModelFiles,
                                 const std::map<std::string, vpHomogeneousMatrix>& mapOfCameraPoses, bool verbose,
                                 const std::map<std::string, vpHomogeneousMatrix>& mapOfT) {
  require_known_cameras(impl_->rig, "reInitModel", mapOfColorImages, mapOfModelFiles, mapOfCameraPoses, mapOfT);
  clear_model();
  loadModel(mapOfModelFiles, verbose, mapOfT);
  initFromPose(mapOfColorImages, mapOfCameraPoses);
}

vpMbHiddenFaces<vpMbtPolygon>& vpMbIcgTracker::getFaces(const std::string& cameraName) {
  impl_->rig.at(cameraName, "getFaces");
  return faces;
}

void vpMbIcgTracker::getNbPolygon(std::map<std::string, unsigned int>& mapOfNbPolygons) const {
  mapOfNbPolygons.clear();
  for (const std::string& camera : impl_->rig.names()) mapOfNbPolygons[camera] = getNbPolygon();
}

vpMbtPolygon* vpMbIcgTracker::getPolygon(const std::string& cameraName, unsigned int index) {
  impl_->rig.at(cameraName, "getPolygon");
  return getPolygon(index);
}

std::pair<std::vector<vpPolygon>, std::vector<std::vector<vpPoint>>> vpMbIcgTracker::getPolygonFaces(
    bool orderPolygons, bool useVisibility, bool clipPolygon) {
  // icgp's cues need no face visibility (the viewpoint models have it), so it is computed
  // only when asked for.
  if (useVisibility) {
    bool changed = false;
    faces.setVisible(m_cMo, angleAppears, angleDisappears, changed);
  }
  return vpMbTracker::getPolygonFaces(orderPolygons, useVisibility, clipPolygon);
}

void vpMbIcgTracker::getPolygonFaces(std::map<std::string, std::vector<vpPolygon>>& mapOfPolygons,
                                     std::map<std::string, std::vector<std::vector<vpPoint>>>& mapOfPoints,
                                     bool orderPolygons, bool useVisibility, bool clipPolygon) {
  // vpMbTracker computes the faces of its own camera and pose: each camera's in turn.
  const vpHomogeneousMatrix cMo = m_cMo;
  const vpCameraParameters cam = m_cam;
  mapOfPolygons.clear();
  mapOfPoints.clear();
  for (const auto& [name, camera] : impl_->rig.cameras()) {
    m_cMo = camera.camera_M_reference * cMo;
    m_cam = camera.parameters;
    auto polygons = getPolygonFaces(orderPolygons, useVisibility, clipPolygon);
    mapOfPolygons[name] = std::move(polygons.first);
    mapOfPoints[name] = std::move(polygons.second);
  }
  m_cMo = cMo;
  m_cam = cam;
}

// ------------------------------------------------------ ViSP's .cao / .wrl parser hooks
// vpMbTracker has put each primitive in `faces` and in the projection-error model before it
// calls these; outside loadModel there is nothing to mesh.

void vpMbIcgTracker::initCircle(const vpPoint& p1, const vpPoint& p2, const vpPoint& p3, double radius, int,
                                const std::string& name) {
  if (impl_->cao_builder) impl_->cao_builder->add_circle(p1, p2, p3, radius, name);
}

void vpMbIcgTracker::initCylinder(const vpPoint& p1, const vpPoint& p2, double radius, int, const std::string& name) {
  if (impl_->cao_builder) impl_->cao_builder->add_cylinder(p1, p2, radius, name);
}

void vpMbIcgTracker::initFaceFromCorners(vpMbtPolygon& polygon) {
  if (impl_->cao_builder) impl_->cao_builder->add_face(polygon);
}

void vpMbIcgTracker::initFaceFromLines(vpMbtPolygon& polygon) {
  if (impl_->cao_builder) impl_->cao_builder->add_face(polygon);
}
