// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker: starting without a given pose (initFromDetection) and recovery after a loss.
#include <cstdio>

#include "icgp/visp/conversions.h"

#include "vpMbIcgTracker_impl.h"

using icgp::visp_detail::Failure;
using icgp::visp_detail::guarded;

template <typename Image>
bool vpMbIcgTracker::detect_frame(const std::map<std::string, const Image*>& images,
                                  const std::vector<DepthInput>& depths, const std::string& call) {
  Impl& d = *impl_;
  guarded(call, [&] {
    build_tracker();
    d.apply_body_settings();
  });
  guarded(call, [&] { assemble_frame(images, depths, call); });
  const icgp::visp_detail::EndDepthReads end_depth_reads{d.assembler};
  return guarded(call, [&] {
    const icgp::Detection detection = d.recovery->initialise(d.assembler.frame());
    d.detection_equivalents.clear();
    for (const icgp::Pose& pose : detection.equivalents) d.detection_equivalents.push_back(icgp::to_homogeneous_matrix(pose));
    if (!detection.found) {
      d.detection_message = "not found: " + detection.why_not;
      return false;
    }
    char message[160];
    std::snprintf(message, sizeof message, "found with quality %.3f (%d hypotheses refined of %d candidates)%s",
                  detection.quality, detection.refined, detection.candidates,
                  detection.equivalents.empty() ? "" : "; the object's symmetry gives equivalent poses");
    d.detection_message = message;
    m_cMo = icgp::to_homogeneous_matrix(detection.reference_T_body);
    d.start_pending = false;  // initialise() started the cues on this frame
    d.quality = detection.quality;
    d.hessian.reset();
    return true;
  }, Failure::kTracking);
}

bool vpMbIcgTracker::initFromDetection(const vpImage<unsigned char>& I) {
  return detect_frame(std::map<std::string, const vpImage<unsigned char>*>{{impl_->rig.reference(), &I}}, {},
                      "initFromDetection(I)");
}

bool vpMbIcgTracker::initFromDetection(const vpImage<vpRGBa>& I_color) {
  return detect_frame(std::map<std::string, const vpImage<vpRGBa>*>{{impl_->rig.reference(), &I_color}}, {},
                      "initFromDetection(I_color)");
}

bool vpMbIcgTracker::initFromDetection(const vpImage<unsigned char>& I, const vpImage<uint16_t>& I_depth_raw,
                                       double depthScale) {
  const std::string call = "initFromDetection(I, I_depth_raw, depthScale)";
  return detect_frame(std::map<std::string, const vpImage<unsigned char>*>{{impl_->rig.reference(), &I}},
                      {raw_depth_input(I_depth_raw, depthScale, call)}, call);
}

bool vpMbIcgTracker::initFromDetection(const vpImage<vpRGBa>& I_color, const vpImage<uint16_t>& I_depth_raw,
                                       double depthScale) {
  const std::string call = "initFromDetection(I_color, I_depth_raw, depthScale)";
  return detect_frame(std::map<std::string, const vpImage<vpRGBa>*>{{impl_->rig.reference(), &I_color}},
                      {raw_depth_input(I_depth_raw, depthScale, call)}, call);
}

bool vpMbIcgTracker::initFromDetection(std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                                       std::map<std::string, const std::vector<vpColVector>*>& mapOfPointClouds,
                                       std::map<std::string, unsigned int>& mapOfPointCloudWidths,
                                       std::map<std::string, unsigned int>& mapOfPointCloudHeights) {
  return detect_frame(mapOfImages, cloud_depth_inputs(mapOfPointClouds, mapOfPointCloudWidths, mapOfPointCloudHeights),
                      "initFromDetection");
}

bool vpMbIcgTracker::initFromDetection(std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
                                       std::map<std::string, const std::vector<vpColVector>*>& mapOfPointClouds,
                                       std::map<std::string, unsigned int>& mapOfPointCloudWidths,
                                       std::map<std::string, unsigned int>& mapOfPointCloudHeights) {
  return detect_frame(mapOfColorImages,
                      cloud_depth_inputs(mapOfPointClouds, mapOfPointCloudWidths, mapOfPointCloudHeights),
                      "initFromDetection");
}

std::string vpMbIcgTracker::getDetectionMessage() const { return impl_->detection_message; }

std::vector<vpHomogeneousMatrix> vpMbIcgTracker::getDetectionEquivalentPoses() const {
  return impl_->detection_equivalents;
}

void vpMbIcgTracker::setRecovery(bool enable) {
  impl_->config.detection.recovery = enable;
  if (impl_->recovery) impl_->recovery->set_recovery(enable);
}

bool vpMbIcgTracker::getRecovery() const { return impl_->config.detection.recovery; }
