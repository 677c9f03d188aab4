// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker: initialisation (initFromPose, initClick, initFromPoints, setPose,
// resetTracker) and the tracker they build.
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/conversions.h"

#include "vpMbIcgTracker_impl.h"

using icgp::visp_detail::guarded;
using icgp::visp_detail::require_known_cameras;
// ------------------------------------------------------------------------ initialisation

void vpMbIcgTracker::build_tracker() {
  Impl& d = *impl_;
  if (d.mesh.parts.empty())
    throw vpTrackingException(vpTrackingException::initializationError,
                              "vpMbIcgTracker::init: no model; call loadModel() before initialising");
  if (d.tracker) return;
  d.cues = d.rig.cues();
  d.tracker = icgp::build_tracker(d.config, d.mesh, Impl::kBody, d.cues, d.renderer,
                                  [](const std::string& file, double scale) { return icgp::load_any_mesh(file, scale); });
  d.recovery = std::make_unique<icgp::Recovery>(*d.tracker, d.config, Impl::kBody, d.cues, d.renderer);
}

void vpMbIcgTracker::init(const vpImage<unsigned char>&) {
  guarded("init", [&] {
    Impl& d = *impl_;
    build_tracker();
    d.tracker->body(Impl::kBody).reference_T_body = icgp::to_pose(m_cMo);
    d.apply_body_settings();
    d.recovery->reset();
    d.start_pending = true;
    d.quality = 0.0;
    d.hessian.reset();
  });
}

void vpMbIcgTracker::initFromPose(const vpImage<unsigned char>& I, const vpHomogeneousMatrix& cMo) {
  m_cMo = cMo;
  init(I);
}

void vpMbIcgTracker::initFromPose(const vpImage<vpRGBa>&, const vpHomogeneousMatrix& cMo) {
  m_cMo = cMo;
  init(m_I);  // init() reads no image: the cues start on the next tracked frame
}

namespace {

/// The camera whose file ViSP's multi-camera initialisations use: the reference camera's
/// if given, else the first.
template <typename Map>
typename Map::const_iterator reference_or_first(const Map& files, const std::string& reference,
                                                const std::string& call) {
  auto it = files.find(reference);
  if (it == files.end()) it = files.begin();
  if (it == files.end()) throw vpException(vpException::badValue, "vpMbIcgTracker::" + call + ": no file given");
  return it;
}

template <typename Image>
const Image& image_of(const std::map<std::string, const Image*>& images, const std::string& camera,
                      const std::string& call) {
  const auto it = images.find(camera);
  if (it == images.end() || !it->second)
    throw vpException(vpException::badValue, "vpMbIcgTracker::" + call + ": no image of camera '" + camera + "'");
  return *it->second;
}

}  // namespace

vpHomogeneousMatrix vpMbIcgTracker::reference_pose(const std::string& camera, const vpHomogeneousMatrix& cMo,
                                                   const std::string& call) const {
  // c_M_reference * referenceMo = cMo
  return impl_->rig.at(camera, call).camera_M_reference.inverse() * cMo;
}

template <typename Image>
void vpMbIcgTracker::init_from_poses(const std::map<std::string, const Image*>& images,
                                     const std::map<std::string, vpHomogeneousMatrix>& poses,
                                     const std::string& call) {
  require_known_cameras(impl_->rig, call, images, poses);
  // As ViSP: the reference camera's pose if given, else the first camera's, moved into it.
  const auto pose = reference_or_first(poses, impl_->rig.reference(), call);
  m_cMo = reference_pose(pose->first, pose->second, call);
  init(m_I);
}

template <typename Image>
void vpMbIcgTracker::init_from_pose_files(const std::map<std::string, const Image*>& images,
                                          const std::map<std::string, std::string>& files, const std::string& call) {
  require_known_cameras(impl_->rig, call, images, files);
  const auto file = reference_or_first(files, impl_->rig.reference(), call);
  const Image& I = image_of(images, file->first, call);
  // vpMbTracker reads the file (its format and its ".pos" rule) and calls initFromPose(I, cMo).
  vpMbTracker::initFromPose(I, file->second);
  if (file->first != impl_->rig.reference()) initFromPose(I, reference_pose(file->first, m_cMo, call));
}

void vpMbIcgTracker::initFromPose(const vpImage<unsigned char>& I1, const vpImage<unsigned char>& I2,
                                  const std::string& initFile1, const std::string& initFile2) {
  const auto [first, second] = impl_->rig.pair("initFromPose");
  init_from_pose_files(std::map<std::string, const vpImage<unsigned char>*>{{first, &I1}, {second, &I2}},
                       {{first, initFile1}, {second, initFile2}}, "initFromPose");
}

void vpMbIcgTracker::initFromPose(const vpImage<vpRGBa>& I_color1, const vpImage<vpRGBa>& I_color2,
                                  const std::string& initFile1, const std::string& initFile2) {
  const auto [first, second] = impl_->rig.pair("initFromPose");
  init_from_pose_files(std::map<std::string, const vpImage<vpRGBa>*>{{first, &I_color1}, {second, &I_color2}},
                       {{first, initFile1}, {second, initFile2}}, "initFromPose");
}

void vpMbIcgTracker::initFromPose(const std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                                  const std::map<std::string, std::string>& mapOfInitPoses) {
  init_from_pose_files(mapOfImages, mapOfInitPoses, "initFromPose");
}

void vpMbIcgTracker::initFromPose(const std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
                                  const std::map<std::string, std::string>& mapOfInitPoses) {
  init_from_pose_files(mapOfColorImages, mapOfInitPoses, "initFromPose");
}

void vpMbIcgTracker::initFromPose(const vpImage<unsigned char>& I1, const vpImage<unsigned char>& I2,
                                  const vpHomogeneousMatrix& c1Mo, const vpHomogeneousMatrix& c2Mo) {
  const auto [first, second] = impl_->rig.pair("initFromPose");
  init_from_poses(std::map<std::string, const vpImage<unsigned char>*>{{first, &I1}, {second, &I2}},
                  {{first, c1Mo}, {second, c2Mo}}, "initFromPose");
}

void vpMbIcgTracker::initFromPose(const vpImage<vpRGBa>& I_color1, const vpImage<vpRGBa>& I_color2,
                                  const vpHomogeneousMatrix& c1Mo, const vpHomogeneousMatrix& c2Mo) {
  const auto [first, second] = impl_->rig.pair("initFromPose");
  init_from_poses(std::map<std::string, const vpImage<vpRGBa>*>{{first, &I_color1}, {second, &I_color2}},
                  {{first, c1Mo}, {second, c2Mo}}, "initFromPose");
}

void vpMbIcgTracker::initFromPose(const std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                                  const std::map<std::string, vpHomogeneousMatrix>& mapOfCameraPoses) {
  init_from_poses(mapOfImages, mapOfCameraPoses, "initFromPose");
}

void vpMbIcgTracker::initFromPose(const std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
                                  const std::map<std::string, vpHomogeneousMatrix>& mapOfCameraPoses) {
  init_from_poses(mapOfColorImages, mapOfCameraPoses, "initFromPose");
}

void vpMbIcgTracker::initClick(const vpImage<unsigned char>& I1, const vpImage<unsigned char>& I2,
                               const std::string& initFile1, const std::string& initFile2, bool displayHelp,
                               const vpHomogeneousMatrix& T1, const vpHomogeneousMatrix& T2) {
  const auto [first, second] = impl_->rig.pair("initClick");
  initClick(std::map<std::string, const vpImage<unsigned char>*>{{first, &I1}, {second, &I2}},
            {{first, initFile1}, {second, initFile2}}, displayHelp, {{first, T1}, {second, T2}});
}

void vpMbIcgTracker::initClick(const vpImage<vpRGBa>& I_color1, const vpImage<vpRGBa>& I_color2,
                               const std::string& initFile1, const std::string& initFile2, bool displayHelp,
                               const vpHomogeneousMatrix& T1, const vpHomogeneousMatrix& T2) {
  const auto [first, second] = impl_->rig.pair("initClick");
  initClick(std::map<std::string, const vpImage<vpRGBa>*>{{first, &I_color1}, {second, &I_color2}},
            {{first, initFile1}, {second, initFile2}}, displayHelp, {{first, T1}, {second, T2}});
}

namespace {

/// Runs one of vpMbTracker's single-camera initialisations (clicks, points) in `camera`:
/// vpMbTracker computes the pose with m_cam, so it is that camera's during the call.
template <typename Init>
void in_camera(vpCameraParameters& m_cam, const vpCameraParameters& camera, Init&& init) {
  const vpCameraParameters reference = m_cam;
  m_cam = camera;
  try {
    init();
  } catch (...) {
    m_cam = reference;
    throw;
  }
  m_cam = reference;
}

}  // namespace

template <typename Image>
void vpMbIcgTracker::init_click(const std::map<std::string, const Image*>& images,
                                const std::map<std::string, std::string>& files, bool displayHelp,
                                const std::map<std::string, vpHomogeneousMatrix>& mapOfT) {
  const auto file = reference_or_first(files, impl_->rig.reference(), "initClick");
  const std::string& camera = file->first;
  const Image& I = image_of(images, camera, "initClick");
  const auto T = mapOfT.find(camera);
  in_camera(m_cam, impl_->rig.at(camera, "initClick").parameters, [&] {
    vpMbTracker::initClick(I, file->second, displayHelp, T == mapOfT.end() ? vpHomogeneousMatrix() : T->second);
  });
  if (camera != impl_->rig.reference()) initFromPose(I, reference_pose(camera, m_cMo, "initClick"));
}

void vpMbIcgTracker::initClick(const std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                               const std::map<std::string, std::string>& mapOfInitFiles, bool displayHelp,
                               const std::map<std::string, vpHomogeneousMatrix>& mapOfT) {
  init_click(mapOfImages, mapOfInitFiles, displayHelp, mapOfT);
}

void vpMbIcgTracker::initClick(const std::map<std::string, const vpImage<vpRGBa>*>& mapOfImages,
                               const std::map<std::string, std::string>& mapOfInitFiles, bool displayHelp,
                               const std::map<std::string, vpHomogeneousMatrix>& mapOfT) {
  init_click(mapOfImages, mapOfInitFiles, displayHelp, mapOfT);
}

void vpMbIcgTracker::initFromPoints(const vpImage<unsigned char>& I1, const vpImage<unsigned char>& I2,
                                    const std::string& initFile1, const std::string& initFile2) {
  const auto [first, second] = impl_->rig.pair("initFromPoints");
  initFromPoints(std::map<std::string, const vpImage<unsigned char>*>{{first, &I1}, {second, &I2}},
                 {{first, initFile1}, {second, initFile2}});
}

void vpMbIcgTracker::initFromPoints(const vpImage<vpRGBa>& I_color1, const vpImage<vpRGBa>& I_color2,
                                    const std::string& initFile1, const std::string& initFile2) {
  const auto [first, second] = impl_->rig.pair("initFromPoints");
  initFromPoints(std::map<std::string, const vpImage<vpRGBa>*>{{first, &I_color1}, {second, &I_color2}},
                 {{first, initFile1}, {second, initFile2}});
}

template <typename Image>
void vpMbIcgTracker::init_from_points(const std::map<std::string, const Image*>& images,
                                      const std::map<std::string, std::string>& points) {
  const auto file = reference_or_first(points, impl_->rig.reference(), "initFromPoints");
  const Image& I = image_of(images, file->first, "initFromPoints");
  in_camera(m_cam, impl_->rig.at(file->first, "initFromPoints").parameters,
            [&] { vpMbTracker::initFromPoints(I, file->second); });
  if (file->first != impl_->rig.reference()) initFromPose(I, reference_pose(file->first, m_cMo, "initFromPoints"));
}

void vpMbIcgTracker::initFromPoints(const std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                                    const std::map<std::string, std::string>& mapOfInitPoints) {
  init_from_points(mapOfImages, mapOfInitPoints);
}

void vpMbIcgTracker::initFromPoints(const std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
                                    const std::map<std::string, std::string>& mapOfInitPoints) {
  init_from_points(mapOfColorImages, mapOfInitPoints);
}

void vpMbIcgTracker::setPose(const vpImage<unsigned char>& I, const vpHomogeneousMatrix& cdMo) {
  impl_->require_initialised("setPose");
  initFromPose(I, cdMo);
}

void vpMbIcgTracker::setPose(const vpImage<vpRGBa>& I_color, const vpHomogeneousMatrix& cdMo) {
  impl_->require_initialised("setPose");
  initFromPose(I_color, cdMo);
}

void vpMbIcgTracker::setPose(const vpImage<unsigned char>& I1, const vpImage<unsigned char>& I2,
                             const vpHomogeneousMatrix& c1Mo, const vpHomogeneousMatrix& c2Mo) {
  impl_->require_initialised("setPose");
  const auto [first, second] = impl_->rig.pair("setPose");
  init_from_poses(std::map<std::string, const vpImage<unsigned char>*>{{first, &I1}, {second, &I2}},
                  {{first, c1Mo}, {second, c2Mo}}, "setPose");
}

void vpMbIcgTracker::setPose(const vpImage<vpRGBa>& I_color1, const vpImage<vpRGBa>& I_color2,
                             const vpHomogeneousMatrix& c1Mo, const vpHomogeneousMatrix& c2Mo) {
  impl_->require_initialised("setPose");
  const auto [first, second] = impl_->rig.pair("setPose");
  init_from_poses(std::map<std::string, const vpImage<vpRGBa>*>{{first, &I_color1}, {second, &I_color2}},
                  {{first, c1Mo}, {second, c2Mo}}, "setPose");
}

void vpMbIcgTracker::setPose(const std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                             const std::map<std::string, vpHomogeneousMatrix>& mapOfCameraPoses) {
  impl_->require_initialised("setPose");
  init_from_poses(mapOfImages, mapOfCameraPoses, "setPose");
}

void vpMbIcgTracker::setPose(const std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
                             const std::map<std::string, vpHomogeneousMatrix>& mapOfCameraPoses) {
  impl_->require_initialised("setPose");
  init_from_poses(mapOfColorImages, mapOfCameraPoses, "setPose");
}

void vpMbIcgTracker::resetTracker() {
  // As vpMbGenericTracker: the cameras, their types and their transformation matrices
  // stay; ViSP's programs reload the model, the settings and the cameras' parameters.
  icgp::CameraRig rig = impl_->rig;
  for (const std::string& name : rig.names()) {
    icgp::CameraRig::Camera& camera = rig.at(name, "resetTracker");
    camera.parameters = vpCameraParameters();
    camera.parameters_set = false;
  }
  clear_model();
  impl_ = std::make_unique<Impl>(std::move(rig));
  m_cMo.eye();
  m_cam = vpCameraParameters();
  // clear(), not resize(0): ViSP's resize to 0 hands memset a null pointer.
  m_error.clear();
  m_w.clear();
  modelInitialised = false;
  projectionError = 90.0;
  covarianceMatrix.clear();
}
