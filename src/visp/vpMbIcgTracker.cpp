// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/visp/vpMbIcgTracker.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
#include <set>
#include <visp3/core/vpDisplay.h>
#include <visp3/core/vpTrackingException.h>
#include <visp3/mbt/vpMbtXmlGenericParser.h>

#include "icgp/render/model_edges.h"
#include "icgp/render/renderer.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/conversions.h"

#include "frame_assembly.h"

namespace {

constexpr const char* kColorCamera = "Camera1";
constexpr const char* kDepthCamera = "Camera2";
constexpr const char* kBody = "object";

std::string lower_extension(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

void require_file(const std::string& path, const std::string& what) {
  if (!std::filesystem::is_regular_file(path))
    throw vpException(vpException::ioError, "vpMbIcgTracker: " + what + " '" + path + "' does not exist");
}

/// The <camera> block of a ViSP tracker XML file, read by ViSP's own parser. The parser
/// reads <camera> only for the cue types: PROJECTION_ERROR_PARSER alone skips it and leaves
/// ViSP's default camera (600, 600, 192, 144).
vpCameraParameters camera_of_visp_xml(const std::string& path, bool verbose) {
  require_file(path, "configuration file");
  vpMbtXmlGenericParser parser(static_cast<vpMbtXmlGenericParser::vpParserType>(
      vpMbtXmlGenericParser::EDGE_PARSER | vpMbtXmlGenericParser::KLT_PARSER |
      vpMbtXmlGenericParser::DEPTH_NORMAL_PARSER | vpMbtXmlGenericParser::DEPTH_DENSE_PARSER));
  parser.setVerbose(verbose);
  parser.parse(path);
  vpCameraParameters camera;
  parser.getCameraParameters(camera);
  return camera;
}

}  // namespace

struct vpMbIcgTracker::Impl {
  icgp::TrackerConfig config;
  icgp::Mesh mesh;
  bool has_cao_part = false;  ///< ViSP's projection-error model exists
  std::unique_ptr<icgp::Tracker> tracker;  ///< for the current mesh and config, built by init()
  bool start_pending = false;

  bool color_camera_set = false;
  std::optional<vpCameraParameters> depth_camera;
  vpHomogeneousMatrix depth_M_color;

  icgp::FrameAssembler assembler;
  double quality = 0.0;
  std::optional<icgp::Mat66> hessian;  ///< of the last update's data terms

  std::set<std::string> reported_without_effect;  ///< ViSP settings already reported once

  std::unique_ptr<icgp::ModelEdges> edges;  ///< for display, made on first use
  std::unique_ptr<icgp::Renderer> renderer;
  icgp::Renderer::BodyHandle render_body{};

  void require_initialised() const {
    if (!tracker)
      throw vpTrackingException(vpTrackingException::initializationError,
                                "vpMbIcgTracker::track: not initialised; call loadModel() and initFromPose() first");
  }

  /// track(I) has only a colour image: a configuration of the depth cue alone has nothing to
  /// track it with.
  void require_colour_cue() const {
    const auto& m = config.modalities;
    if (std::find(m.begin(), m.end(), "region") == m.end() && std::find(m.begin(), m.end(), "texture") == m.end())
      throw vpException(vpException::badValue,
                        "vpMbIcgTracker::track(I): the configured cues need depth; give a point cloud or a depth "
                        "image (track with the maps of clouds, or track(I, I_depth_raw, depthScale))");
  }

  /// A ViSP setting this tracker accepts but cannot honour: said once per tracker.
  void report_without_effect(const std::string& call, const std::string& why) {
    if (reported_without_effect.insert(call).second)
      std::cerr << "vpMbIcgTracker::" << call << ": no effect (" << why << ")\n";
  }

  void model_changed() {
    tracker.reset();
    edges.reset();
    renderer.reset();
  }
};

vpMbIcgTracker::vpMbIcgTracker() : impl_(std::make_unique<Impl>()) {}
vpMbIcgTracker::~vpMbIcgTracker() = default;

// ---------------------------------------------------------------------------- parameters

void vpMbIcgTracker::loadConfigFile(const std::string& configFile, bool verbose) {
  const std::string extension = lower_extension(configFile);
  if (extension == ".yaml" || extension == ".yml") {
    require_file(configFile, "configuration file");
    try {
      setTrackerConfig(icgp::load_tracker_config(configFile));
    } catch (const std::exception& e) {
      throw vpException(vpException::badValue, std::string("vpMbIcgTracker: ") + e.what());
    }
    if (verbose) std::cout << "vpMbIcgTracker: parameters from " << configFile << "\n";
  } else if (extension == ".xml") {
    setCameraParameters(camera_of_visp_xml(configFile, verbose));
    if (verbose) std::cout << "vpMbIcgTracker: colour camera from " << configFile << "\n";
  } else {
    throw vpException(vpException::badValue, "vpMbIcgTracker: configuration file '" + configFile +
                                                 "' must be icgp's YAML (.yaml, .yml) or a ViSP tracker XML (.xml)");
  }
}

void vpMbIcgTracker::loadConfigFile(const std::string& colorConfigFile, const std::string& depthConfigFile,
                                    bool verbose) {
  loadConfigFile(colorConfigFile, verbose);
  if (lower_extension(depthConfigFile) == ".xml") {
    impl_->depth_camera = camera_of_visp_xml(depthConfigFile, verbose);
    if (verbose) std::cout << "vpMbIcgTracker: depth camera from " << depthConfigFile << "\n";
  } else {
    loadConfigFile(depthConfigFile, verbose);
  }
}

void vpMbIcgTracker::setTrackerConfig(const icgp::TrackerConfig& config) {
  impl_->config = config;
  impl_->tracker.reset();
}

const icgp::TrackerConfig& vpMbIcgTracker::getTrackerConfig() const { return impl_->config; }

void vpMbIcgTracker::setModalities(const std::vector<std::string>& modalities) {
  icgp::TrackerConfig config = impl_->config;
  config.modalities = modalities;
  setTrackerConfig(config);
}

// --------------------------------------------------------------------------------- model

void vpMbIcgTracker::loadModel(const std::string& modelFile, bool verbose, const vpHomogeneousMatrix& T) {
  require_file(modelFile, "model file");
  icgp::Mesh part;
  try {
    part = icgp::load_any_mesh(modelFile, 1.0, icgp::to_pose(T));
  } catch (const std::exception& e) {
    throw vpException(vpException::badValue,
                      "vpMbIcgTracker: cannot load model '" + modelFile + "' (.cao, or a mesh format assimp reads): " +
                          e.what());
  }
  // ViSP's own parser also fills `faces` and the projection-error model, so that
  // computeCurrentProjectionError means what it means for ViSP's trackers.
  if (lower_extension(modelFile) == ".cao") {
    vpMbTracker::loadModel(modelFile, verbose, T);
    impl_->has_cao_part = true;
  }

  Impl& d = *impl_;
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
}

void vpMbIcgTracker::loadModel(const std::string& colorModelFile, const std::string& depthModelFile, bool verbose,
                               const vpHomogeneousMatrix& colorT, const vpHomogeneousMatrix& depthT) {
  if (!depthModelFile.empty() && (std::filesystem::path(depthModelFile) != std::filesystem::path(colorModelFile) ||
                                  !(colorT == depthT)))
    throw vpException(vpException::badValue, "vpMbIcgTracker: one rigid object is tracked with both cameras, so the "
                                             "depth camera's model must be the colour camera's ('" +
                                                 colorModelFile + "'), got '" + depthModelFile + "'");
  loadModel(colorModelFile, verbose, colorT);
}

// ------------------------------------------------------------------------------- cameras

void vpMbIcgTracker::setCameraParameters(const vpCameraParameters& colorCamera) {
  m_cam = colorCamera;
  impl_->color_camera_set = true;
}

void vpMbIcgTracker::setCameraParameters(const vpCameraParameters& colorCamera, const vpCameraParameters& depthCamera) {
  setCameraParameters(colorCamera);
  impl_->depth_camera = depthCamera;
}

void vpMbIcgTracker::setCameraParameters(const std::map<std::string, vpCameraParameters>& mapOfCameraParameters) {
  for (const auto& [name, camera] : mapOfCameraParameters) {
    if (name == kColorCamera)
      setCameraParameters(camera);
    else if (name == kDepthCamera)
      impl_->depth_camera = camera;
    else
      throw vpException(vpException::badValue, "vpMbIcgTracker: unknown camera '" + name +
                                                   "' (the cameras are \"Camera1\" colour and \"Camera2\" depth)");
  }
}

void vpMbIcgTracker::getCameraParameters(vpCameraParameters& colorCamera, vpCameraParameters& depthCamera) const {
  colorCamera = m_cam;
  depthCamera = impl_->depth_camera.value_or(m_cam);
}

void vpMbIcgTracker::setCameraTransformationMatrix(const std::string& cameraName,
                                                   const vpHomogeneousMatrix& cameraTransformationMatrix) {
  if (cameraName == kDepthCamera) {
    impl_->depth_M_color = cameraTransformationMatrix;
  } else if (cameraName == kColorCamera) {
    if (!(cameraTransformationMatrix == vpHomogeneousMatrix()))
      throw vpException(vpException::badValue, "vpMbIcgTracker: \"Camera1\" is the reference camera, its "
                                               "transformation matrix must be the identity");
  } else {
    throw vpException(vpException::badValue, "vpMbIcgTracker: unknown camera '" + cameraName +
                                                 "' (the cameras are \"Camera1\" colour and \"Camera2\" depth)");
  }
}

void vpMbIcgTracker::setCameraTransformationMatrix(
    const std::map<std::string, vpHomogeneousMatrix>& mapOfTransformationMatrix) {
  for (const auto& [name, M] : mapOfTransformationMatrix) setCameraTransformationMatrix(name, M);
}

std::vector<std::string> vpMbIcgTracker::getCameraNames() const { return {kColorCamera, kDepthCamera}; }
std::string vpMbIcgTracker::getReferenceCameraName() const { return kColorCamera; }

// ------------------------------------------------------------------------ initialisation

void vpMbIcgTracker::init(const vpImage<unsigned char>&) {
  Impl& d = *impl_;
  if (d.mesh.parts.empty())
    throw vpTrackingException(vpTrackingException::initializationError,
                              "vpMbIcgTracker: no model; call loadModel() before initialising");
  if (!d.tracker) {
    try {
      d.tracker = icgp::build_tracker(d.config, d.mesh, kBody);
    } catch (const std::exception& e) {
      throw vpException(vpException::badValue, std::string("vpMbIcgTracker: ") + e.what());
    }
  }
  d.tracker->body(kBody).reference_T_body = icgp::to_pose(m_cMo);
  d.start_pending = true;
  d.quality = 0.0;
  d.hessian.reset();
}

void vpMbIcgTracker::initFromPose(const vpImage<unsigned char>& I, const vpHomogeneousMatrix& cMo) {
  m_cMo = cMo;
  init(I);
}

void vpMbIcgTracker::initFromPose(const vpImage<vpRGBa>&, const vpHomogeneousMatrix& cMo) {
  m_cMo = cMo;
  init(m_I);  // init() reads no image: the cues start on the next tracked frame
}

void vpMbIcgTracker::setPose(const vpImage<unsigned char>& I, const vpHomogeneousMatrix& cdMo) {
  if (!impl_->tracker)
    throw vpTrackingException(vpTrackingException::initializationError,
                              "vpMbIcgTracker: setPose() before initFromPose()");
  initFromPose(I, cdMo);
}

void vpMbIcgTracker::setPose(const vpImage<vpRGBa>& I_color, const vpHomogeneousMatrix& cdMo) {
  if (!impl_->tracker)
    throw vpTrackingException(vpTrackingException::initializationError,
                              "vpMbIcgTracker: setPose() before initFromPose()");
  initFromPose(I_color, cdMo);
}

void vpMbIcgTracker::resetTracker() {
  // As vpMbGenericTracker, which keeps its map of camera transformation matrices: ViSP's
  // programs reload the model, settings and cameras after a reset, not the extrinsics.
  const vpHomogeneousMatrix depth_M_color = impl_->depth_M_color;
  impl_ = std::make_unique<Impl>();
  impl_->depth_M_color = depth_M_color;
  m_cMo.eye();
  m_cam = vpCameraParameters();
  m_error.resize(0);
  m_w.resize(0);
  faces.reset();
  m_projectionErrorFaces.reset();
  modelInitialised = false;
  projectionError = 90.0;
  covarianceMatrix.resize(0, 0);
}

void vpMbIcgTracker::setScanLineVisibilityTest(const bool& v) {
  vpMbTracker::setScanLineVisibilityTest(v);
  impl_->report_without_effect("setScanLineVisibilityTest",
                               "visibility comes from the rendered viewpoint models, exact for every face");
}

// ------------------------------------------------------------------------------ tracking

void vpMbIcgTracker::track(const vpImage<unsigned char>& I) {
  impl_->require_initialised();
  impl_->require_colour_cue();
  impl_->assembler.set_color(kColorCamera, I, m_cam, impl_->color_camera_set);
  // A colour-only call: the depth cue, on by default, sits the frame out as when a depth
  // camera delivers nothing, so a monocular program runs on the defaults.
  impl_->assembler.set_no_depth(kDepthCamera);
  track_current_frame(&I);
}

void vpMbIcgTracker::track(const vpImage<vpRGBa>& I_color) {
  impl_->require_initialised();
  impl_->require_colour_cue();
  impl_->assembler.set_color(kColorCamera, I_color, m_cam, impl_->color_camera_set);
  impl_->assembler.set_no_depth(kDepthCamera);
  track_current_frame(nullptr);
}

namespace {

/// Z of an organised cloud's point, ViSP's zero-length vectors included.
float cloud_depth(const std::vector<vpColVector>& cloud, unsigned int width, int row, int col) {
  const vpColVector& point = cloud[static_cast<std::size_t>(row) * width + col];
  return point.size() >= 3 ? static_cast<float>(point[2]) : 0.f;
}

/// The one organised cloud of "Camera2" in ViSP's map form, with its size checked.
const std::vector<vpColVector>& cloud_of_depth_camera(std::map<std::string, const std::vector<vpColVector>*>& clouds,
                                                      std::map<std::string, unsigned int>& widths,
                                                      std::map<std::string, unsigned int>& heights, unsigned int& width,
                                                      unsigned int& height) {
  const std::vector<vpColVector>* cloud = nullptr;
  for (const auto& [name, c] : clouds) {
    if (name != kDepthCamera)
      throw vpException(vpException::badValue, "vpMbIcgTracker::track: unknown camera '" + name +
                                                   "' in the point clouds (the depth camera is \"Camera2\")");
    cloud = c;
  }
  if (!cloud) throw vpException(vpException::badValue, "vpMbIcgTracker::track: no point cloud of \"Camera2\"");
  if (!widths.count(kDepthCamera) || !heights.count(kDepthCamera))
    throw vpException(vpException::badValue, "vpMbIcgTracker::track: no width/height of \"Camera2\"'s point cloud");
  width = widths[kDepthCamera];
  height = heights[kDepthCamera];
  // Width and height 0 is ViSP's "no depth this frame", whatever the cloud holds.
  if (width == 0 && height == 0) return *cloud;
  if (cloud->size() != static_cast<std::size_t>(width) * height)
    throw vpException(vpException::badValue, "vpMbIcgTracker::track: the point cloud of \"Camera2\" has " +
                                                 std::to_string(cloud->size()) + " points, but width x height is " +
                                                 std::to_string(width) + " x " + std::to_string(height) +
                                                 " (an organised cloud has one point per pixel)");
  return *cloud;
}

}  // namespace

template <typename Image>
void vpMbIcgTracker::track_with_depth(std::map<std::string, const Image*>& images, unsigned int depthWidth,
                                      unsigned int depthHeight, DepthReader read) {
  const Image* color = nullptr;
  for (const auto& [name, image] : images) {
    if (name == kColorCamera)
      color = image;
    else if (name != kDepthCamera)  // ViSP users may pass the depth camera's image too
      throw vpException(vpException::badValue, "vpMbIcgTracker::track: unknown camera '" + name +
                                                   "' in the images (the cameras are \"Camera1\" and \"Camera2\")");
  }
  if (!color) throw vpException(vpException::badValue, "vpMbIcgTracker::track: no image of \"Camera1\"");
  track_with_depth(*color, depthWidth, depthHeight, std::move(read));
}

template void vpMbIcgTracker::track_with_depth(std::map<std::string, const vpImage<unsigned char>*>&, unsigned int,
                                               unsigned int, DepthReader);
template void vpMbIcgTracker::track_with_depth(std::map<std::string, const vpImage<vpRGBa>*>&, unsigned int,
                                               unsigned int, DepthReader);

void vpMbIcgTracker::set_depth(unsigned int width, unsigned int height, DepthReader read, bool depthFromColorCamera) {
  Impl& d = *impl_;
  if (width == 0 && height == 0) {  // as in ViSP: no depth this frame; the depth cue sits it out
    d.assembler.set_no_depth(kDepthCamera);
    return;
  }
  const std::optional<vpCameraParameters> camera = depthFromColorCamera ? std::optional(m_cam) : d.depth_camera;
  const vpHomogeneousMatrix M = depthFromColorCamera ? vpHomogeneousMatrix() : d.depth_M_color;
  d.assembler.set_depth(kDepthCamera, width, height, camera, M, std::move(read));
}

void vpMbIcgTracker::track_with_depth(const vpImage<unsigned char>& I, unsigned int depthWidth,
                                      unsigned int depthHeight, DepthReader read, bool depthFromColorCamera) {
  impl_->require_initialised();
  impl_->assembler.set_color(kColorCamera, I, m_cam, impl_->color_camera_set);
  set_depth(depthWidth, depthHeight, std::move(read), depthFromColorCamera);
  track_current_frame(&I);
}

void vpMbIcgTracker::track_with_depth(const vpImage<vpRGBa>& I, unsigned int depthWidth, unsigned int depthHeight,
                                      DepthReader read, bool depthFromColorCamera) {
  impl_->require_initialised();
  impl_->assembler.set_color(kColorCamera, I, m_cam, impl_->color_camera_set);
  set_depth(depthWidth, depthHeight, std::move(read), depthFromColorCamera);
  track_current_frame(nullptr);
}

template <typename Image>
void vpMbIcgTracker::track_with_clouds(std::map<std::string, const Image*>& images,
                                       std::map<std::string, const std::vector<vpColVector>*>& clouds,
                                       std::map<std::string, unsigned int>& widths,
                                       std::map<std::string, unsigned int>& heights) {
  unsigned int width = 0, height = 0;
  const auto& cloud = cloud_of_depth_camera(clouds, widths, heights, width, height);
  track_with_depth(images, width, height,
                   [&cloud, width](int row, int col) { return cloud_depth(cloud, width, row, col); });
}

void vpMbIcgTracker::track(std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                           std::map<std::string, const std::vector<vpColVector>*>& mapOfPointClouds,
                           std::map<std::string, unsigned int>& mapOfPointCloudWidths,
                           std::map<std::string, unsigned int>& mapOfPointCloudHeights) {
  track_with_clouds(mapOfImages, mapOfPointClouds, mapOfPointCloudWidths, mapOfPointCloudHeights);
}

void vpMbIcgTracker::track(std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
                           std::map<std::string, const std::vector<vpColVector>*>& mapOfPointClouds,
                           std::map<std::string, unsigned int>& mapOfPointCloudWidths,
                           std::map<std::string, unsigned int>& mapOfPointCloudHeights) {
  track_with_clouds(mapOfColorImages, mapOfPointClouds, mapOfPointCloudWidths, mapOfPointCloudHeights);
}

namespace {

/// Raw depth times the scale.
std::function<float(int, int)> raw_depth_reader(const vpImage<uint16_t>& raw, double scale) {
  if (!(scale > 0.0) || !std::isfinite(scale))
    throw vpException(vpException::badValue,
                      "vpMbIcgTracker::track: the depth scale must be positive (metres per raw unit), got " +
                          std::to_string(scale));
  return [&raw, scale = static_cast<float>(scale)](int row, int col) {
    return scale * raw[static_cast<unsigned int>(row)][col];
  };
}

}  // namespace

void vpMbIcgTracker::track(const vpImage<unsigned char>& I, const vpImage<uint16_t>& I_depth_raw, double depthScale) {
  track_with_depth(I, I_depth_raw.getWidth(), I_depth_raw.getHeight(), raw_depth_reader(I_depth_raw, depthScale));
}

void vpMbIcgTracker::track(const vpImage<vpRGBa>& I_color, const vpImage<uint16_t>& I_depth_raw, double depthScale) {
  track_with_depth(I_color, I_depth_raw.getWidth(), I_depth_raw.getHeight(),
                   raw_depth_reader(I_depth_raw, depthScale));
}

void vpMbIcgTracker::track_current_frame(const vpImage<unsigned char>* grey) {
  Impl& d = *impl_;
  const icgp::Frame& frame = d.assembler.frame();
  icgp::Body& body = d.tracker->body(kBody);
  // The depth reader refers to the caller's cloud, which is only known valid during this call.
  struct EndDepthReads {
    icgp::FrameAssembler& assembler;
    ~EndDepthReads() { assembler.end_depth_reads(); }
  } end_depth_reads{d.assembler};
  try {
    if (d.start_pending) {
      body.reference_T_body = icgp::to_pose(m_cMo);
      d.tracker->start(frame);
      d.start_pending = false;
    }
    const icgp::BodyResult result = d.tracker->track(frame).front();
    d.quality = result.quality;
  } catch (const std::invalid_argument& e) {
    // The frame does not suit the configured cues (a missing depth image, a wrong size):
    // the caller's mistake, reported the ViSP way.
    throw vpException(vpException::badValue, std::string("vpMbIcgTracker::track: ") + e.what());
  }
  m_cMo = icgp::to_homogeneous_matrix(body.reference_T_body);
  d.hessian = d.tracker->last_hessian(kBody);
  computeVVSInit();
  computeVVSInteractionMatrixAndResidu();

  if (computeCovariance) covarianceMatrix = getCovarianceMatrix();
  if (computeProjError) {
    projectionError = computeCurrentProjectionError(grey ? *grey : d.assembler.grey_image(), m_cMo, m_cam);
  }
}

void vpMbIcgTracker::testTracking() {
  const icgp::Tracker* tracker = impl_->tracker.get();
  if (!tracker)
    throw vpTrackingException(vpTrackingException::initializationError, "vpMbIcgTracker::testTracking: not initialised");
  const double threshold = tracker->params().quality_threshold;
  if (impl_->quality < threshold)
    throw vpTrackingException(vpTrackingException::fatalError,
                              "vpMbIcgTracker: tracking lost (quality " + std::to_string(impl_->quality) +
                                  " below the threshold " + std::to_string(threshold) + ")");
}

double vpMbIcgTracker::getTrackingQuality() const { return impl_->quality; }

// ----------------------------------------------------------------------------- results

void vpMbIcgTracker::computeVVSInit() {
  m_error.resize(0);
  m_w.resize(0);
}

void vpMbIcgTracker::computeVVSInteractionMatrixAndResidu() {
  if (!impl_->tracker) return;
  std::vector<double> residuals, weights;
  impl_->tracker->residuals(kBody, residuals, weights);
  m_error.resize(static_cast<unsigned int>(residuals.size()), false);
  m_w.resize(static_cast<unsigned int>(weights.size()), false);
  for (unsigned int i = 0; i < m_error.size(); ++i) {
    m_error[i] = residuals[i];
    m_w[i] = weights[i];
  }
}

double vpMbIcgTracker::computeCurrentProjectionError(const vpImage<unsigned char>& I, const vpHomogeneousMatrix& cMo,
                                                     const vpCameraParameters& cam) {
  if (!impl_->has_cao_part)
    throw vpException(vpException::notImplementedError,
                      "vpMbIcgTracker: the projection error is ViSP's, computed on the edges of a .cao model; this "
                      "model has no .cao part");
  return vpMbTracker::computeCurrentProjectionError(I, cMo, cam);
}

vpColVector vpMbIcgTracker::getError() const { return m_error; }
vpColVector vpMbIcgTracker::getRobustWeights() const { return m_w; }

vpMatrix vpMbIcgTracker::getCovarianceMatrix() const {
  if (!impl_->hessian)
    throw vpTrackingException(vpTrackingException::initializationError,
                              "vpMbIcgTracker::getCovarianceMatrix: no frame has been tracked yet");
  // Σ_θ = (−H)⁻¹ over the body-frame variation θ = [θ_r; θ_t] (T ← T exp(θ)). A body-frame
  // twist ξ_b is the camera-frame twist ξ_c = Ad(cMo) ξ_b; ViSP orders twists (v, ω).
  const Eigen::Matrix<double, 6, 6> information = -*impl_->hessian;
  const Eigen::Matrix<double, 6, 6> body_covariance = information.completeOrthogonalDecomposition().pseudoInverse();
  Eigen::Matrix<double, 6, 6> to_v_omega = Eigen::Matrix<double, 6, 6>::Zero();  // (v, ω) = P θ
  to_v_omega.block<3, 3>(0, 3).setIdentity();
  to_v_omega.block<3, 3>(3, 0).setIdentity();
  const icgp::Pose cMo = icgp::to_pose(m_cMo);
  const Eigen::Matrix3d R = cMo.rotation();
  Eigen::Matrix3d t_cross;
  t_cross << 0, -cMo.translation().z(), cMo.translation().y(), cMo.translation().z(), 0, -cMo.translation().x(),
      -cMo.translation().y(), cMo.translation().x(), 0;
  Eigen::Matrix<double, 6, 6> adjoint = Eigen::Matrix<double, 6, 6>::Zero();
  adjoint.block<3, 3>(0, 0) = R;
  adjoint.block<3, 3>(0, 3) = t_cross * R;
  adjoint.block<3, 3>(3, 3) = R;
  const Eigen::Matrix<double, 6, 6> A = adjoint * to_v_omega;
  const Eigen::Matrix<double, 6, 6> product = A * body_covariance * A.transpose();
  const Eigen::Matrix<double, 6, 6> camera_covariance = 0.5 * (product + product.transpose());  // exactly symmetric
  vpMatrix out(6, 6);
  for (unsigned int i = 0; i < 6; ++i)
    for (unsigned int j = 0; j < 6; ++j) out[i][j] = camera_covariance(i, j);
  return out;
}

// ----------------------------------------------------------------------------- display

std::vector<std::vector<double>> vpMbIcgTracker::getModelForDisplay(unsigned int width, unsigned int height,
                                                                    const vpHomogeneousMatrix& cMo,
                                                                    const vpCameraParameters& cam,
                                                                    bool displayFullModel) {
  Impl& d = *impl_;
  if (d.mesh.parts.empty())
    throw vpTrackingException(vpTrackingException::initializationError, "vpMbIcgTracker: no model to display");
  if (!d.edges) d.edges = std::make_unique<icgp::ModelEdges>(d.mesh);
  const icgp::Intrinsics k = icgp::to_intrinsics(cam, static_cast<int>(width), static_cast<int>(height));
  const icgp::Pose camera_T_body = icgp::to_pose(cMo);
  cv::Mat depth;
  if (!displayFullModel) {
    if (!d.renderer) {
      d.renderer = std::make_unique<icgp::Renderer>();
      d.render_body = d.renderer->add_body(d.mesh, 1);
    }
    d.renderer->set_body_pose(d.render_body, camera_T_body);
    depth = d.renderer->render(k, icgp::Pose(), icgp::kRenderDepth).depth;
  }
  std::vector<std::vector<double>> lines;
  for (const icgp::ImageSegment& s : d.edges->project(k, camera_T_body, depth))
    lines.push_back({0.0, s.a.y(), s.a.x(), s.b.y(), s.b.x()});  // ViSP: i is the row (v), j the column (u)
  return lines;
}

namespace {

template <typename Image>
void draw_lines(const Image& I, const std::vector<std::vector<double>>& lines, const vpColor& color,
                unsigned int thickness) {
  for (const std::vector<double>& l : lines)
    vpDisplay::displayLine(I, vpImagePoint(l[1], l[2]), vpImagePoint(l[3], l[4]), color, thickness);
}

}  // namespace

void vpMbIcgTracker::display(const vpImage<unsigned char>& I, const vpHomogeneousMatrix& cMo,
                             const vpCameraParameters& cam, const vpColor& col, unsigned int thickness,
                             bool displayFullModel) {
  draw_lines(I, getModelForDisplay(I.getWidth(), I.getHeight(), cMo, cam, displayFullModel), col, thickness);
}

void vpMbIcgTracker::display(const vpImage<vpRGBa>& I, const vpHomogeneousMatrix& cMo, const vpCameraParameters& cam,
                             const vpColor& col, unsigned int thickness, bool displayFullModel) {
  draw_lines(I, getModelForDisplay(I.getWidth(), I.getHeight(), cMo, cam, displayFullModel), col, thickness);
}

// ------------------------------------------------------------ ViSP's .cao parser hooks

void vpMbIcgTracker::initCircle(const vpPoint&, const vpPoint&, const vpPoint&, double, int, const std::string&) {}
void vpMbIcgTracker::initCylinder(const vpPoint&, const vpPoint&, double, int, const std::string&) {}
void vpMbIcgTracker::initFaceFromCorners(vpMbtPolygon&) {}
void vpMbIcgTracker::initFaceFromLines(vpMbtPolygon&) {}
