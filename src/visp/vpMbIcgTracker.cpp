// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker: construction, parameters and cameras (the model in vpMbIcgTracker_model.cpp,
// initialisation in vpMbIcgTracker_init.cpp, tracking in vpMbIcgTracker_track.cpp, errors
// made ViSP's in vpMbIcgTracker_errors.cpp).
#include <algorithm>
#include <visp3/mbt/vpMbtXmlGenericParser.h>

#include "icgp/io/file_extension.h"
#include "icgp/tracker/cue_registry.h"
#include "icgp/visp/conversions.h"

#include "vpMbIcgTracker_impl.h"

using icgp::visp_detail::guarded;
using icgp::visp_detail::require_file;

static_assert(int{vpMbIcgTracker::EDGE_TRACKER} == icgp::visp_type::kEdge &&
                  int{vpMbIcgTracker::KLT_TRACKER} == icgp::visp_type::kKlt &&
                  int{vpMbIcgTracker::DEPTH_NORMAL_TRACKER} == icgp::visp_type::kDepthNormal &&
                  int{vpMbIcgTracker::DEPTH_DENSE_TRACKER} == icgp::visp_type::kDepthDense,
              "the rig's tracker types are vpMbGenericTracker's");

namespace {

/// A ViSP tracker XML file read by ViSP's own parser, for every cue type: the parser reads
/// <camera> only for them (PROJECTION_ERROR_PARSER alone skips it and leaves ViSP's default
/// camera, 600, 600, 192, 144).
std::unique_ptr<vpMbtXmlGenericParser> parse_visp_xml(const std::string& path, bool verbose) {
  require_file(path, "configuration file");
  auto parser = std::make_unique<vpMbtXmlGenericParser>(static_cast<vpMbtXmlGenericParser::vpParserType>(
      vpMbtXmlGenericParser::EDGE_PARSER | vpMbtXmlGenericParser::KLT_PARSER |
      vpMbtXmlGenericParser::DEPTH_NORMAL_PARSER | vpMbtXmlGenericParser::DEPTH_DENSE_PARSER));
  parser->setVerbose(verbose);
  parser->parse(path);
  return parser;
}

}  // namespace

// ------------------------------------------------------------------------ construction

vpMbIcgTracker::vpMbIcgTracker()
    : vpMbIcgTracker(std::vector<std::string>{"Camera"},
                     std::vector<int>{EDGE_TRACKER | KLT_TRACKER | DEPTH_DENSE_TRACKER}) {}

vpMbIcgTracker::vpMbIcgTracker(unsigned int nbCameras, int trackerType)
    : vpMbIcgTracker(icgp::CameraRig::visp_names(nbCameras), std::vector<int>(nbCameras, trackerType)) {}

vpMbIcgTracker::vpMbIcgTracker(const std::vector<int>& trackerTypes)
    : vpMbIcgTracker(icgp::CameraRig::visp_names(trackerTypes.size()), trackerTypes) {}

vpMbIcgTracker::vpMbIcgTracker(const std::vector<std::string>& cameraNames, const std::vector<int>& trackerTypes)
    : impl_(std::make_unique<Impl>(icgp::CameraRig(cameraNames, trackerTypes))) {}

vpMbIcgTracker::~vpMbIcgTracker() = default;

// ---------------------------------------------------------------------------- parameters

void vpMbIcgTracker::loadConfigFile(const std::string& configFile, bool verbose) {
  loadConfigFile(std::map<std::string, std::string>{{impl_->rig.reference(), configFile}}, verbose);
}

void vpMbIcgTracker::loadConfigFile(const std::string& configFile1, const std::string& configFile2, bool verbose) {
  const auto [first, second] = impl_->rig.pair("loadConfigFile");
  loadConfigFile(std::map<std::string, std::string>{{first, configFile1}, {second, configFile2}}, verbose);
}

void vpMbIcgTracker::loadConfigFile(const std::map<std::string, std::string>& mapOfConfigFiles, bool verbose) {
  guarded("loadConfigFile", [&] {
    for (const auto& [camera, file] : mapOfConfigFiles) {
      impl_->rig.at(camera, "loadConfigFile");
      const std::string extension = icgp::lower_extension(file);
      if (extension == ".yaml" || extension == ".yml") {
        require_file(file, "configuration file");
        try {
          setTrackerConfig(icgp::load_tracker_config(file, Impl::default_config()));
        } catch (const std::exception& e) {
          throw vpException(vpException::badValue, std::string("vpMbIcgTracker::loadConfigFile: ") + e.what());
        }
        if (verbose) std::cout << "vpMbIcgTracker: parameters from " << file << "\n";
      } else if (extension == ".xml") {
        const std::unique_ptr<vpMbtXmlGenericParser> parser = parse_visp_xml(file, verbose);
        vpCameraParameters parameters;
        parser->getCameraParameters(parameters);
        setCameraParameters(std::map<std::string, vpCameraParameters>{{camera, parameters}});
        store_visp_xml_settings(camera, *parser);
        if (verbose)
          std::cout << "vpMbIcgTracker: camera \"" << camera << "\" from " << file
                    << " (its settings of ViSP's own cues are kept for their getters only)\n";
      } else {
        throw vpException(vpException::badValue, "vpMbIcgTracker::loadConfigFile: '" + file +
                                                     "' must be icgp's YAML (.yaml, .yml) or a ViSP tracker XML (.xml)");
      }
    }
  });
}

void vpMbIcgTracker::setTrackerConfig(const icgp::TrackerConfig& config) {
  try {
    icgp::validate(config, "tracker configuration");
  } catch (const std::exception& e) {
    throw vpException(vpException::badValue, std::string("vpMbIcgTracker::setTrackerConfig: ") + e.what());
  }
  impl_->config = config;
  impl_->tracker_changed();
}

const icgp::TrackerConfig& vpMbIcgTracker::getTrackerConfig() const { return impl_->config; }

void vpMbIcgTracker::setModalities(const std::vector<std::string>& modalities) {
  icgp::TrackerConfig config = impl_->config;
  config.modalities = guarded("setModalities", [&] { return icgp::parse_cue_list(modalities); });
  setTrackerConfig(config);
}

void vpMbIcgTracker::addCue(const icgp::CueEntry& cue) {
  guarded("addCue", [&] {
    icgp::CueRegistry& registry = icgp::CueRegistry::instance();
    if (registry.built_in(cue.name))
      throw std::invalid_argument("'" + cue.name + "' is a built-in cue; select it with setModalities");
    if (!registry.find(cue.name)) registry.add(cue);
  });
  if (icgp::has_cue(impl_->config.modalities, cue.name)) return;
  std::vector<std::string> modalities = impl_->config.modalities;
  modalities.push_back(cue.name);
  setModalities(modalities);
}

void vpMbIcgTracker::setTrackerType(int type) {
  for (const std::string& camera : impl_->rig.names()) impl_->rig.set_types(camera, type, "setTrackerType");
  impl_->tracker_changed();
}

void vpMbIcgTracker::setTrackerType(const std::map<std::string, int>& mapOfTrackerTypes) {
  for (const auto& [camera, type] : mapOfTrackerTypes) impl_->rig.set_types(camera, type, "setTrackerType");
  impl_->tracker_changed();
}

int vpMbIcgTracker::getTrackerType() const { return impl_->rig.reference_camera().types; }

std::map<std::string, int> vpMbIcgTracker::getCameraTrackerTypes() const {
  std::map<std::string, int> types;
  for (const auto& [name, camera] : impl_->rig.cameras()) types[name] = camera.types;
  return types;
}

// ------------------------------------------------------------------------------- cameras

void vpMbIcgTracker::setCameraParameters(const vpCameraParameters& camera) {
  setCameraParameters(std::map<std::string, vpCameraParameters>{{impl_->rig.reference(), camera}});
}

void vpMbIcgTracker::setCameraParameters(const vpCameraParameters& camera1, const vpCameraParameters& camera2) {
  const auto [first, second] = impl_->rig.pair("setCameraParameters");
  setCameraParameters(std::map<std::string, vpCameraParameters>{{first, camera1}, {second, camera2}});
}

void vpMbIcgTracker::setCameraParameters(const std::map<std::string, vpCameraParameters>& mapOfCameraParameters) {
  for (const auto& [name, parameters] : mapOfCameraParameters) {
    icgp::CameraRig::Camera& camera = impl_->rig.at(name, "setCameraParameters");
    camera.parameters = parameters;
    camera.parameters_set = true;
    if (name == impl_->rig.reference()) m_cam = parameters;  // vpMbTracker's clicks and projection error use it
  }
}

void vpMbIcgTracker::getCameraParameters(vpCameraParameters& camera) const {
  camera = impl_->rig.reference_camera().parameters;
}

void vpMbIcgTracker::getCameraParameters(vpCameraParameters& cam1, vpCameraParameters& cam2) const {
  const auto [first, second] = impl_->rig.pair("getCameraParameters");
  cam1 = impl_->rig.at(first, "getCameraParameters").parameters;
  cam2 = impl_->rig.at(second, "getCameraParameters").parameters;
}

void vpMbIcgTracker::getCameraParameters(std::map<std::string, vpCameraParameters>& mapOfCameraParameters) const {
  mapOfCameraParameters.clear();
  for (const auto& [name, camera] : impl_->rig.cameras()) mapOfCameraParameters[name] = camera.parameters;
}

void vpMbIcgTracker::setCameraTransformationMatrix(const std::string& cameraName,
                                                   const vpHomogeneousMatrix& cameraTransformationMatrix) {
  icgp::CameraRig::Camera& camera = impl_->rig.at(cameraName, "setCameraTransformationMatrix");
  if (cameraName == impl_->rig.reference() && !(cameraTransformationMatrix == vpHomogeneousMatrix()))
    throw vpException(vpException::badValue, "vpMbIcgTracker::setCameraTransformationMatrix: \"" + cameraName +
                                                 "\" is the reference camera, its transformation matrix must be "
                                                 "the identity");
  camera.camera_M_reference = cameraTransformationMatrix;
}

void vpMbIcgTracker::setCameraTransformationMatrix(
    const std::map<std::string, vpHomogeneousMatrix>& mapOfTransformationMatrix) {
  for (const auto& [name, M] : mapOfTransformationMatrix) setCameraTransformationMatrix(name, M);
}

std::vector<std::string> vpMbIcgTracker::getCameraNames() const { return impl_->rig.names(); }
std::string vpMbIcgTracker::getReferenceCameraName() const { return impl_->rig.reference(); }

void vpMbIcgTracker::setReferenceCameraName(const std::string& referenceCameraName) {
  impl_->rig.set_reference(referenceCameraName);
  m_cam = impl_->rig.reference_camera().parameters;
}
