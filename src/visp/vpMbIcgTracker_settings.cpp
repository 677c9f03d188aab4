// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker: the settings of ViSP's own cues (moving edges, KLT, depth features,
// visibility, clipping). Each is stored for its getter; where icgp has a parameter of that
// meaning it is set, otherwise the first call says once on std::cerr that it has no effect.
#include <visp3/core/vpPolygon3D.h>

#include <visp3/mbt/vpMbtXmlGenericParser.h>

#include "vpMbIcgTracker_impl.h"

namespace {

const char* const kVisibility = "the cues' visibility comes from the viewpoint models rendered from the mesh";
const char* const kMovingEdges = "icgp's region and edge cues replace the moving edges: their correspondence lines, "
                                 "search ranges and sampling are set in the YAML parameters (region:, edge:)";
const char* const kKlt = "icgp's flow and texture cues replace the KLT tracker (flow: and texture: in the YAML "
                         "parameters)";
const char* const kDepthFeatures = "icgp's depth cue pairs the model's sparse viewpoint points, or with depth as "
                                   "the only cue a render's sampled pixels, with the closest measurements (depth: in "
                                   "the YAML parameters)";

/// The values of a two-camera call as a map of the first and second camera.
template <typename T>
std::map<std::string, T> as_map(const std::pair<std::string, std::string>& cameras, const T& first, const T& second) {
  return {{cameras.first, first}, {cameras.second, second}};
}

/// ViSP's sampling step of its depth features as icgp's dense depth step. ViSP refuses a
/// step of 0 too; the upper bound is the largest image side vpMbIcgTracker takes.
icgp::SamplingStep sampling_step(unsigned int step_x, unsigned int step_y, const std::string& call) {
  const unsigned int most = icgp::kMaxImageSide;
  if (step_x == 0 || step_y == 0 || step_x > most || step_y > most)
    throw vpException(vpException::badValue, "vpMbIcgTracker::" + call + ": sampling step (" + std::to_string(step_x) +
                                                 ", " + std::to_string(step_y) + ") must be pixels from 1 to " +
                                                 std::to_string(most) + " along columns (stepX) and rows (stepY)");
  return {static_cast<int>(step_x), static_cast<int>(step_y)};
}

/// Stores a camera's sampling step; true when it changed. The cues are rebuilt (at the next
/// initialisation) only then, so that loading the same settings again leaves tracking running.
bool store_step(std::optional<icgp::SamplingStep>& stored, const icgp::SamplingStep& step) {
  if (stored && stored->x == step.x && stored->y == step.y) return false;
  stored = step;
  return true;
}

/// A camera's clipping flags: as set, else vpMbGenericTracker's default (none).
unsigned int clipping_flags_of(const std::map<std::string, unsigned int>& flags, const std::string& camera) {
  const auto it = flags.find(camera);
  return it == flags.end() ? static_cast<unsigned int>(vpPolygon3D::NO_CLIPPING) : it->second;
}

/// vpMbKltTracker's KLT settings, what vpMbGenericTracker::getKltOpencv returns before any
/// setKltOpencv.
vpKltOpencv visp_default_klt() {
  vpKltOpencv klt;
  klt.setTrackerId(1);
  klt.setUseHarris(1);
  klt.setMaxFeatures(10000);
  klt.setWindowSize(5);
  klt.setQuality(0.01);
  klt.setMinDistance(5);
  klt.setHarrisFreeParameter(0.01);
  klt.setBlockSize(3);
  klt.setPyramidLevels(3);
  return klt;
}

/// The flow cue's parameters with a KLT tracker's corner and flow settings, which have the
/// same meaning (FlowParams). vpKltOpencv has no getter of its Harris switch: the flow's stays.
icgp::FlowParams with_klt_settings(icgp::FlowParams flow, const vpKltOpencv& klt) {
  flow.max_features = klt.getMaxFeatures();
  flow.quality = klt.getQuality();
  flow.min_distance = klt.getMinDistance();
  flow.block_size = klt.getBlockSize();
  flow.harris_k = klt.getHarrisFreeParameter();
  flow.window_size = klt.getWindowSize();
  flow.pyramid_levels = klt.getPyramidLevels();
  return flow;
}

}  // namespace

void vpMbIcgTracker::apply_klt_settings(const vpKltOpencv& klt, unsigned int mask_border) {
  icgp::TrackerConfig config = impl_->config;
  config.flow = with_klt_settings(config.flow, klt);
  config.flow.mask_border = static_cast<int>(mask_border);
  setTrackerConfig(config);
}

void vpMbIcgTracker::store_visp_xml_settings(const std::string& camera, const vpMbtXmlGenericParser& parser) {
  // What vpMbGenericTracker's loadConfigFile sets from <ecm>, <klt> and <face>, quietly:
  // loading ViSP's files is the expected way in, none of it changes icgp's cues.
  Impl::VispSettings& s = impl_->visp;
  parser.getEdgeMe(s.moving_edges[camera]);
  vpKltOpencv klt = visp_default_klt();
  klt.setMaxFeatures(static_cast<int>(parser.getKltMaxFeatures()));
  klt.setWindowSize(static_cast<int>(parser.getKltWindowSize()));
  klt.setQuality(parser.getKltQuality());
  klt.setMinDistance(parser.getKltMinDistance());
  klt.setHarrisFreeParameter(parser.getKltHarrisParam());
  klt.setBlockSize(static_cast<int>(parser.getKltBlockSize()));
  klt.setPyramidLevels(static_cast<int>(parser.getKltPyramidLevels()));
  s.klts[camera] = klt;
  s.klt_mask_borders[camera] = parser.getKltMaskBorder();
  // The sampling steps of <depth_dense> and <depth_normal> are the one part that steers
  // icgp: its dense depth samples the pixels they say, as ViSP's depth features do.
  icgp::CameraRig::Camera& rig_camera = impl_->rig.at(camera, "loadConfigFile");
  const bool dense_changed = store_step(
      rig_camera.dense_step,
      sampling_step(parser.getDepthDenseSamplingStepX(), parser.getDepthDenseSamplingStepY(), "loadConfigFile"));
  const bool normal_changed = store_step(
      rig_camera.normal_step,
      sampling_step(parser.getDepthNormalSamplingStepX(), parser.getDepthNormalSamplingStepY(), "loadConfigFile"));
  if (dense_changed || normal_changed) impl_->tracker_changed();
  unsigned int& flags = s.clipping_flags[camera];
  if (parser.hasNearClippingDistance()) flags |= vpPolygon3D::NEAR_CLIPPING;
  if (parser.hasFarClippingDistance()) flags |= vpPolygon3D::FAR_CLIPPING;
  if (parser.getFovClipping()) flags |= vpPolygon3D::FOV_CLIPPING;
  // The flow cue's parameters are shared by every camera: they come from the <klt> block of
  // the reference camera, or of the camera that tracks KLT when the reference does not.
  // A file without a <klt> block leaves ViSP's parser at zeros, no window among them.
  const bool has_klt_block = parser.getKltWindowSize() > 0;
  const bool tracks_klt = (impl_->rig.at(camera, "loadConfigFile").types & KLT_TRACKER) != 0;
  const bool reference_tracks_klt = (impl_->rig.at(impl_->rig.reference(), "loadConfigFile").types & KLT_TRACKER) != 0;
  if (has_klt_block && tracks_klt && (camera == impl_->rig.reference() || !reference_tracks_klt))
    apply_klt_settings(klt, parser.getKltMaskBorder());
  if (camera != impl_->rig.reference()) return;
  // As vpMbGenericTracker: the reference camera's angles and clipping flags become
  // vpMbTracker's own; its clipping distances do not.
  vpMbTracker::setAngleAppear(vpMath::rad(parser.getAngleAppear()));
  vpMbTracker::setAngleDisappear(vpMath::rad(parser.getAngleDisappear()));
  vpMbTracker::setClipping(flags);
}

// --------------------------------------------------------------- visibility and clipping

void vpMbIcgTracker::setAngleAppear(const double& a) {
  vpMbTracker::setAngleAppear(a);
  impl_->report_without_effect("setAngleAppear", kVisibility);
}

void vpMbIcgTracker::setAngleAppear(const double& a1, const double& a2) {
  setAngleAppear(as_map(impl_->rig.pair("setAngleAppear"), a1, a2));
}

void vpMbIcgTracker::setAngleAppear(const std::map<std::string, double>& mapOfAngles) {
  for (const auto& [camera, angle] : mapOfAngles) {
    impl_->rig.at(camera, "setAngleAppear");
    if (camera == impl_->rig.reference()) setAngleAppear(angle);
  }
  impl_->report_without_effect("setAngleAppear", kVisibility);
}

void vpMbIcgTracker::setAngleDisappear(const double& a) {
  vpMbTracker::setAngleDisappear(a);
  impl_->report_without_effect("setAngleDisappear", kVisibility);
}

void vpMbIcgTracker::setAngleDisappear(const double& a1, const double& a2) {
  setAngleDisappear(as_map(impl_->rig.pair("setAngleDisappear"), a1, a2));
}

void vpMbIcgTracker::setAngleDisappear(const std::map<std::string, double>& mapOfAngles) {
  for (const auto& [camera, angle] : mapOfAngles) {
    impl_->rig.at(camera, "setAngleDisappear");
    if (camera == impl_->rig.reference()) setAngleDisappear(angle);
  }
  impl_->report_without_effect("setAngleDisappear", kVisibility);
}

void vpMbIcgTracker::setClipping(const unsigned int& flags) {
  std::map<std::string, unsigned int> all;
  for (const std::string& camera : impl_->rig.names()) all[camera] = flags;
  setClipping(all);
}

void vpMbIcgTracker::setClipping(const unsigned int& flags1, const unsigned int& flags2) {
  setClipping(as_map(impl_->rig.pair("setClipping"), flags1, flags2));
}

void vpMbIcgTracker::setClipping(const std::map<std::string, unsigned int>& mapOfClippingFlags) {
  for (const auto& [camera, flags] : mapOfClippingFlags) {
    impl_->rig.at(camera, "setClipping");
    impl_->visp.clipping_flags[camera] = flags;
    if (camera == impl_->rig.reference()) vpMbTracker::setClipping(flags);
  }
  impl_->report_without_effect("setClipping", kVisibility);
}

void vpMbIcgTracker::getClipping(unsigned int& clippingFlag1, unsigned int& clippingFlag2) const {
  std::map<std::string, unsigned int> flags;
  getClipping(flags);
  const auto [first, second] = impl_->rig.pair("getClipping");
  clippingFlag1 = flags[first];
  clippingFlag2 = flags[second];
}

void vpMbIcgTracker::getClipping(std::map<std::string, unsigned int>& mapOfClippingFlags) const {
  mapOfClippingFlags.clear();
  for (const std::string& camera : impl_->rig.names())
    mapOfClippingFlags[camera] = clipping_flags_of(impl_->visp.clipping_flags, camera);
}

// As in vpMbGenericTracker, a near or far distance a camera accepts adds NEAR_CLIPPING or
// FAR_CLIPPING to that camera's flags; vpMbTracker's rule refuses a negative distance and a
// near distance at or beyond the far one (or a far one at or before the near one). The
// reference camera's distances are vpMbTracker's; the other cameras' are not kept, so
// their distances are checked against the reference camera's (the same when, as usual,
// every camera is given the same distances).

void vpMbIcgTracker::setNearClippingDistance(const double& dist) {
  std::map<std::string, double> all;
  for (const std::string& camera : impl_->rig.names()) all[camera] = dist;
  setNearClippingDistance(all);
}

void vpMbIcgTracker::setNearClippingDistance(const double& dist1, const double& dist2) {
  setNearClippingDistance(as_map(impl_->rig.pair("setNearClippingDistance"), dist1, dist2));
}

void vpMbIcgTracker::setNearClippingDistance(const std::map<std::string, double>& mapOfDists) {
  for (const auto& [camera, dist] : mapOfDists) impl_->rig.at(camera, "setNearClippingDistance");
  for (const auto& [camera, dist] : mapOfDists) {
    unsigned int& flags = impl_->visp.clipping_flags[camera];  // NO_CLIPPING when new
    const bool far_set = (flags & vpPolygon3D::FAR_CLIPPING) != 0;
    if (dist >= 0.0 && !(far_set && dist >= getFarClippingDistance())) flags |= vpPolygon3D::NEAR_CLIPPING;
  }
  const auto reference = mapOfDists.find(impl_->rig.reference());
  if (reference != mapOfDists.end()) vpMbTracker::setNearClippingDistance(reference->second);
  impl_->report_without_effect("setNearClippingDistance", kVisibility);
}

void vpMbIcgTracker::setFarClippingDistance(const double& dist) {
  std::map<std::string, double> all;
  for (const std::string& camera : impl_->rig.names()) all[camera] = dist;
  setFarClippingDistance(all);
}

void vpMbIcgTracker::setFarClippingDistance(const double& dist1, const double& dist2) {
  setFarClippingDistance(as_map(impl_->rig.pair("setFarClippingDistance"), dist1, dist2));
}

void vpMbIcgTracker::setFarClippingDistance(const std::map<std::string, double>& mapOfClippingDists) {
  for (const auto& [camera, dist] : mapOfClippingDists) impl_->rig.at(camera, "setFarClippingDistance");
  for (const auto& [camera, dist] : mapOfClippingDists) {
    unsigned int& flags = impl_->visp.clipping_flags[camera];
    const bool near_set = (flags & vpPolygon3D::NEAR_CLIPPING) != 0;
    if (dist >= 0.0 && !(near_set && dist <= getNearClippingDistance())) flags |= vpPolygon3D::FAR_CLIPPING;
  }
  const auto reference = mapOfClippingDists.find(impl_->rig.reference());
  if (reference != mapOfClippingDists.end()) vpMbTracker::setFarClippingDistance(reference->second);
  impl_->report_without_effect("setFarClippingDistance", kVisibility);
}

void vpMbIcgTracker::setLod(bool useLod, const std::string& name) {
  vpMbTracker::setLod(useLod, name);
  impl_->report_without_effect("setLod", kVisibility);
}

void vpMbIcgTracker::setMinLineLengthThresh(double minLineLengthThresh, const std::string& name) {
  vpMbTracker::setMinLineLengthThresh(minLineLengthThresh, name);
  impl_->report_without_effect("setMinLineLengthThresh", kVisibility);
}

void vpMbIcgTracker::setMinPolygonAreaThresh(double minPolygonAreaThresh, const std::string& name) {
  vpMbTracker::setMinPolygonAreaThresh(minPolygonAreaThresh, name);
  impl_->report_without_effect("setMinPolygonAreaThresh", kVisibility);
}

void vpMbIcgTracker::setOgreShowConfigDialog(bool showConfigDialog) {
  vpMbTracker::setOgreShowConfigDialog(showConfigDialog);
  impl_->report_without_effect("setOgreShowConfigDialog", kVisibility);
}

void vpMbIcgTracker::setOgreVisibilityTest(const bool& v) {
  // vpMbTracker's would start Ogre (absent from Debian's ViSP): only the flag is kept.
  useOgre = v;
  impl_->report_without_effect("setOgreVisibilityTest", kVisibility);
}

void vpMbIcgTracker::setScanLineVisibilityTest(const bool& v) {
  vpMbTracker::setScanLineVisibilityTest(v);
  impl_->report_without_effect("setScanLineVisibilityTest", kVisibility);
}

// --------------------------------------------------------------- the cues and the solver

void vpMbIcgTracker::setDepthDenseFilteringMaxDistance(double) {
  impl_->report_without_effect("setDepthDenseFilteringMaxDistance", kDepthFeatures);
}
void vpMbIcgTracker::setDepthDenseFilteringMethod(int) {
  impl_->report_without_effect("setDepthDenseFilteringMethod", kDepthFeatures);
}
void vpMbIcgTracker::setDepthDenseFilteringMinDistance(double) {
  impl_->report_without_effect("setDepthDenseFilteringMinDistance", kDepthFeatures);
}
void vpMbIcgTracker::setDepthDenseFilteringOccupancyRatio(double) {
  impl_->report_without_effect("setDepthDenseFilteringOccupancyRatio", kDepthFeatures);
}
void vpMbIcgTracker::setDepthDenseSamplingStep(unsigned int stepX, unsigned int stepY) {
  const icgp::SamplingStep step = sampling_step(stepX, stepY, "setDepthDenseSamplingStep");
  bool changed = false;
  for (const std::string& camera : impl_->rig.names())
    changed |= store_step(impl_->rig.at(camera, "setDepthDenseSamplingStep").dense_step, step);
  if (changed) impl_->tracker_changed();
}
void vpMbIcgTracker::setDepthNormalFaceCentroidMethod(const vpMbtFaceDepthNormal::vpFaceCentroidType&) {
  impl_->report_without_effect("setDepthNormalFaceCentroidMethod", kDepthFeatures);
}
void vpMbIcgTracker::setDepthNormalFeatureEstimationMethod(const vpMbtFaceDepthNormal::vpFeatureEstimationType&) {
  impl_->report_without_effect("setDepthNormalFeatureEstimationMethod", kDepthFeatures);
}
void vpMbIcgTracker::setDepthNormalPclPlaneEstimationMethod(int) {
  impl_->report_without_effect("setDepthNormalPclPlaneEstimationMethod", kDepthFeatures);
}
void vpMbIcgTracker::setDepthNormalPclPlaneEstimationRansacMaxIter(int) {
  impl_->report_without_effect("setDepthNormalPclPlaneEstimationRansacMaxIter", kDepthFeatures);
}
void vpMbIcgTracker::setDepthNormalPclPlaneEstimationRansacThreshold(double) {
  impl_->report_without_effect("setDepthNormalPclPlaneEstimationRansacThreshold", kDepthFeatures);
}
void vpMbIcgTracker::setDepthNormalSamplingStep(unsigned int stepX, unsigned int stepY) {
  const icgp::SamplingStep step = sampling_step(stepX, stepY, "setDepthNormalSamplingStep");
  bool changed = false;
  for (const std::string& camera : impl_->rig.names())
    changed |= store_step(impl_->rig.at(camera, "setDepthNormalSamplingStep").normal_step, step);
  if (changed) impl_->tracker_changed();
}

void vpMbIcgTracker::setDisplayFeatures(bool displayF) { vpMbTracker::setDisplayFeatures(displayF); }

void vpMbIcgTracker::setFeatureFactors(const std::map<vpTrackerType, double>&) {
  impl_->report_without_effect("setFeatureFactors",
                               "icgp weighs each cue by the noise it estimates from its residuals (docs/accuracy.md)");
}

void vpMbIcgTracker::setGoodMovingEdgesRatioThreshold(double threshold) {
  impl_->visp.good_moving_edges_ratio = threshold;
  impl_->report_without_effect("setGoodMovingEdgesRatioThreshold",
                               "loss is the cues' quality below tracker.quality_threshold (getTrackingQuality)");
}

double vpMbIcgTracker::getGoodMovingEdgesRatioThreshold() const { return impl_->visp.good_moving_edges_ratio; }

void vpMbIcgTracker::setKltOpencv(const vpKltOpencv& t) {
  std::map<std::string, vpKltOpencv> all;
  for (const std::string& camera : impl_->rig.names()) all[camera] = t;
  setKltOpencv(all);
}

void vpMbIcgTracker::setKltOpencv(const vpKltOpencv& t1, const vpKltOpencv& t2) {
  setKltOpencv(as_map(impl_->rig.pair("setKltOpencv"), t1, t2));
}

void vpMbIcgTracker::setKltOpencv(const std::map<std::string, vpKltOpencv>& mapOfKlts) {
  for (const auto& [camera, klt] : mapOfKlts) {
    impl_->rig.at(camera, "setKltOpencv");
    impl_->visp.klts[camera] = klt;
  }
  if (mapOfKlts.empty()) return;
  // The cues' parameters are shared by every camera: the reference camera's settings win.
  // They are the flow cue's, and the maximum number of features is also the texture cue's
  // keypoint count.
  const auto reference = mapOfKlts.find(impl_->rig.reference());
  const auto& klt = reference != mapOfKlts.end() ? reference->second : mapOfKlts.begin()->second;
  if (klt.getMaxFeatures() > 0 && klt.getMaxFeatures() != impl_->config.texture.orb_n_features) {
    icgp::TrackerConfig config = impl_->config;
    config.texture.orb_n_features = klt.getMaxFeatures();
    setTrackerConfig(config);
  }
  apply_klt_settings(klt, getKltMaskBorder());
}

vpKltOpencv vpMbIcgTracker::getKltOpencv() const {
  const auto it = impl_->visp.klts.find(impl_->rig.reference());
  return it == impl_->visp.klts.end() ? visp_default_klt() : it->second;
}

void vpMbIcgTracker::getKltOpencv(vpKltOpencv& klt1, vpKltOpencv& klt2) const {
  std::map<std::string, vpKltOpencv> klts;
  getKltOpencv(klts);
  const auto [first, second] = impl_->rig.pair("getKltOpencv");
  klt1 = klts[first];
  klt2 = klts[second];
}

void vpMbIcgTracker::getKltOpencv(std::map<std::string, vpKltOpencv>& mapOfKlts) const {
  mapOfKlts.clear();
  for (const std::string& camera : impl_->rig.names()) {
    const auto it = impl_->visp.klts.find(camera);
    mapOfKlts[camera] = it == impl_->visp.klts.end() ? visp_default_klt() : it->second;
  }
}

void vpMbIcgTracker::setKltMaskBorder(const unsigned int& e) {
  std::map<std::string, unsigned int> all;
  for (const std::string& camera : impl_->rig.names()) all[camera] = e;
  setKltMaskBorder(all);
}

void vpMbIcgTracker::setKltMaskBorder(const unsigned int& e1, const unsigned int& e2) {
  setKltMaskBorder(as_map(impl_->rig.pair("setKltMaskBorder"), e1, e2));
}

void vpMbIcgTracker::setKltMaskBorder(const std::map<std::string, unsigned int>& mapOfErosions) {
  for (const auto& [camera, erosion] : mapOfErosions) {
    impl_->rig.at(camera, "setKltMaskBorder");
    impl_->visp.klt_mask_borders[camera] = erosion;
  }
  apply_klt_settings(getKltOpencv(), getKltMaskBorder());
}

unsigned int vpMbIcgTracker::getKltMaskBorder() const {
  const auto it = impl_->visp.klt_mask_borders.find(impl_->rig.reference());
  return it == impl_->visp.klt_mask_borders.end() ? 5u : it->second;  // vpMbKltTracker's default
}

void vpMbIcgTracker::setKltThresholdAcceptation(double th) {
  impl_->visp.klt_threshold_acceptation = th;
  impl_->report_without_effect("setKltThresholdAcceptation", kKlt);
}

double vpMbIcgTracker::getKltThresholdAcceptation() const { return impl_->visp.klt_threshold_acceptation; }

void vpMbIcgTracker::setMovingEdge(const vpMe& me) {
  std::map<std::string, vpMe> all;
  for (const std::string& camera : impl_->rig.names()) all[camera] = me;
  setMovingEdge(all);
}

void vpMbIcgTracker::setMovingEdge(const vpMe& me1, const vpMe& me2) {
  setMovingEdge(as_map(impl_->rig.pair("setMovingEdge"), me1, me2));
}

void vpMbIcgTracker::setMovingEdge(const std::map<std::string, vpMe>& mapOfMe) {
  for (const auto& [camera, me] : mapOfMe) {
    impl_->rig.at(camera, "setMovingEdge");
    impl_->visp.moving_edges[camera] = me;
  }
  impl_->report_without_effect("setMovingEdge", kMovingEdges);
}

vpMe vpMbIcgTracker::getMovingEdge() const {
  const auto it = impl_->visp.moving_edges.find(impl_->rig.reference());
  return it == impl_->visp.moving_edges.end() ? vpMe() : it->second;
}

void vpMbIcgTracker::getMovingEdge(vpMe& me1, vpMe& me2) const {
  std::map<std::string, vpMe> moving_edges;
  getMovingEdge(moving_edges);
  const auto [first, second] = impl_->rig.pair("getMovingEdge");
  me1 = moving_edges[first];
  me2 = moving_edges[second];
}

void vpMbIcgTracker::getMovingEdge(std::map<std::string, vpMe>& mapOfMovingEdges) const {
  mapOfMovingEdges.clear();
  for (const std::string& camera : impl_->rig.names()) {
    const auto it = impl_->visp.moving_edges.find(camera);
    mapOfMovingEdges[camera] = it == impl_->visp.moving_edges.end() ? vpMe() : it->second;
  }
}

void vpMbIcgTracker::setOptimizationMethod(const vpMbtOptimizationMethod& opt) {
  vpMbTracker::setOptimizationMethod(opt);
  impl_->report_without_effect("setOptimizationMethod",
                               "icgp fuses its cues in a Newton step with Tikhonov regularisation (tracker: in the "
                               "YAML parameters)");
}

void vpMbIcgTracker::setProjectionErrorComputation(const bool& flag) {
  vpMbTracker::setProjectionErrorComputation(flag);  // computed after each track() on .cao / .wrl models
}

void vpMbIcgTracker::setProjectionErrorDisplay(bool display) {
  vpMbTracker::setProjectionErrorDisplay(display);
  impl_->report_without_effect("setProjectionErrorDisplay", "display() draws the model's edges only");
}

void vpMbIcgTracker::setProjectionErrorDisplayArrowLength(unsigned int length) {
  vpMbTracker::setProjectionErrorDisplayArrowLength(length);
  impl_->report_without_effect("setProjectionErrorDisplayArrowLength", "display() draws the model's edges only");
}

void vpMbIcgTracker::setProjectionErrorDisplayArrowThickness(unsigned int thickness) {
  vpMbTracker::setProjectionErrorDisplayArrowThickness(thickness);
  impl_->report_without_effect("setProjectionErrorDisplayArrowThickness", "display() draws the model's edges only");
}

void vpMbIcgTracker::setUseDepthDenseTracking(const std::string&, const bool&) {
  impl_->report_without_effect("setUseDepthDenseTracking", "icgp's cues use the whole model, not named faces");
}
void vpMbIcgTracker::setUseDepthNormalTracking(const std::string&, const bool&) {
  impl_->report_without_effect("setUseDepthNormalTracking", "icgp's cues use the whole model, not named faces");
}
void vpMbIcgTracker::setUseEdgeTracking(const std::string&, const bool&) {
  impl_->report_without_effect("setUseEdgeTracking", "icgp's cues use the whole model, not named faces");
}
void vpMbIcgTracker::setUseKltTracking(const std::string&, const bool&) {
  impl_->report_without_effect("setUseKltTracking", "icgp's cues use the whole model, not named faces");
}
