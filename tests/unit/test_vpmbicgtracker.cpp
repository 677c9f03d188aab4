// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker's ViSP contract on teabox-blender: display edges and projection error
// against vpMbGenericTracker's, the raw-depth and PCL inputs against the cloud input,
// residuals, covariance convention, lost detection, multi-part models, .cao / .wrl models
// read once by ViSP's parser.
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <functional>
#include <iostream>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/core/vpTrackingException.h>
#include <visp3/mbt/vpMbGenericTracker.h>

#include "icgp/base/standard_stream_capture.h"
#include "icgp/eval/metrics.h"
#include "icgp/eval/sequence.h"
#include "icgp/render/model_edges.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/rgbd_tracking_loop.h"
#include "icgp/visp/conversions.h"
#include "icgp/visp/visp_camera_xml.h"
#include "icgp/visp/vpMbIcgTracker.h"
#include "test_temp_dir.h"
#include "vpmbicgtracker_test_setup.h"

using namespace icgp;

namespace {

const std::filesystem::path kBlender = std::filesystem::path(ICGP_TEST_DATA_DIR) / "teabox-blender";
const std::string kTeabox = (kBlender / "teabox.cao").string();

const std::vector<Frame>& teabox_frames() {
  static const std::vector<Frame> frames = [] {
    // Blender's principal point convention, for both trackers alike: these tests measure the
    // trackers, not how far the XML's (320, 240) is from the renderer's camera.
    SequenceOptions blender = visp_sequence_options();
    blender.blender_principal_point = true;
    const Sequence sequence = Sequence::open(kBlender.string(), blender);
    std::vector<Frame> f;
    for (int i = 0; i < 8; ++i) f.push_back(sequence.load(test::kFirstTeaboxFrame + i));  // where the box moves
    return f;
  }();
  return frames;
}

struct VispFrame {
  vpImage<vpRGBa> color;
  vpImage<unsigned char> grey;
  vpImage<uint16_t> depth_raw;  ///< 0.1 mm units
};

/// Each pixel's point on its pinhole ray at the raw depth (0.1 mm units).
std::vector<Eigen::Vector3f> pinhole_points(const Intrinsics& k, const vpImage<uint16_t>& depth_raw) {
  std::vector<Eigen::Vector3f> points;
  for (unsigned int r = 0; r < depth_raw.getHeight(); ++r)
    for (unsigned int c = 0; c < depth_raw.getWidth(); ++c)
      points.push_back(k.back_project<float>(static_cast<float>(c), static_cast<float>(r), depth_raw[r][c] * 1e-4f));
  return points;
}

VispFrame to_visp(const Frame& frame) {
  VispFrame v;
  to_vp_image(frame.colors[0].image, v.color);
  cv::Mat grey;
  cv::cvtColor(frame.colors[0].image, grey, cv::COLOR_BGR2GRAY);
  to_vp_image(grey, v.grey);
  const cv::Mat& depth = frame.depths[0].depth;
  v.depth_raw.resize(static_cast<unsigned int>(depth.rows), static_cast<unsigned int>(depth.cols));
  for (int r = 0; r < depth.rows; ++r)
    for (int c = 0; c < depth.cols; ++c)
      v.depth_raw[r][c] = static_cast<uint16_t>(std::lround(depth.at<float>(r, c) * 1e4f));
  return v;
}

/// Coarse viewpoint models (fast to generate) and icgp's defaults.
void configure(vpMbIcgTracker& tracker, const std::vector<std::string>& modalities) {
  TrackerConfig config = tracker.getTrackerConfig();
  config.region_model.n_divides = config.depth_model.n_divides = 3;
  config.region_model.image_size = config.depth_model.image_size = 800;
  config.cache_dir = (std::filesystem::temp_directory_path() / "icgp-test-vpmbicgtracker-cache").string();
  config.modalities = parse_cue_list(modalities);
  tracker.setTrackerConfig(config);
}

void set_cameras(vpMbIcgTracker& tracker, const Frame& frame) {
  tracker.setCameraParameters(to_camera_parameters(frame.colors[0].intrinsics),
                              to_camera_parameters(frame.depths[0].intrinsics));
  tracker.setCameraTransformationMatrix("Camera2", to_homogeneous_matrix(frame.depths[0].camera_T_reference));
}

double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double s = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-12), 0.0, 1.0);
  return (p - (a + s * ab)).norm();
}

std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> as_segments(const std::vector<std::vector<double>>& model) {
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> out;
  for (const auto& f : model)
    if (f[0] == 0) out.emplace_back(Eigen::Vector2d(f[2], f[1]), Eigen::Vector2d(f[4], f[3]));
  return out;
}

}  // namespace

TEST_CASE("vpMbIcgTracker shows the teabox edges vpMbGenericTracker shows at the same pose") {
  const Frame& frame = teabox_frames().front();
  const vpCameraParameters cam = to_camera_parameters(frame.colors[0].intrinsics);
  const vpHomogeneousMatrix cMo = to_homogeneous_matrix(*frame.truth());

  vpMbIcgTracker ours;
  ours.loadModel(kTeabox);
  vpMbGenericTracker visp(vpMbGenericTracker::EDGE_TRACKER);
  visp.loadModel(kTeabox);
  visp.setCameraParameters(cam);
  visp.initFromPose(to_visp(frame).grey, cMo);  // ViSP decides face visibility here
  const auto our_lines = as_segments(ours.getModelForDisplay(640, 480, cMo, cam));
  const auto visp_lines = as_segments(visp.getModelForDisplay(640, 480, cMo, cam));
  REQUIRE(!visp_lines.empty());
  REQUIRE(!our_lines.empty());

  // Every point we draw lies on an edge ViSP draws, and we draw as much as ViSP.
  double our_length = 0.0, visp_length = 0.0, worst = 0.0;
  for (const auto& [a, b] : our_lines) {
    our_length += (b - a).norm();
    for (double s = 0.0; s <= 1.0; s += 0.1) {
      const Eigen::Vector2d p = a + s * (b - a);
      double nearest = 1e9;
      for (const auto& [c, d] : visp_lines) nearest = std::min(nearest, distance_to_segment(p, c, d));
      worst = std::max(worst, nearest);
    }
  }
  for (const auto& [c, d] : visp_lines) visp_length += (d - c).norm();
  CHECK(worst < 2.0);
  CHECK(our_length == Approx(visp_length).epsilon(0.1));

  // The full model shows the hidden edges too: all 12 edges of the box.
  const auto full = as_segments(ours.getModelForDisplay(640, 480, cMo, cam, true));
  CHECK(full.size() == 12);
}

TEST_CASE("vpMbIcgTracker's projection error is ViSP's") {
  const Frame& frame = teabox_frames().front();
  const VispFrame v = to_visp(frame);
  const vpCameraParameters cam = to_camera_parameters(frame.colors[0].intrinsics);
  const vpHomogeneousMatrix truth = to_homogeneous_matrix(*frame.truth());
  const vpHomogeneousMatrix off = vpHomogeneousMatrix(0.01, 0.0, 0.0, 0.0, 0.0, 0.1) * truth;

  vpMbIcgTracker ours;
  ours.loadModel(kTeabox);
  vpMbGenericTracker visp(vpMbGenericTracker::EDGE_TRACKER);
  visp.loadModel(kTeabox);
  visp.setCameraParameters(cam);
  const double at_truth = ours.computeCurrentProjectionError(v.grey, truth, cam);
  CHECK(at_truth == Approx(visp.computeCurrentProjectionError(v.grey, truth, cam)).margin(1e-9));
  CHECK(ours.computeCurrentProjectionError(v.grey, off, cam) ==
        Approx(visp.computeCurrentProjectionError(v.grey, off, cam)).margin(1e-9));
  CHECK(at_truth < ours.computeCurrentProjectionError(v.grey, off, cam));
}

TEST_CASE("vpMbIcgTracker tracks raw depth, PCL clouds and vector clouds alike") {
  const auto& frames = teabox_frames();
  const vpHomogeneousMatrix cMo0 = to_homogeneous_matrix(*frames.front().truth());

  const auto run = [&](const std::function<void(vpMbIcgTracker&, const Frame&, const VispFrame&)>& track) {
    vpMbIcgTracker tracker(kRgbdTrackerTypes);
    configure(tracker, {"region", "depth"});
    tracker.loadModel(kTeabox);
    set_cameras(tracker, frames.front());
    const VispFrame first = to_visp(frames.front());
    tracker.initFromPose(first.color, cMo0);
    std::vector<vpHomogeneousMatrix> poses;
    for (const Frame& f : frames) {
      track(tracker, f, to_visp(f));
      poses.push_back(tracker.getPose());
    }
    return poses;
  };

  const auto raw = run([](vpMbIcgTracker& t, const Frame&, const VispFrame& v) { t.track(v.color, v.depth_raw, 1e-4); });
  // Clouds as a sensor's SDK de-projects the depth image: each pixel's point on its ray.
  const auto vectors = run([](vpMbIcgTracker& t, const Frame& f, const VispFrame& v) {
    const std::vector<Eigen::Vector3f> points = pinhole_points(f.depths[0].intrinsics, v.depth_raw);
    std::vector<vpColVector> cloud(v.depth_raw.getSize(), vpColVector(3, 0.0));
    for (unsigned int i = 0; i < v.depth_raw.getSize(); ++i)
      for (unsigned int k = 0; k < 3; ++k) cloud[i][k] = points[i][k];
    std::map<std::string, const vpImage<vpRGBa>*> images{{"Camera1", &v.color}};
    std::map<std::string, const std::vector<vpColVector>*> clouds{{"Camera2", &cloud}};
    std::map<std::string, unsigned int> widths{{"Camera2", v.depth_raw.getWidth()}};
    std::map<std::string, unsigned int> heights{{"Camera2", v.depth_raw.getHeight()}};
    t.track(images, clouds, widths, heights);
  });
  const auto pcl_clouds = run([](vpMbIcgTracker& t, const Frame& f, const VispFrame& v) {
    const std::vector<Eigen::Vector3f> points = pinhole_points(f.depths[0].intrinsics, v.depth_raw);
    auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>(v.depth_raw.getWidth(), v.depth_raw.getHeight());
    for (unsigned int i = 0; i < v.depth_raw.getSize(); ++i)
      cloud->points[i].getVector3fMap() = points[i];
    std::map<std::string, const vpImage<vpRGBa>*> images{{"Camera1", &v.color}};
    std::map<std::string, std::shared_ptr<const pcl::PointCloud<pcl::PointXYZ>>> clouds{{"Camera2", cloud}};
    t.track(images, clouds);
  });

  for (std::size_t i = 0; i < frames.size(); ++i) {
    INFO("frame " << i);
    CHECK(translation_error_mm(to_pose(raw[i]), *frames[i].truth()) < 0.5);
    CHECK(rotation_error_deg(to_pose(raw[i]), *frames[i].truth()) < 0.3);
    // Depth in float from the same 0.1 mm values: the same frames to float precision.
    CHECK(translation_error_mm(to_pose(vectors[i]), to_pose(raw[i])) < 1e-3);
    CHECK(translation_error_mm(to_pose(pcl_clouds[i]), to_pose(raw[i])) < 1e-3);
  }
}

TEST_CASE("vpMbIcgTracker reads clouds as 3D points: a sensor's cloud de-projected with its lens distortion") {
  // A depth sensor with barrel distortion sees the true surface points at distorted pixels;
  // its SDK de-projects each pixel through the distortion, so a cloud pixel holds the true
  // point, off the pinhole ray of that pixel (by up to ~20 px at the corners here). Read as
  // Z alone on pinhole rays, the same cloud places every point beside the surface.
  const auto& frames = teabox_frames();
  constexpr float kBarrel = -0.15f;  // u = pu + fu x (1 + k r^2)
  const auto distorted_cloud = [&](const Frame& f, bool z_only) {
    const Intrinsics& k = f.depths[0].intrinsics;
    const VispFrame v = to_visp(f);
    std::vector<vpColVector> cloud(v.depth_raw.getSize(), vpColVector(3, 0.0));
    for (const Eigen::Vector3f& P : pinhole_points(k, v.depth_raw)) {
      if (!(P.z() > 0.f)) continue;
      const float x = P.x() / P.z(), y = P.y() / P.z(), radial = 1.f + kBarrel * (x * x + y * y);
      const long u = std::lround(k.pu + k.fu * x * radial), row = std::lround(k.pv + k.fv * y * radial);
      if (u < 0 || row < 0 || u >= k.width || row >= k.height) continue;
      vpColVector& pixel = cloud[static_cast<std::size_t>(row) * k.width + u];
      if (pixel[2] != 0.0 && pixel[2] < P.z()) continue;  // the nearest surface is seen
      const Eigen::Vector3f on_pinhole_ray =
          k.back_project<float>(static_cast<float>(u), static_cast<float>(row), P.z());
      const Eigen::Vector3f stored = z_only ? on_pinhole_ray : P;
      for (unsigned int c = 0; c < 3; ++c) pixel[c] = stored[c];
    }
    return cloud;
  };
  const auto mean_error_mm = [&](bool z_only) {
    vpMbIcgTracker tracker(kRgbdTrackerTypes);
    configure(tracker, {"depth"});
    tracker.loadModel(kTeabox);
    set_cameras(tracker, frames.front());
    tracker.initFromPose(vpImage<unsigned char>(), to_homogeneous_matrix(*frames.front().truth()));
    double sum = 0.0;
    for (const Frame& f : frames) {
      const std::vector<vpColVector> cloud = distorted_cloud(f, z_only);
      std::map<std::string, const vpImage<unsigned char>*> images;
      std::map<std::string, const std::vector<vpColVector>*> clouds{{"Camera2", &cloud}};
      std::map<std::string, unsigned int> widths{{"Camera2", static_cast<unsigned int>(f.depths[0].intrinsics.width)}};
      std::map<std::string, unsigned int> heights{{"Camera2", static_cast<unsigned int>(f.depths[0].intrinsics.height)}};
      tracker.track(images, clouds, widths, heights);
      sum += translation_error_mm(to_pose(tracker.getPose()), *f.truth());
    }
    return sum / frames.size();
  };
  const double as_points = mean_error_mm(false), as_depth = mean_error_mm(true);
  INFO("mean translation error: " << as_points << " mm read as points, " << as_depth << " mm read as Z on pinhole rays");
  CHECK(as_points < 0.5);
  CHECK(as_depth > 3.0 * as_points);
}

TEST_CASE("vpMbIcgTracker takes colour and depth from one registered PCL cloud") {
  // A registered cloud sees depth from the colour camera: make one by rendering... the
  // teabox frames have their depth in a separate camera, so build the cloud in the colour
  // camera from the ground-truth-aligned depth by re-projecting each depth pixel.
  const auto& frames = teabox_frames();
  vpMbIcgTracker tracker;
  configure(tracker, {"region", "depth"});
  tracker.loadModel(kTeabox);
  tracker.setCameraParameters(to_camera_parameters(frames[0].colors[0].intrinsics));
  tracker.initFromPose(vpImage<unsigned char>(), to_homogeneous_matrix(*frames[0].truth()));
  for (const Frame& f : frames) {
    const Intrinsics& kc = f.colors[0].intrinsics;
    const Intrinsics& kd = f.depths[0].intrinsics;
    const Pose color_T_depth = f.depths[0].camera_T_reference.inverse();
    auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZRGBA>>(kc.width, kc.height);
    for (int v = 0; v < kc.height; ++v)
      for (int u = 0; u < kc.width; ++u) {
        const cv::Vec3b bgr = f.colors[0].image.at<cv::Vec3b>(v, u);
        auto& p = cloud->points[static_cast<std::size_t>(v) * kc.width + u];
        p.r = bgr[2];
        p.g = bgr[1];
        p.b = bgr[0];
        p.a = 255;
        p.x = p.y = p.z = 0.f;
      }
    for (int v = 0; v < kd.height; ++v)
      for (int u = 0; u < kd.width; ++u) {
        const float z = f.depths[0].depth.at<float>(v, u);
        if (!(z > 0.f)) continue;
        const Eigen::Vector3d X = color_T_depth * kd.back_project<double>(u, v, z);
        const Eigen::Vector2d x = kc.project<double>(X);
        const int cu = static_cast<int>(std::lround(x.x())), cv_ = static_cast<int>(std::lround(x.y()));
        if (cu < 0 || cv_ < 0 || cu >= kc.width || cv_ >= kc.height) continue;
        auto& p = cloud->points[static_cast<std::size_t>(cv_) * kc.width + cu];
        // The registered point of the pixel: on its ray, at the depth that reaches it.
        if (p.z == 0.f || X.z() < p.z)
          p.getVector3fMap() = kc.back_project<float>(static_cast<float>(cu), static_cast<float>(cv_), static_cast<float>(X.z()));
      }
    tracker.track(std::shared_ptr<const pcl::PointCloud<pcl::PointXYZRGBA>>(cloud));
    INFO("frame " << f.index);
    CHECK(translation_error_mm(to_pose(tracker.getPose()), *f.truth()) < 1.0);
  }
}

TEST_CASE("vpMbIcgTracker's residuals, weights and covariance") {
  const auto& frames = teabox_frames();
  vpMbIcgTracker tracker(kRgbdTrackerTypes);
  configure(tracker, {"region", "depth"});
  tracker.loadModel(kTeabox);
  set_cameras(tracker, frames[0]);
  tracker.setCovarianceComputation(true);
  const VispFrame v = to_visp(frames[0]);
  tracker.initFromPose(v.color, to_homogeneous_matrix(*frames[0].truth()));
  CHECK_THROWS_AS(tracker.getCovarianceMatrix(), vpTrackingException);
  tracker.track(v.color, v.depth_raw, 1e-4);

  const vpColVector e = tracker.getError();
  const vpColVector w = tracker.getRobustWeights();
  REQUIRE(e.size() > 100);
  REQUIRE(w.size() == e.size());
  for (unsigned int i = 0; i < w.size(); ++i) REQUIRE((w[i] >= 0.0 && w[i] <= 1.0));
  // At the converged pose residuals are small: sub-pixel contours, sub-millimetre depth.
  std::vector<double> magnitudes;
  for (unsigned int i = 0; i < e.size(); ++i) magnitudes.push_back(std::abs(e[i]));
  std::nth_element(magnitudes.begin(), magnitudes.begin() + magnitudes.size() / 2, magnitudes.end());
  CHECK(magnitudes[magnitudes.size() / 2] < 1.0);

  const vpMatrix C = tracker.getCovarianceMatrix();
  REQUIRE(C.getRows() == 6);
  Eigen::Matrix<double, 6, 6> M;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) M(i, j) = C[i][j];
  CHECK((M - M.transpose()).norm() <= 1e-9 * M.norm());
  CHECK(Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>>(M).eigenvalues().minCoeff() > 0.0);
}

TEST_CASE("vpMbIcgTracker's covariance is about the camera, in ViSP's (v, ω) order") {
  const auto& frames = teabox_frames();
  const VispFrame v = to_visp(frames[1]);
  const auto covariance = [&](const vpHomogeneousMatrix& T, const vpHomogeneousMatrix& cMo) {
    vpMbIcgTracker tracker(kRgbdTrackerTypes);
    configure(tracker, {"depth"});
    tracker.loadModel(kTeabox, false, T);
    set_cameras(tracker, frames[1]);
    tracker.setCovarianceComputation(true);
    tracker.initFromPose(v.color, cMo);
    tracker.track(v.color, v.depth_raw, 1e-4);
    return tracker.getCovarianceMatrix();
  };
  const vpHomogeneousMatrix cMo = to_homogeneous_matrix(*frames[1].truth());
  const vpMatrix a = covariance(vpHomogeneousMatrix(), cMo);

  // Depth measures distance along the optical axis best: of the camera-frame translations,
  // v_z (index 2) is by far the best determined. In the box's frame, or in (ω, v) order,
  // index 2 would be another axis or a rotation.
  CHECK(a[2][2] < 0.1 * a[0][0]);
  CHECK(a[2][2] < 0.1 * a[1][1]);

  // The same physical box with its model expressed in a frame 6 cm away: the camera-frame
  // covariance must not change (model views are placed around the geometry, so both
  // models sample the box alike; the rest is tracking noise).
  const vpHomogeneousMatrix oMn(0.05, -0.02, 0.03, 0.0, 0.0, 0.0);
  const vpMatrix b = covariance(oMn.inverse(), cMo * oMn);
  for (unsigned int i = 0; i < 6; ++i)
    for (unsigned int j = 0; j < 6; ++j) {
      INFO("entry " << i << ", " << j);
      CHECK(b[i][j] == Approx(a[i][j]).margin(0.25 * std::sqrt(a[i][i] * a[j][j])));
    }
}

TEST_CASE("vpMbIcgTracker::testTracking tells a tracked box from a lost one") {
  const auto& frames = teabox_frames();
  vpMbIcgTracker tracker(kRgbdTrackerTypes);
  configure(tracker, {"region", "depth"});
  tracker.loadModel(kTeabox);
  set_cameras(tracker, frames[0]);
  const VispFrame v = to_visp(frames[0]);
  tracker.initFromPose(v.color, to_homogeneous_matrix(*frames[0].truth()));
  tracker.track(v.color, v.depth_raw, 1e-4);
  CHECK_NOTHROW(tracker.testTracking());
  CHECK(tracker.getTrackingQuality() > 0.5);

  // 12 cm to the side the box is not there: the colour statistics and depth disagree.
  // Without recovery the verdict stands as the cues give it.
  tracker.setRecovery(false);
  const vpHomogeneousMatrix aside = vpHomogeneousMatrix(0.12, 0.0, 0.0, 0.0, 0.0, 0.0) * tracker.getPose();
  tracker.setPose(v.color, aside);
  const VispFrame next = to_visp(frames[1]);
  tracker.track(next.color, next.depth_raw, 1e-4);
  CHECK(tracker.getTrackingQuality() < 0.5);
  CHECK_THROWS_AS(tracker.testTracking(), vpTrackingException);

  // With recovery (the default) the same frame finds the box again, verified.
  tracker.setRecovery(true);
  tracker.setPose(v.color, aside);
  tracker.track(next.color, next.depth_raw, 1e-4);
  CHECK_NOTHROW(tracker.testTracking());
  CHECK(tracker.getTrackingQuality() > 0.5);
  // The teabox .cao is a plain box: found at the truth or at a 180-degree twin, whose
  // centre is the same point.
  const vpHomogeneousMatrix found = tracker.getPose(), truth = to_homogeneous_matrix(*frames[1].truth());
  const vpColVector centre{0.0, 0.0, 0.084094, 1.0};  // the middle of the .cao's eight corners
  CHECK((found.getTranslationVector() - aside.getTranslationVector()).frobeniusNorm() > 0.05);
  CHECK((found * centre - truth * centre).frobeniusNorm() < 0.005);
  // Of the twins, the one turned as the pose it was lost at (aside is the truth moved).
  CHECK(rotation_angle_between(to_pose(found).rotation(), to_pose(truth).rotation()) < 5.0 * kPi / 180.0);
}

TEST_CASE("vpMbIcgTracker::initFromDetection finds the teabox; its twins by symmetry are the equivalent poses") {
  const auto& frames = teabox_frames();
  vpMbIcgTracker tracker(kRgbdTrackerTypes);
  configure(tracker, {"region", "depth"});
  tracker.loadModel(kTeabox);
  set_cameras(tracker, frames[0]);
  const VispFrame v = to_visp(frames[0]);
  REQUIRE(tracker.initFromDetection(v.color, v.depth_raw, 1e-4));
  INFO(tracker.getDetectionMessage());
  // The .cao is a plain box of three different sides: its three half turns about its
  // centre give poses no image can tell apart, one of the four is the truth.
  const std::vector<vpHomogeneousMatrix> equivalents = tracker.getDetectionEquivalentPoses();
  REQUIRE(equivalents.size() == 3);
  const vpHomogeneousMatrix truth = to_homogeneous_matrix(*frames[0].truth());
  const vpColVector centre{0.0, 0.0, 0.084094, 1.0};  // the middle of the .cao's eight corners
  std::vector<vpHomogeneousMatrix> poses = equivalents;
  poses.push_back(tracker.getPose());
  int at_truth = 0;
  for (const vpHomogeneousMatrix& pose : poses) {
    CHECK((pose * centre - truth * centre).frobeniusNorm() < 0.005);
    const double turn = rotation_angle_between(to_pose(pose).rotation(), to_pose(tracker.getPose()).rotation());
    if (pose != tracker.getPose()) CHECK(turn == Approx(kPi).margin(0.01));
    if (rotation_angle_between(to_pose(pose).rotation(), to_pose(truth).rotation()) < 5.0 * kPi / 180.0) ++at_truth;
  }
  CHECK(at_truth == 1);
  // Tracking goes on from the detected pose.
  tracker.track(to_visp(frames[1]).color, to_visp(frames[1]).depth_raw, 1e-4);
  CHECK_NOTHROW(tracker.testTracking());
}

TEST_CASE("vpMbIcgTracker::loadModel adds parts to one rigid object") {
  const Frame& frame = teabox_frames().front();
  const vpCameraParameters cam = to_camera_parameters(frame.colors[0].intrinsics);
  const vpHomogeneousMatrix cMo = to_homogeneous_matrix(*frame.truth());
  vpMbIcgTracker tracker;
  tracker.loadModel(kTeabox);
  const std::size_t one = tracker.getModelForDisplay(640, 480, cMo, cam, true).size();
  tracker.loadModel(kTeabox, false, vpHomogeneousMatrix(0.0, 0.0, 0.2, 0.0, 0.0, 0.0));
  CHECK(tracker.getModelForDisplay(640, 480, cMo, cam, true).size() == 2 * one);
  tracker.resetTracker();
  CHECK_THROWS_AS(tracker.getModelForDisplay(640, 480, cMo, cam, true), vpException);
}

namespace {

/// How many times `text` appears on std::cout during `call`.
int printed_during(const std::function<void()>& call, const std::string& text) {
  std::string printed;
  {
    const icgp::StandardStreamCapture out(std::cout);
    call();
    printed = out.text();
  }
  int count = 0;
  for (std::size_t at = printed.find(text); at != std::string::npos; at = printed.find(text, at + 1)) ++count;
  return count;
}

/// The vpException `call` throws.
vpException vp_exception_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const vpException& e) {
    return e;
  }
  FAIL("no vpException was thrown");
  return vpException(-1, "no vpException was thrown");
}

/// The edges of load_any_mesh(path, 1, T) in getModelForDisplay's format, every one whole.
std::vector<std::vector<double>> standalone_edges(const std::string& path, const vpHomogeneousMatrix& T,
                                                  const vpHomogeneousMatrix& cMo, const vpCameraParameters& cam) {
  const ModelEdges edges(load_any_mesh(path, 1.0, to_pose(T)));
  std::vector<std::vector<double>> lines;
  for (const ImageSegment& s : edges.project(to_intrinsics(cam, 640, 480), to_pose(cMo), cv::Mat()))
    lines.push_back({0.0, s.a.y(), s.a.x(), s.b.y(), s.b.x()});
  return lines;
}

void check_same_lines(const std::vector<std::vector<double>>& ours, const std::vector<std::vector<double>>& expected) {
  REQUIRE(ours.size() == expected.size());
  for (std::size_t i = 0; i < ours.size(); ++i)
    for (std::size_t k = 0; k < 5; ++k) CHECK(ours[i][k] == Approx(expected[i][k]).margin(1e-6));
}

}  // namespace

TEST_CASE("vpMbIcgTracker::loadModel reads a .cao once; its mesh and ViSP's faces are the same box") {
  const vpHomogeneousMatrix T(0.02, -0.01, 0.03, 0.1, -0.2, 0.3);
  const vpCameraParameters cam(600, 600, 320, 240);
  const vpHomogeneousMatrix cMo(0.0, 0.0, 0.6, 0.4, -0.3, 0.2);

  // ViSP's parser prints a summary of each .cao file it reads on std::cout, "> 8 points"
  // first for the teabox's 8 points: vpMbGenericTracker reads the file once, and so do we.
  vpMbGenericTracker visp(vpMbGenericTracker::EDGE_TRACKER);
  REQUIRE(printed_during([&] { visp.loadModel(kTeabox, false, T); }, "> 8 points\n") == 1);
  vpMbIcgTracker ours;
  CHECK(printed_during([&] { ours.loadModel(kTeabox, false, T); }, "> 8 points\n") == 1);

  // ViSP's faces are vpMbGenericTracker's: the box's six faces, moved by T.
  REQUIRE(ours.getNbPolygon() == 6);
  REQUIRE(visp.getNbPolygon() == 6);
  std::vector<std::pair<vpImagePoint, vpImagePoint>> face_edges;
  for (unsigned int i = 0; i < 6; ++i) {
    vpMbtPolygon& face = *ours.getPolygon(i);
    REQUIRE(face.getNbPoint() == 4);
    for (unsigned int j = 0; j < 4; ++j) {
      const vpPoint& p = face.getPoint(j);
      const vpPoint& q = visp.getPolygon(i)->getPoint(j);
      CHECK((p.get_oX() == q.get_oX() && p.get_oY() == q.get_oY() && p.get_oZ() == q.get_oZ()));
    }
    std::vector<vpImagePoint> corners;
    for (unsigned int j = 0; j < 4; ++j) {
      vpPoint p = face.getPoint(j);
      p.project(cMo);
      vpImagePoint ip;
      vpMeterPixelConversion::convertPoint(cam, p.get_x(), p.get_y(), ip);
      corners.push_back(ip);
    }
    for (unsigned int j = 0; j < 4; ++j) face_edges.emplace_back(corners[j], corners[(j + 1) % 4]);
  }

  // icgp's mesh is the standalone loader's (the same edges, T applied)...
  const std::vector<std::vector<double>> full = ours.getModelForDisplay(640, 480, cMo, cam, true);
  check_same_lines(full, standalone_edges(kTeabox, T, cMo, cam));
  // ... and its 12 edges are those of ViSP's faces, each shared by two faces.
  CHECK(full.size() == 12);
  const auto joins = [](const std::vector<double>& line, const std::pair<vpImagePoint, vpImagePoint>& edge) {
    const auto near = [](double i, double j, const vpImagePoint& p) {
      return std::abs(i - p.get_i()) < 1e-3 && std::abs(j - p.get_j()) < 1e-3;
    };
    return (near(line[1], line[2], edge.first) && near(line[3], line[4], edge.second)) ||
           (near(line[1], line[2], edge.second) && near(line[3], line[4], edge.first));
  };
  for (const std::vector<double>& line : full)
    CHECK(std::count_if(face_edges.begin(), face_edges.end(), [&](const auto& e) { return joins(line, e); }) == 2);
  for (const auto& edge : face_edges)
    CHECK(std::count_if(full.begin(), full.end(), [&](const auto& line) { return joins(line, edge); }) == 1);
}

TEST_CASE("vpMbIcgTracker meshes cylinders, circles and .wrl files as load_any_mesh does, T included") {
  test::TempDir dir("icgp-vpmbicgtracker");
  // A cylinder along z and a disc standing across its foot: their facets follow the file's
  // frame, wherever T puts them.
  const std::string curved =
      dir.write("curved.cao", "V1\n3\n0 0 0\n0 0 0.1\n0.05 0 0\n0\n0\n0\n1\n0 1 0.03\n1\n0.02 2 0 1\n");
  const std::string wrl = (std::filesystem::path(ICGP_TEST_DATA_DIR) / "realsense-cube" / "models" / "teabox" /
                           "teabox.wrl").string();
  const vpCameraParameters cam(600, 600, 320, 240);
  const vpHomogeneousMatrix cMo(0.0, 0.0, 0.5, 0.4, -0.3, 0.2);
  for (const vpHomogeneousMatrix& T :
       {vpHomogeneousMatrix(), vpHomogeneousMatrix(0.02, -0.01, 0.03, 0.1, -0.2, 0.3),
        vpHomogeneousMatrix(0.0, 0.0, 0.0, 0.0, 1.5707963267948966, 0.0)}) {
    for (const std::string& model : {curved, wrl}) {
      CAPTURE(model, T);
      vpMbIcgTracker tracker;
      tracker.loadModel(model, false, T);
      check_same_lines(tracker.getModelForDisplay(640, 480, cMo, cam, true), standalone_edges(model, T, cMo, cam));
    }
  }
}

TEST_CASE("vpMbIcgTracker: a model file that fails to load leaves the object and ViSP's faces as they were") {
  test::TempDir dir("icgp-vpmbicgtracker");
  // A face crossing itself: ViSP reads it, icgp cannot triangulate it.
  const std::string crossed =
      dir.write("crossed.cao",
                "V1\n6\n0.03 0.04 0\n0 0.03 0\n0.01 0.03 0\n0.03 0.01 0\n0.02 0.04 0\n0.02 0 0\n0\n0\n1\n"
                "6 0 1 2 3 4 5\n0\n0\n");
  const vpCameraParameters cam(600, 600, 320, 240);
  const vpHomogeneousMatrix cMo(0.0, 0.0, 0.6, 0.4, -0.3, 0.2);
  vpMbIcgTracker tracker(std::vector<int>{vpMbIcgTracker::EDGE_TRACKER, vpMbIcgTracker::DEPTH_DENSE_TRACKER});
  tracker.loadModel(kTeabox);
  const auto lines = tracker.getModelForDisplay(640, 480, cMo, cam, true);
  const auto faces = tracker.getPolygonFaces(false, false, false);

  const auto unchanged = [&] {
    CHECK(tracker.getNbPolygon() == 6);
    CHECK(tracker.getModelForDisplay(640, 480, cMo, cam, true) == lines);
    const auto now = tracker.getPolygonFaces(false, false, false);
    REQUIRE(now.second.size() == faces.second.size());
    for (std::size_t i = 0; i < faces.second.size(); ++i) {
      REQUIRE(now.second[i].size() == faces.second[i].size());
      for (std::size_t j = 0; j < faces.second[i].size(); ++j)
        CHECK(now.second[i][j].get_oX() == faces.second[i][j].get_oX());
    }
  };
  SECTION("the file itself") {
    const vpException e = vp_exception_of([&] { tracker.loadModel(crossed); });
    CHECK(e.getCode() == vpException::badValue);
    CHECK_THAT(e.getStringMessage(), Catch::Contains(crossed) && Catch::Contains("face #1"));
    unchanged();
  }
  SECTION("another camera's file, read after the reference camera's") {
    const vpException e = vp_exception_of([&] { tracker.loadModel(kTeabox, crossed); });
    CHECK(e.getCode() == vpException::badValue);
    CHECK_THAT(e.getStringMessage(), Catch::Contains(crossed));
    unchanged();
  }
}
