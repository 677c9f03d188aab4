// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker: tracking calls, and the results of the last frame.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <type_traits>
#include <visp3/core/vpImageConvert.h>

#include "icgp/modality/cue_kind.h"
#include "icgp/optimizer/covariance.h"
#include "icgp/visp/conversions.h"

#include "vector_cloud_reader.h"
#include "vpMbIcgTracker_impl.h"

using icgp::visp_detail::DepthInput;
using icgp::visp_detail::Failure;
using icgp::visp_detail::guarded;

// ------------------------------------------------------------------------------ tracking

template <typename Image>
void vpMbIcgTracker::track_frame(const std::map<std::string, const Image*>& images,
                                 const std::vector<DepthInput>& depths, const std::string& call) {
  Impl& d = *impl_;
  d.require_initialised(call);
  const vpImage<unsigned char>* reference_grey = guarded(call, [&] { return assemble_frame(images, depths, call); });
  track_step(reference_grey, call);
}

namespace {

/// A camera's colour and depth in one frame are registered, pixel for pixel (one set of
/// parameters serves both): their sizes must be the same.
void require_registered(const std::string& call, const DepthInput& depth, const icgp::ColorImage* color) {
  if (!color || (color->image.cols == static_cast<int>(depth.width) && color->image.rows == static_cast<int>(depth.height)))
    return;
  throw vpException(vpException::badValue,
                    "vpMbIcgTracker::" + call + ": camera '" + depth.camera + "' has a " +
                        std::to_string(color->image.cols) + " x " + std::to_string(color->image.rows) +
                        " image but a " + std::to_string(depth.width) + " x " + std::to_string(depth.height) +
                        " depth; one camera's image and depth must be the same size (registered; give a depth "
                        "of another size to a camera of its own)");
}

std::string no_measurement(const DepthInput& depth) {
  return "the depth of camera '" + depth.camera + "' (" + std::to_string(depth.width) + " x " +
         std::to_string(depth.height) + ") has no valid measurement: every point is NaN, infinite or at Z <= 0";
}

}  // namespace

template <typename Image>
const vpImage<unsigned char>* vpMbIcgTracker::assemble_frame(const std::map<std::string, const Image*>& images,
                                                             const std::vector<DepthInput>& depths,
                                                             const std::string& call) {
  Impl& d = *impl_;
  const icgp::CameraRig& rig = d.rig;
  d.assembler.begin_frame();
  const vpImage<unsigned char>* reference_grey = nullptr;
  for (const auto& [name, image] : images) {
    const icgp::CameraRig::Camera& camera = rig.at(name, call);
    // ViSP programs also pass a depth camera's image: only colour cues read one.
    const icgp::CameraCues& cues = d.cues_of(name);
    if (!image || !cues.reads_image(d.config.modalities)) continue;
    icgp::require_image_size(
        call, [&name = name] { return "the image of camera '" + name + "'"; }, image->getWidth(), image->getHeight());
    d.assembler.set_color(name, *image, camera.parameters, camera.parameters_set, camera.camera_M_reference);
    const int channels = std::is_same_v<Image, vpImage<unsigned char>> ? 1 : 3;
    const auto [last, first_image] = d.image_channels.emplace(name, channels);
    if (!first_image && last->second != channels) {
      last->second = channels;
      d.start_pending = true;  // ViSP takes grey or colour on any frame
    }
    if constexpr (std::is_same_v<Image, vpImage<unsigned char>>)
      if (name == rig.reference()) reference_grey = image;
  }
  bool any_depth = false;
  std::vector<const DepthInput*> without_measurement;
  for (const DepthInput& depth : depths) {
    const icgp::CameraRig::Camera& camera = rig.at(depth.camera, call);
    if (!rig.is_depth_camera(depth.camera)) continue;  // as ViSP: a cloud no cue of the camera reads
    if (depth.width == 0 && depth.height == 0) continue;  // ViSP's "no depth this frame"
    require_registered(call, depth, d.assembler.frame().find_color(depth.camera));
    // A depth without one measurement is none: its camera's depth cue sits the frame out.
    if (!icgp::visp_detail::has_measurement(depth)) {
      without_measurement.push_back(&depth);
      continue;
    }
    d.depth_without_measurement.erase(depth.camera);
    if (depth.points)
      d.assembler.set_depth_points(depth.camera, depth.width, depth.height, camera.parameters,
                                   camera.parameters_set, camera.camera_M_reference, depth.points, depth.read_many);
    else
      d.assembler.set_depth(depth.camera, depth.width, depth.height, camera.parameters, camera.parameters_set,
                            camera.camera_M_reference, depth.depth, depth.read_many);
    any_depth = any_depth || d.cues_of(depth.camera).reads_depth(d.config.modalities);
  }
  bool any_color = false;
  for (const icgp::CameraCues& cues : d.cues) {
    const std::string& name = cues.camera;
    if (rig.is_depth_camera(name)) d.assembler.set_no_depth(name);  // unless delivered above
    if (!cues.reads_image(d.config.modalities)) continue;
    if (!d.assembler.frame().find_color(name))
      throw vpException(vpException::badValue, "vpMbIcgTracker::" + call + ": no image of camera '" + name +
                                                   "', whose cues (EDGE_TRACKER: region, KLT_TRACKER: texture) "
                                                   "read one");
    any_color = true;
  }
  if (!any_color && !any_depth && !without_measurement.empty())
    // As vpMbGenericTracker when its depth trackers find too few features.
    throw vpTrackingException(vpTrackingException::notEnoughPointError,
                              "vpMbIcgTracker::" + call + ": " + no_measurement(*without_measurement.front()) +
                                  ", and no other cue has data this frame: nothing to track");
  // ViSP tracks on with its other cues and says nothing; icgp says it, once per run of such
  // frames of a camera.
  for (const DepthInput* depth : without_measurement)
    if (d.depth_without_measurement.insert(depth->camera).second)
      std::cerr << "vpMbIcgTracker::" << call << ": " << no_measurement(*depth)
                << "; its depth cue sits out until a frame has some\n";
  if (!any_color && !any_depth)
    throw vpException(vpException::badValue,
                      "vpMbIcgTracker::" + call + ": nothing to track: the tracker's cues read depth only, and this "
                                                  "call gives none (track with the maps of point clouds, or with a raw "
                                                  "depth image)");
  return reference_grey;
}

// initFromDetection (vpMbIcgTracker_detection.cpp) assembles its frames here too.
template const vpImage<unsigned char>* vpMbIcgTracker::assemble_frame(
    const std::map<std::string, const vpImage<unsigned char>*>&, const std::vector<DepthInput>&, const std::string&);
template const vpImage<unsigned char>* vpMbIcgTracker::assemble_frame(const std::map<std::string, const vpImage<vpRGBa>*>&,
                                                                      const std::vector<DepthInput>&, const std::string&);
template void vpMbIcgTracker::track_frame(const std::map<std::string, const vpImage<unsigned char>*>&,
                                          const std::vector<DepthInput>&, const std::string&);
template void vpMbIcgTracker::track_frame(const std::map<std::string, const vpImage<vpRGBa>*>&,
                                          const std::vector<DepthInput>&, const std::string&);

void vpMbIcgTracker::track_step(const vpImage<unsigned char>* grey, const std::string& call) {
  Impl& d = *impl_;
  const icgp::Frame& frame = d.assembler.frame();
  icgp::Body& body = d.tracker->body(Impl::kBody);
  const icgp::visp_detail::EndDepthReads end_depth_reads{d.assembler};
  guarded(call, [&] {
    if (d.start_pending) {
      body.reference_T_body = icgp::to_pose(m_cMo);
      d.tracker->start(frame);
      d.start_pending = false;
    }
    std::vector<icgp::BodyResult> results = d.tracker->track(frame);
    d.recovery->after_track(frame, results);
    for (const icgp::BodyResult& r : results) d.body_results[r.body] = r;
    d.quality = results.front().quality;
  }, Failure::kTracking);
  guarded(call, [&] {
    // A lost object is where it was last trusted until it is found again.
    m_cMo = icgp::to_homogeneous_matrix(d.body_results.at(Impl::kBody).reference_T_body);
    d.hessian = d.tracker->last_hessian(Impl::kBody);
    computeVVSInit();
    computeVVSInteractionMatrixAndResidu();

    if (computeCovariance) covarianceMatrix = getCovarianceMatrix();
    if (computeProjError && d.has_visp_model_part) {
      const vpImage<unsigned char>* image = grey ? grey : d.assembler.grey_image(d.rig.reference());
      if (image) projectionError = computeCurrentProjectionError(*image, m_cMo, m_cam);
    }
  });
}

void vpMbIcgTracker::track(const vpImage<unsigned char>& I) {
  track_frame(std::map<std::string, const vpImage<unsigned char>*>{{impl_->rig.reference(), &I}}, {}, "track(I)");
}

void vpMbIcgTracker::track(const vpImage<vpRGBa>& I_color) {
  track_frame(std::map<std::string, const vpImage<vpRGBa>*>{{impl_->rig.reference(), &I_color}}, {},
              "track(I_color)");
}

void vpMbIcgTracker::track(const vpImage<unsigned char>& I1, const vpImage<unsigned char>& I2) {
  const auto [first, second] = impl_->rig.pair("track");
  track_frame(std::map<std::string, const vpImage<unsigned char>*>{{first, &I1}, {second, &I2}}, {},
              "track(I1, I2)");
}

void vpMbIcgTracker::track(const vpImage<vpRGBa>& I_color1, const vpImage<vpRGBa>& I_color2) {
  const auto [first, second] = impl_->rig.pair("track");
  track_frame(std::map<std::string, const vpImage<vpRGBa>*>{{first, &I_color1}, {second, &I_color2}}, {},
              "track(I_color1, I_color2)");
}

void vpMbIcgTracker::track(std::map<std::string, const vpImage<unsigned char>*>& mapOfImages) {
  track_frame(mapOfImages, {}, "track");
}

void vpMbIcgTracker::track(std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages) {
  track_frame(mapOfColorImages, {}, "track");
}

std::vector<vpMbIcgTracker::DepthInput> vpMbIcgTracker::cloud_depth_inputs(
    const std::map<std::string, const std::vector<vpColVector>*>& clouds,
    std::map<std::string, unsigned int>& widths, std::map<std::string, unsigned int>& heights) {
  std::vector<DepthInput> depths;
  for (const auto& [name, cloud] : clouds) {
    const icgp::CameraRig::Camera& camera = impl_->rig.at(name, "track");
    if (!widths.count(name) || !heights.count(name))
      throw vpException(vpException::badValue,
                        "vpMbIcgTracker::track: no width/height of camera '" + name + "''s point cloud");
    DepthInput depth{name, widths[name], heights[name]};
    icgp::visp_detail::require_depth_size("track", depth);
    if (depth.width == 0 && depth.height == 0) {  // ViSP's "no depth this frame", whatever the cloud holds
      depths.push_back(depth);
      continue;
    }
    if (!cloud)
      throw vpException(vpException::badValue, "vpMbIcgTracker::track: the point cloud of camera '" + name + "' is null");
    if (cloud->size() != static_cast<std::size_t>(depth.width) * depth.height)
      throw vpException(vpException::badValue, "vpMbIcgTracker::track: the point cloud of camera '" + name + "' has " +
                                                   std::to_string(cloud->size()) + " points, but width x height is " +
                                                   std::to_string(depth.width) + " x " +
                                                   std::to_string(depth.height) +
                                                   " (an organised cloud has one point per pixel)");
    const icgp::VectorCloudReader reader(*cloud, depth.width);
    icgp::visp_detail::read_cloud(depth, reader, camera.parameters);
    depth.read_many = reader;
    depths.push_back(std::move(depth));
  }
  return depths;
}

void vpMbIcgTracker::track(std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                           std::map<std::string, const std::vector<vpColVector>*>& mapOfPointClouds,
                           std::map<std::string, unsigned int>& mapOfPointCloudWidths,
                           std::map<std::string, unsigned int>& mapOfPointCloudHeights) {
  track_frame(mapOfImages, cloud_depth_inputs(mapOfPointClouds, mapOfPointCloudWidths, mapOfPointCloudHeights), "track");
}

void vpMbIcgTracker::track(std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
                           std::map<std::string, const std::vector<vpColVector>*>& mapOfPointClouds,
                           std::map<std::string, unsigned int>& mapOfPointCloudWidths,
                           std::map<std::string, unsigned int>& mapOfPointCloudHeights) {
  track_frame(mapOfColorImages, cloud_depth_inputs(mapOfPointClouds, mapOfPointCloudWidths, mapOfPointCloudHeights),
              "track");
}

std::string vpMbIcgTracker::depth_camera_of_raw_depth() const {
  const icgp::CameraRig& rig = impl_->rig;
  if (rig.is_depth_camera(rig.reference())) return rig.reference();
  for (const std::string& name : rig.names())
    if (rig.is_depth_camera(name)) return name;
  throw vpException(vpException::badValue, "vpMbIcgTracker::track(I, I_depth_raw, depthScale): no camera has a depth "
                                           "tracker type (DEPTH_DENSE_TRACKER or DEPTH_NORMAL_TRACKER)");
}

vpMbIcgTracker::DepthInput vpMbIcgTracker::raw_depth_input(const vpImage<uint16_t>& I_depth_raw, double depthScale,
                                                           const std::string& call) const {
  if (!(depthScale > 0.0) || !std::isfinite(depthScale))
    throw vpException(vpException::badValue, "vpMbIcgTracker::" + call +
                                                 ": the depth scale must be positive (metres per raw unit), got " +
                                                 std::to_string(depthScale));
  DepthInput depth{depth_camera_of_raw_depth(), I_depth_raw.getWidth(), I_depth_raw.getHeight()};
  icgp::visp_detail::require_depth_size(call, depth);
  depth.depth = [&I_depth_raw, scale = static_cast<float>(depthScale)](int row, int col) {
    return scale * I_depth_raw[static_cast<unsigned int>(row)][col];
  };
  return depth;
}

void vpMbIcgTracker::track(const vpImage<unsigned char>& I, const vpImage<uint16_t>& I_depth_raw, double depthScale) {
  const std::string call = "track(I, I_depth_raw, depthScale)";
  track_frame(std::map<std::string, const vpImage<unsigned char>*>{{impl_->rig.reference(), &I}},
              {raw_depth_input(I_depth_raw, depthScale, call)}, call);
}

void vpMbIcgTracker::track(const vpImage<vpRGBa>& I_color, const vpImage<uint16_t>& I_depth_raw, double depthScale) {
  const std::string call = "track(I_color, I_depth_raw, depthScale)";
  track_frame(std::map<std::string, const vpImage<vpRGBa>*>{{impl_->rig.reference(), &I_color}},
              {raw_depth_input(I_depth_raw, depthScale, call)}, call);
}

void vpMbIcgTracker::testTracking() {
  const icgp::Tracker* tracker = impl_->tracker.get();
  if (!tracker)
    throw vpTrackingException(vpTrackingException::initializationError, "vpMbIcgTracker::testTracking: not initialised");
  const double threshold = tracker->params().quality_threshold;
  if (impl_->recovery->lost(Impl::kBody))
    throw vpTrackingException(vpTrackingException::fatalError,
                              "vpMbIcgTracker: tracking lost, and the object not trusted again since: " +
                                  impl_->recovery->why_lost(Impl::kBody) + " (quality " +
                                  std::to_string(impl_->quality) + ")");
  if (impl_->quality < threshold)
    throw vpTrackingException(vpTrackingException::fatalError,
                              "vpMbIcgTracker: tracking lost (quality " + std::to_string(impl_->quality) +
                                  " below the threshold " + std::to_string(threshold) + ")");
}

double vpMbIcgTracker::getTrackingQuality() const { return impl_->quality; }

std::vector<vpMbIcgTracker::CueQuality> vpMbIcgTracker::getCueQualities() const {
  const Impl& d = *impl_;
  const auto result = d.body_results.find(Impl::kBody);
  if (!d.tracker || result == d.body_results.end()) return {};
  // The tracker's modalities and the result's qualities are in the same order, the order
  // the cues were added (icgp::BodyResult::modalities).
  const std::vector<const icgp::Modality*> cues = d.tracker->modalities(Impl::kBody);
  const std::vector<icgp::ModalityQuality>& qualities = result->second.modalities;
  std::vector<CueQuality> out;
  if (cues.size() != qualities.size()) return out;  // a frame of cues since rebuilt: not theirs
  for (std::size_t i = 0; i < cues.size(); ++i) out.push_back({cues[i]->name(), cues[i]->camera(), qualities[i]});
  return out;
}

void vpMbIcgTracker::setMask(const vpImage<bool>& mask) {
  guarded("setMask", [&] {
    vpMbTracker::setMask(mask);
    impl_->assembler.set_mask(mask);
  });
}

// ----------------------------------------------------------------------------- results

void vpMbIcgTracker::getPose(vpHomogeneousMatrix& c1Mo, vpHomogeneousMatrix& c2Mo) const {
  const auto [first, second] = impl_->rig.pair("getPose");
  c1Mo = impl_->rig.at(first, "getPose").camera_M_reference * m_cMo;
  c2Mo = impl_->rig.at(second, "getPose").camera_M_reference * m_cMo;
}

void vpMbIcgTracker::getPose(std::map<std::string, vpHomogeneousMatrix>& mapOfCameraPoses) const {
  mapOfCameraPoses.clear();
  for (const auto& [name, camera] : impl_->rig.cameras()) mapOfCameraPoses[name] = camera.camera_M_reference * m_cMo;
}

void vpMbIcgTracker::computeVVSInit() {
  // clear(), not resize(0): ViSP's resize to 0 hands memset a null pointer (undefined
  // behaviour that UBSan reports).
  m_error.clear();
  m_w.clear();
}

void vpMbIcgTracker::computeVVSInteractionMatrixAndResidu() {
  if (!impl_->tracker) return;
  std::vector<double>& residuals = impl_->residuals;
  std::vector<double>& weights = impl_->weights;
  residuals.clear();
  weights.clear();
  impl_->tracker->residuals(Impl::kBody, residuals, weights);
  m_error.resize(static_cast<unsigned int>(residuals.size()), false);
  m_w.resize(static_cast<unsigned int>(weights.size()), false);
  for (unsigned int i = 0; i < m_error.size(); ++i) {
    m_error[i] = residuals[i];
    m_w[i] = weights[i];
  }
}

vpColVector vpMbIcgTracker::getError() const { return m_error; }
vpColVector vpMbIcgTracker::getRobustWeights() const { return m_w; }

std::vector<const icgp::Modality*> vpMbIcgTracker::cues_counted_as(icgp::VispFeatures features,
                                                                    const std::string& camera) const {
  std::vector<const icgp::Modality*> out;
  if (!impl_->tracker) return out;
  // Registry order, then the tracker's order: region before edge, texture before flow. A
  // cue that reads no camera (a sensor's) is the reference camera's.
  const std::vector<const icgp::Modality*> all = impl_->tracker->modalities(Impl::kBody);
  const auto of_camera = [&](const icgp::Modality& m) {
    return camera.empty() || m.camera() == camera || (m.camera().empty() && camera == impl_->rig.reference());
  };
  for (const icgp::CueEntry& entry : icgp::CueRegistry::instance().entries()) {
    if (entry.visp_features != features) continue;
    for (const icgp::Modality* m : all)
      if (m->name() == entry.name && of_camera(*m)) out.push_back(m);
  }
  return out;
}

unsigned int vpMbIcgTracker::count_features(icgp::VispFeatures features, const std::string& camera,
                                            int depth_type) const {
  if (!impl_->tracker) return 0;
  // The optimizer's part of each cue in the last update: the correspondences it summed
  // over are the features ViSP counts in its minimisation.
  const std::vector<const icgp::Modality*> all = impl_->tracker->modalities(Impl::kBody);
  const std::vector<icgp::CueTerms>& terms = impl_->tracker->last_cue_terms(Impl::kBody);
  unsigned int n = 0;
  for (std::size_t i = 0; i < terms.size(); ++i) {
    const icgp::Modality& m = *all[i];
    const icgp::CueEntry* entry = icgp::CueRegistry::instance().find(m.name());
    if (!entry || entry->visp_features != features || (!camera.empty() && m.camera() != camera)) continue;
    if (depth_type != 0) {
      // A camera with both depth types counts as DEPTH_DENSE, ICG's point-to-plane cue.
      const int types = impl_->rig.at(m.camera(), "getNbFeatures").types;
      if (((types & DEPTH_DENSE_TRACKER) ? DEPTH_DENSE_TRACKER : DEPTH_NORMAL_TRACKER) != depth_type) continue;
    }
    n += static_cast<unsigned int>(terms[i].n_correspondences);
  }
  return n;
}

unsigned int vpMbIcgTracker::getNbFeaturesEdge() const { return count_features(icgp::VispFeatures::kEdge); }
unsigned int vpMbIcgTracker::getNbFeaturesKlt() const {
  // ViSP counts the rows of its KLT error vector: x and y of each point, as getError() here.
  return 2 * count_features(icgp::VispFeatures::kKlt);
}
unsigned int vpMbIcgTracker::getNbFeaturesDepthNormal() const {
  return count_features(icgp::VispFeatures::kDepth, "", DEPTH_NORMAL_TRACKER);
}
unsigned int vpMbIcgTracker::getNbFeaturesDepthDense() const {
  return count_features(icgp::VispFeatures::kDepth, "", DEPTH_DENSE_TRACKER);
}

unsigned int vpMbIcgTracker::getNbPoints(unsigned int) const {
  return count_features(icgp::VispFeatures::kEdge, impl_->rig.reference());
}

void vpMbIcgTracker::getNbPoints(std::map<std::string, unsigned int>& mapOfNbPoints, unsigned int) const {
  mapOfNbPoints.clear();
  for (const std::string& name : impl_->rig.names())
    mapOfNbPoints[name] = count_features(icgp::VispFeatures::kEdge, name);
}

std::vector<std::vector<double>> vpMbIcgTracker::features_for_display(const std::string& camera) const {
  std::vector<std::vector<double>> out;
  constexpr double kFullWeight = 0.0, kDownWeighted = 4.0;  // vpMeSite::NO_SUPPRESSION, M_ESTIMATOR
  std::vector<icgp::ImageFeature> features;
  for (const icgp::Modality* m : cues_counted_as(icgp::VispFeatures::kEdge, camera)) m->append_image_features(features);
  for (const icgp::ImageFeature& f : features)
    out.push_back({0.0, f.pixel.y(), f.pixel.x(), f.weight >= 0.5 ? kFullWeight : kDownWeighted});
  features.clear();
  for (const icgp::Modality* m : cues_counted_as(icgp::VispFeatures::kKlt, camera)) m->append_image_features(features);
  for (std::size_t id = 0; id < features.size(); ++id)
    out.push_back({1.0, features[id].pixel.y(), features[id].pixel.x(), static_cast<double>(id)});
  return out;
}

std::vector<std::vector<double>> vpMbIcgTracker::getFeaturesForDisplay() {
  return features_for_display(impl_->rig.reference());
}

void vpMbIcgTracker::getFeaturesForDisplay(std::map<std::string, std::vector<std::vector<double>>>& mapOfFeatures) {
  mapOfFeatures.clear();
  for (const std::string& name : impl_->rig.names()) mapOfFeatures[name] = features_for_display(name);
}

std::map<int, vpImagePoint> vpMbIcgTracker::getKltImagePointsWithId() const {
  std::vector<icgp::ImageFeature> features;
  for (const icgp::Modality* m : cues_counted_as(icgp::VispFeatures::kKlt, impl_->rig.reference()))
    m->append_image_features(features);
  std::map<int, vpImagePoint> points;
  for (std::size_t id = 0; id < features.size(); ++id)
    points[static_cast<int>(id)] = vpImagePoint(features[id].pixel.y(), features[id].pixel.x());
  return points;
}

std::vector<vpImagePoint> vpMbIcgTracker::getKltImagePoints() const {
  std::vector<vpImagePoint> points;
  for (const auto& [id, point] : getKltImagePointsWithId()) points.push_back(point);
  return points;
}

int vpMbIcgTracker::getKltNbPoints() const { return static_cast<int>(getKltImagePointsWithId().size()); }

std::vector<cv::Point2f> vpMbIcgTracker::getKltPoints() const {
  std::vector<cv::Point2f> points;
  for (const auto& [id, point] : getKltImagePointsWithId())
    points.emplace_back(static_cast<float>(point.get_u()), static_cast<float>(point.get_v()));
  return points;
}

double vpMbIcgTracker::computeCurrentProjectionError(const vpImage<unsigned char>& I, const vpHomogeneousMatrix& cMo,
                                                     const vpCameraParameters& cam) {
  if (!impl_->has_visp_model_part)
    throw vpException(vpException::notImplementedError,
                      "vpMbIcgTracker::computeCurrentProjectionError: the projection error is ViSP's, computed on the "
                      "edges of a .cao or .wrl model; this model has none");
  return vpMbTracker::computeCurrentProjectionError(I, cMo, cam);
}

double vpMbIcgTracker::computeCurrentProjectionError(const vpImage<vpRGBa>& I, const vpHomogeneousMatrix& cMo,
                                                     const vpCameraParameters& cam) {
  vpImage<unsigned char> grey;
  vpImageConvert::convert(I, grey);
  return computeCurrentProjectionError(grey, cMo, cam);
}

vpMatrix vpMbIcgTracker::getCovarianceMatrix() const {
  if (!impl_->hessian)
    throw vpTrackingException(vpTrackingException::initializationError,
                              "vpMbIcgTracker::getCovarianceMatrix: no frame has been tracked yet");
  const Eigen::Matrix<double, 6, 6> camera_covariance = icgp::camera_twist_covariance(*impl_->hessian, icgp::to_pose(m_cMo));
  vpMatrix out(6, 6);
  for (unsigned int i = 0; i < 6; ++i)
    for (unsigned int j = 0; j < 6; ++j) out[i][j] = camera_covariance(i, j);
  return out;
}

std::list<vpMbtDistanceCircle*>& vpMbIcgTracker::getFeaturesCircle() { return impl_->no_circles; }
std::list<vpMbtDistanceKltCylinder*>& vpMbIcgTracker::getFeaturesKltCylinder() { return impl_->no_klt_cylinders; }
std::list<vpMbtDistanceKltPoints*>& vpMbIcgTracker::getFeaturesKlt() { return impl_->no_klt_points; }

void vpMbIcgTracker::getLcircle(std::list<vpMbtDistanceCircle*>& circlesList, unsigned int) const {
  circlesList.clear();
}
void vpMbIcgTracker::getLcircle(const std::string& cameraName, std::list<vpMbtDistanceCircle*>& circlesList,
                                unsigned int) const {
  impl_->rig.at(cameraName, "getLcircle");
  circlesList.clear();
}
void vpMbIcgTracker::getLcylinder(std::list<vpMbtDistanceCylinder*>& cylindersList, unsigned int) const {
  cylindersList.clear();
}
void vpMbIcgTracker::getLcylinder(const std::string& cameraName, std::list<vpMbtDistanceCylinder*>& cylindersList,
                                  unsigned int) const {
  impl_->rig.at(cameraName, "getLcylinder");
  cylindersList.clear();
}
void vpMbIcgTracker::getLline(std::list<vpMbtDistanceLine*>& linesList, unsigned int) const { linesList.clear(); }
void vpMbIcgTracker::getLline(const std::string& cameraName, std::list<vpMbtDistanceLine*>& linesList,
                              unsigned int) const {
  impl_->rig.at(cameraName, "getLline");
  linesList.clear();
}
