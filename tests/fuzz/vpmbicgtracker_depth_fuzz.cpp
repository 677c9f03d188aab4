// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker's depth entry points on fuzzed clouds and depth images: width, height,
// cloud size (also not width x height), NaN, inf, zero, negative and huge coordinates.
// Two trackers are set up once on the teabox (very coarse models, cached in the build tree): a
// rig of a colour and a depth camera, and one RGB-D camera for registered clouds, all 80 x 60
// pixels; each input resets their pose and tracks one frame. Input layout (missing bytes read as 0):
//   byte 0: entry point (vpColVector clouds / raw depth / PCL XYZ / PCL XYZRGBA),
//   bytes 1, 2: cloud width and height (0 .. 255; 80 x 60 matches the camera),
//   byte 3: cloud size minus width x height (signed), for the vpColVector entry point,
//   byte 4: the raw depth scale, from a table of good and bad values,
//   the rest: one code byte per point, cycled over the cloud (see point_from_code).
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <vector>

#include "fuzz_support.h"
#include "icgp/eval/sequence.h"
#include "icgp/visp/conversions.h"
#include "icgp/visp/rgbd_tracking_loop.h"
#include "icgp/visp/vpMbIcgTracker.h"

namespace {

constexpr unsigned kWidth = 80, kHeight = 60;
constexpr double kFocal = 75.0;  // teabox-blender's 600 px depth camera at 1/8 of its size
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// Reads the input front to back; past its end every byte is 0.
class InputBytes {
 public:
  InputBytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t next() { return position_ < size_ ? data_[position_++] : 0; }
  /// The unread rest, cycled: byte i of an endless stream (0 when nothing is left).
  std::uint8_t rest_cycled(std::size_t i) const {
    const std::size_t left = size_ - std::min(position_, size_);
    return left == 0 ? 0 : data_[position_ + i % left];
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t position_ = 0;
};

/// The point of pixel (u, v) for a code byte: codes 0..15 put a special value (NaN, inf,
/// -inf, 0, negative, huge, tiny, -0) into Z (0..7) or X (8..15), the others lie on the
/// pixel's ray at 0.4 .. 0.8 m, about where the teabox is.
Eigen::Vector3d point_from_code(std::uint8_t code, unsigned u, unsigned v) {
  static const double kSpecial[] = {kNaN, kInf, -kInf, 0.0, -0.5, 1e30, 1e-30, -0.0};
  const double z = code < 16 ? 0.6 : 0.4 + (code - 16) * (0.4 / 239.0);
  Eigen::Vector3d p((u - (kWidth - 1) / 2.0) * z / kFocal, (v - (kHeight - 1) / 2.0) * z / kFocal, z);
  if (code < 8) p.z() = kSpecial[code];
  else if (code < 16) p.x() = kSpecial[code - 8];
  return p;
}

/// vpMbIcgTracker on the teabox with very coarse models (cached in the build tree), its
/// cameras 80 x 60 pixels, ready to track from the first ground-truth pose.
vpMbIcgTracker& teabox_tracker(vpMbIcgTracker& tracker) {
  const std::string teabox = ICGP_TEST_DATA_DIR "/teabox-blender";
  icgp::TrackerConfig config = tracker.getTrackerConfig();
  // Coarser still than the tests' models (42 views of 256 px): made in seconds under ASan,
  // and the fuzzed inputs, not the models, are what this target is about.
  for (icgp::ViewpointModelParams* model : {&config.region_model, &config.depth_model}) {
    model->n_divides = 1;
    model->image_size = 256;
  }
  config.cache_dir = ICGP_FUZZ_CACHE_DIR;
  config.modalities = {icgp::cue::kRegion, icgp::cue::kDepth};
  tracker.setTrackerConfig(config);
  tracker.loadModel(teabox + "/teabox.cao");
  const vpCameraParameters camera(kFocal, kFocal, (kWidth - 1) / 2.0, (kHeight - 1) / 2.0);
  if (tracker.getCameraNames().size() == 2) {
    tracker.setCameraParameters(camera, camera);
    tracker.setCameraTransformationMatrix(
        "Camera2", icgp::to_homogeneous_matrix(icgp::read_pose_matrix_file(teabox + "/depth_M_color.txt")));
  } else {
    tracker.setCameraParameters(camera);
  }
  return tracker;
}

class TrackerFixture {
 public:
  TrackerFixture()
      : rig_(icgp::kRgbdTrackerTypes),
        rgbd_camera_(std::vector<int>{vpMbGenericTracker::EDGE_TRACKER | vpMbGenericTracker::DEPTH_DENSE_TRACKER}) {
    cMo_ = icgp::to_homogeneous_matrix(
        icgp::read_pose_matrix_file(ICGP_TEST_DATA_DIR "/teabox-blender/camera_poses/Camera_001.txt"));
    color_.resize(kHeight, kWidth, vpRGBa(90, 60, 30));
    grey_.resize(kHeight, kWidth, 128);
    // One good frame each, outside the fuzzed calls: a set-up failure (no OpenGL to make the
    // models, say) must stop the fuzzer, not turn every input into a "clean refusal".
    const vpImage<uint16_t> flat(kHeight, kWidth, 600);
    for (vpMbIcgTracker* tracker : {&teabox_tracker(rig_), &teabox_tracker(rgbd_camera_)}) {
      // A fuzzed frame that loses the object runs the detector (recovery is on by default):
      // it is built here, once, not inside an input's time.
      tracker->initFromDetection(color_, flat, 1e-3);
      tracker->initFromPose(color_, cMo_);
      tracker->track(color_, flat, 1e-3);
    }
  }

  void track_one(InputBytes& input) {
    const int entry = input.next() % 4;
    const unsigned width = input.next(), height = input.next();
    const int size_delta = static_cast<std::int8_t>(input.next());
    static const double kScales[] = {1e-3, 1e-4, 0.0, -1e-3, kNaN, kInf, 1e30, 1e-300};
    const double depth_scale = kScales[input.next() % 8];
    // Every input starts from the same state.
    rig_.initFromPose(color_, cMo_);
    rgbd_camera_.initFromPose(color_, cMo_);
    switch (entry) {
      case 0: track_vector_cloud(input, width, height, size_delta); break;
      case 1: track_raw_depth(input, width, height, depth_scale); break;
      case 2: track_pcl_xyz(input, width, height); break;
      default: track_pcl_xyzrgba(input, width, height); break;
    }
  }

 private:
  void track_vector_cloud(const InputBytes& input, unsigned width, unsigned height, int size_delta) {
    const long size = std::max(0L, static_cast<long>(width) * height + size_delta);
    std::vector<vpColVector> cloud(static_cast<std::size_t>(size), vpColVector(3, 0.0));
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      const unsigned u = width ? static_cast<unsigned>(i % width) : 0, v = width ? static_cast<unsigned>(i / width) : 0;
      const Eigen::Vector3d p = point_from_code(input.rest_cycled(i), u, v);
      for (unsigned k = 0; k < 3; ++k) cloud[i][k] = p[k];
    }
    std::map<std::string, const vpImage<vpRGBa>*> images{{"Camera1", &color_}};
    std::map<std::string, const std::vector<vpColVector>*> clouds{{"Camera2", &cloud}};
    std::map<std::string, unsigned int> widths{{"Camera2", width}}, heights{{"Camera2", height}};
    rig_.track(images, clouds, widths, heights);
  }

  void track_raw_depth(const InputBytes& input, unsigned width, unsigned height, double depth_scale) {
    vpImage<uint16_t> depth(height, width);
    for (unsigned i = 0; i < depth.getSize(); ++i)
      depth.bitmap[i] = static_cast<uint16_t>(input.rest_cycled(2 * i) | input.rest_cycled(2 * i + 1) << 8);
    rig_.track(grey_, depth, depth_scale);
  }

  void track_pcl_xyz(const InputBytes& input, unsigned width, unsigned height) {
    auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>(width, height);
    for (std::size_t i = 0; i < cloud->size(); ++i)
      (*cloud)[i].getVector3fMap() =
          point_from_code(input.rest_cycled(i), static_cast<unsigned>(i % width), static_cast<unsigned>(i / width))
              .cast<float>();
    std::map<std::string, const vpImage<vpRGBa>*> images{{"Camera1", &color_}};
    std::map<std::string, std::shared_ptr<const pcl::PointCloud<pcl::PointXYZ>>> clouds{{"Camera2", cloud}};
    rig_.track(images, clouds);
  }

  /// A registered cloud is one camera's colour and depth: the one-camera RGB-D tracker.
  void track_pcl_xyzrgba(const InputBytes& input, unsigned width, unsigned height) {
    auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZRGBA>>(width, height);
    for (std::size_t i = 0; i < cloud->size(); ++i) {
      const std::uint8_t code = input.rest_cycled(i);
      (*cloud)[i].getVector3fMap() =
          point_from_code(code, static_cast<unsigned>(i % width), static_cast<unsigned>(i / width)).cast<float>();
      (*cloud)[i].r = (*cloud)[i].g = (*cloud)[i].b = code;
    }
    rgbd_camera_.track(std::shared_ptr<const pcl::PointCloud<pcl::PointXYZRGBA>>(cloud));
  }

  vpMbIcgTracker rig_;          ///< colour camera "Camera1" and depth camera "Camera2"
  vpMbIcgTracker rgbd_camera_;  ///< one camera with colour and depth
  vpHomogeneousMatrix cMo_;
  vpImage<vpRGBa> color_;
  vpImage<unsigned char> grey_;
};

}  // namespace

namespace {
std::unique_ptr<TrackerFixture> fixture;
}  // namespace

/// The set-up, models generated on the first run (seconds, more under ASan), happens here,
/// before libFuzzer's per-input timeout starts counting.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  fixture = std::make_unique<TrackerFixture>();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  InputBytes input(data, size);
  icgp::fuzz::refusing_cleanly<vpException>([&] { fixture->track_one(input); });
  return 0;
}
