// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/servo/pose_estimator.h"

#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <visp3/core/vpTrackingException.h>
#include <visp3/mbt/vpMbGenericTracker.h>
#include <visp3/vision/vpPose.h>

#include "icgp/base/camera_names.h"
#include "icgp/servo/servo_controller.h"
#include "icgp/tracker/tracker_config.h"
#include "icgp/visp/rgbd_tracking_loop.h"
#include "icgp/visp/visp_baseline.h"
#include "icgp/visp/vpMbIcgTracker.h"

namespace icgp::servo {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point begin) {
  return std::chrono::duration<double, std::milli>(Clock::now() - begin).count();
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : " + ") + name;
  return text;
}

/// The gripper of a grasp as a second body of vpMbIcgTracker, through the tracker's
/// additional-bodies extension (addBody, setBodyPose, getBodyPose, isBodyTracked). The only
/// place that touches that extension.
class GripperBody {
 public:
  static constexpr const char* kName = "gripper";

  GripperBody(vpMbIcgTracker& tracker, const std::string& model_file) : tracker_(tracker) {
    tracker_.addBody(kName, model_file);
  }
  /// The gripper's pose for the next initFromPose (a start or a restart).
  void start(const vpHomogeneousMatrix& cMg) { tracker_.setBodyPose(kName, cMg); }
  vpHomogeneousMatrix pose() const { return tracker_.getBodyPose(kName); }
  /// The tracker's verdict on the gripper alone (testTracking covers the reference object).
  bool tracked() const { return tracker_.isBodyTracked(kName); }

 private:
  vpMbIcgTracker& tracker_;
};

/// vpMbIcgTracker on the colour image and the raw depth image (no point cloud needed). In a
/// grasp it tracks the gripper too: the object stays ViSP's reference cMo, the gripper is
/// an additional body.
class IcgpEstimator : public PoseEstimator {
 public:
  IcgpEstimator(const TrackerSpec& spec, const Scenario& scenario, const RgbdSimulator& simulator) {
    TrackerConfig config = spec.config.empty() ? TrackerConfig() : load_tracker_config(spec.config);
    if (!spec.modalities.empty()) config.modalities = spec.modalities;
    if (!scenario.object.regions.empty()) config.regions = scenario.object.regions;
    name_ = "icgp (" + joined(config.modalities) + (config.regions.empty() ? "" : ", multi-region") +
            (scenario.grasp ? ", + gripper" : "") + ")";
    tracker_.setTrackerConfig(config);
    tracker_.loadModel(scenario.object.model);
    if (scenario.grasp) gripper_.emplace(tracker_, scenario.grasp->gripper_model);
    tracker_.setCameraParameters(simulator.color_camera(), simulator.depth_camera());
    tracker_.setCameraTransformationMatrix(kDepthCamera, simulator.depth_M_color());
  }

  void start(const RgbdCapture& first, const vpHomogeneousMatrix& cMo,
             const std::optional<vpHomogeneousMatrix>& cMg) override {
    if (gripper_) {
      if (!cMg) throw std::logic_error("icgp tracker: a grasp starts with the gripper's pose");
      gripper_->start(*cMg);
    }
    tracker_.initFromPose(first.color, cMo);
  }

  PoseEstimate track(const RgbdCapture& capture) override {
    PoseEstimate estimate;
    const auto begin = Clock::now();
    tracker_.track(capture.color, capture.depth_raw, capture.depth_scale);
    estimate.track_ms = ms_since(begin);
    tracker_.getPose(estimate.cMo);
    try {
      tracker_.testTracking();
    } catch (const vpTrackingException& e) {
      estimate.lost = true;
      estimate.why_lost = e.getStringMessage();
    }
    if (gripper_) {
      estimate.cMg = gripper_->pose();
      if (!gripper_->tracked() && !estimate.lost) estimate.why_lost = "the gripper is lost";
      estimate.lost = estimate.lost || !gripper_->tracked();
    }
    for (const vpMbIcgTracker::CueQuality& cue : tracker_.getCueQualities())
      estimate.cues.push_back({cue.cue, cue.camera, cue.quality});
    return estimate;
  }

  PoseEstimate detect(const RgbdCapture& capture, const std::optional<vpHomogeneousMatrix>& cMg) override {
    if (gripper_) {
      if (!cMg) throw std::logic_error("icgp tracker: a grasp detects with the gripper's pose");
      gripper_->start(*cMg);
    }
    PoseEstimate estimate;
    const auto begin = Clock::now();
    const bool found = tracker_.initFromDetection(capture.color, capture.depth_raw, capture.depth_scale);
    estimate.track_ms = ms_since(begin);
    estimate.lost = !found;
    if (!found) {
      estimate.why_lost = tracker_.getDetectionMessage();
      return estimate;
    }
    tracker_.getPose(estimate.cMo);
    estimate.equivalents = tracker_.getDetectionEquivalentPoses();
    if (gripper_) estimate.cMg = cMg;
    return estimate;
  }
  bool detects() const override { return true; }
  bool recovers() const override { return tracker_.getRecovery(); }

  std::string name() const override { return name_; }

 private:
  vpMbIcgTracker tracker_{icgp::kRgbdTrackerTypes};
  std::optional<GripperBody> gripper_;
  std::string name_;
};

/// The .cao model and XML settings vpMbGenericTracker reads, written for the scenario's mesh.
VispModelFiles visp_model_files(const std::string& mesh_path) {
  const fs::path dir = fs::temp_directory_path() / "icgp-servo-visp" / fs::path(mesh_path).stem();
  return VispModelFiles::written_for_mesh(mesh_path, dir.string());
}

/// vpMbGenericTracker through its RGB-D API: grey image and organised point cloud.
class VispEstimator : public PoseEstimator {
 public:
  VispEstimator(const TrackerSpec& spec, const Scenario& scenario, const RgbdSimulator& simulator)
      : configuration_(visp_reference_configuration(spec.visp_configuration)),
        depth_intrinsics_(scenario.camera.depth) {
    const VispModelFiles files = visp_model_files(scenario.object.model);
    tracker_ = make_visp_tracker(configuration_, files);
    {
      const detail::StdoutSilencer quiet_parser;
      if (configuration_.dense_depth)
        tracker_->loadModel(files.model, files.model);
      else
        tracker_->loadModel(files.model);
    }
    if (configuration_.dense_depth) {
      tracker_->setCameraParameters(simulator.color_camera(), simulator.depth_camera());
      tracker_->setCameraTransformationMatrix(std::map<std::string, vpHomogeneousMatrix>{
          {kColorCamera, vpHomogeneousMatrix()}, {kDepthCamera, simulator.depth_M_color()}});
    } else {
      tracker_->setCameraParameters(simulator.color_camera());
    }
  }

  // The object alone: in a grasp the loop takes the gripper from the arm's kinematics.
  void start(const RgbdCapture& first, const vpHomogeneousMatrix& cMo, const std::optional<vpHomogeneousMatrix>&) override {
    tracker_->initFromPose(first.grey, cMo);
  }

  PoseEstimate track(const RgbdCapture& capture) override {
    PoseEstimate estimate;
    // The cloud is the caller's work for either tracker (vpMbIcgTracker reads the raw
    // depth directly): only the track() call is timed, as in `icgp compare`.
    if (configuration_.dense_depth) convert_cloud(capture);
    const auto begin = Clock::now();
    try {
      if (configuration_.dense_depth) {
        std::map<std::string, const vpImage<unsigned char>*> images{{kColorCamera, &capture.grey}};
        std::map<std::string, const std::vector<vpColVector>*> clouds{{kDepthCamera, &cloud_}};
        std::map<std::string, unsigned int> widths{{kDepthCamera, capture.depth_raw.getWidth()}};
        std::map<std::string, unsigned int> heights{{kDepthCamera, capture.depth_raw.getHeight()}};
        tracker_->track(images, clouds, widths, heights);
      } else {
        tracker_->track(capture.grey);
      }
      estimate.track_ms = ms_since(begin);
      tracker_->testTracking();
    } catch (const vpException& e) {
      // ViSP throws when too few features remain or the tracking test fails: lost.
      estimate.lost = true;
      estimate.why_lost = e.getStringMessage();
      estimate.track_ms = ms_since(begin);
    }
    tracker_->getPose(estimate.cMo);
    return estimate;
  }

  std::string name() const override { return "visp (" + configuration_.name + ")"; }

 private:
  /// The organised cloud a ViSP RGB-D program builds from the depth image.
  void convert_cloud(const RgbdCapture& capture) {
    const vpImage<uint16_t>& raw = capture.depth_raw;
    cloud_.resize(static_cast<std::size_t>(raw.getSize()), vpColVector(3, 0.0));
    for (unsigned int i = 0; i < raw.getHeight(); ++i)
      for (unsigned int j = 0; j < raw.getWidth(); ++j) {
        vpColVector& point = cloud_[static_cast<std::size_t>(i) * raw.getWidth() + j];
        const double Z = raw[i][j] * capture.depth_scale;
        point[0] = (j - depth_intrinsics_.pu) * Z / depth_intrinsics_.fu;
        point[1] = (i - depth_intrinsics_.pv) * Z / depth_intrinsics_.fv;
        point[2] = Z;
      }
  }

  VispTrackerConfiguration configuration_;
  Intrinsics depth_intrinsics_;
  std::unique_ptr<vpMbGenericTracker> tracker_;
  std::vector<vpColVector> cloud_;
};

/// The ground truth: what a perfect tracker would say, the reference for the control law.
class OracleEstimator : public PoseEstimator {
 public:
  void start(const RgbdCapture&, const vpHomogeneousMatrix&, const std::optional<vpHomogeneousMatrix>&) override {}
  PoseEstimate track(const RgbdCapture& capture) override {
    return {capture.cMo_true, false, 0.0, capture.cMg_true};
  }
  std::string name() const override { return "oracle (ground truth)"; }
};

/// TrackerKind::kImageOracle: the corners' true image points, through the true lens (its
/// distortion too) and read with the nominal intrinsics, as a calibrated program reads an
/// image; vpPose on them. The gripper of a grasp comes from the arm's kinematics.
class ImageOracleEstimator : public PoseEstimator {
 public:
  ImageOracleEstimator(const Scenario& scenario, const RgbdSimulator& simulator)
      : corners_(bounding_box_corners(scenario.object.model)),
        truth_(simulator.true_calibration()),
        nominal_(scenario.camera.color) {}

  void start(const RgbdCapture&, const vpHomogeneousMatrix&, const std::optional<vpHomogeneousMatrix>&) override {}
  PoseEstimate track(const RgbdCapture& capture) override {
    const auto begin = Clock::now();
    vpPose pose;
    for (vpPoint corner : corners_) {
      corner.track(capture.cMo_true);
      const double x = corner.get_x(), y = corner.get_y();
      const double lens = 1.0 + truth_.color_k1 * (x * x + y * y);
      const double u = truth_.color.fu * x * lens + truth_.color.pu;
      const double v = truth_.color.fv * y * lens + truth_.color.pv;
      corner.set_x((u - nominal_.pu) / nominal_.fu);
      corner.set_y((v - nominal_.pv) / nominal_.fv);
      pose.addPoint(corner);
    }
    PoseEstimate estimate;
    pose.computePose(vpPose::DEMENTHON_VIRTUAL_VS, estimate.cMo);  // eight corners, not coplanar
    estimate.track_ms = ms_since(begin);
    return estimate;
  }
  std::string name() const override { return "image oracle (exact corners, nominal calibration)"; }

 private:
  std::vector<vpPoint> corners_;
  TrueCalibration truth_;
  Intrinsics nominal_;
};

}  // namespace

std::unique_ptr<PoseEstimator> make_pose_estimator(const TrackerSpec& spec, const Scenario& scenario,
                                                   const RgbdSimulator& simulator) {
  switch (spec.kind) {
    case TrackerKind::kIcgp:
      return std::make_unique<IcgpEstimator>(spec, scenario, simulator);
    case TrackerKind::kVisp:
      return std::make_unique<VispEstimator>(spec, scenario, simulator);
    case TrackerKind::kOracle:
      return std::make_unique<OracleEstimator>();
    case TrackerKind::kImageOracle:
      return std::make_unique<ImageOracleEstimator>(scenario, simulator);
  }
  throw std::logic_error("unknown tracker kind");
}

}  // namespace icgp::servo
