// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker's state, shared by the files that implement it.
#pragma once

#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>
#include <visp3/core/vpTrackingException.h>

#include "icgp/detection/recovery.h"
#include "icgp/render/model_edges.h"
#include "icgp/render/scene_renderer.h"
#include "icgp/tracker/tracker_builder.h"
#include "icgp/visp/vpMbIcgTracker.h"

#include "camera_rig.h"
#include "frame_assembly.h"

namespace icgp {
class CaoMeshBuilder;
}  // namespace icgp

struct vpMbIcgTracker::Impl {
  static constexpr const char* kBody = "object";

  explicit Impl(icgp::CameraRig rig) : rig(std::move(rig)) {}

  /// icgp's defaults with the flow and edge cues too, standing in for depth: a program that
  /// asks for KLT_TRACKER or EDGE_TRACKER on a colour camera alone expects corners tracked
  /// from frame to frame and the object's creases followed, as ViSP's KLT and moving edges
  /// do. In frames with depth, ICG+'s region, depth and texture hold the pose as well
  /// without them, in a third less time (icgp bench --visp-types). YAML files are read
  /// over them.
  static icgp::TrackerConfig default_config() {
    icgp::TrackerConfig config;
    config.modalities.push_back(icgp::cue::kFlow);
    config.modalities.push_back(icgp::cue::kEdge);
    config.depth_stand_ins = {icgp::cue::kFlow, icgp::cue::kEdge};
    return config;
  }

  icgp::CameraRig rig;
  icgp::TrackerConfig config = default_config();
  icgp::Mesh mesh;
  bool has_visp_model_part = false;  ///< ViSP's projection-error model exists (.cao / .wrl)
  /// Meshes what ViSP's parser calls the init* hooks with, while loadModel parses a .cao / .wrl.
  icgp::CaoMeshBuilder* cao_builder = nullptr;
  std::unique_ptr<icgp::Tracker> tracker;  ///< for the current mesh, config and rig, built by init()
  /// Detection and recovery of `tracker`'s bodies, built with it.
  std::unique_ptr<icgp::Recovery> recovery;
  std::string detection_message = "no detection yet";
  std::vector<vpHomogeneousMatrix> detection_equivalents;  ///< of the last detection, cMo
  std::vector<icgp::CameraCues> cues;      ///< which cues read which camera, as `tracker` was built
  bool start_pending = false;

  icgp::FrameAssembler assembler;
  /// Channels of each camera's last image (1 grey, 3 colour): the colour statistics of the
  /// region cue are of one kind, so a switch restarts the cues at the current pose.
  std::map<std::string, int> image_channels;
  double quality = 0.0;
  std::optional<icgp::Mat66> hessian;  ///< of the last update's data terms
  /// The last frame's residuals and weights (m_error, m_w), kept for their capacity: every
  /// frame gathers several hundred.
  std::vector<double> residuals, weights;
  /// Further bodies (config.bodies): poses (cMb) and joint values set by the program, applied
  /// when the tracker is (re)initialised, and each body's result on the last frame.
  std::map<std::string, icgp::Pose> body_poses;
  std::map<std::string, std::vector<double>> joint_values;
  std::map<std::string, icgp::BodyResult> body_results;

  std::set<std::string> reported_without_effect;  ///< ViSP settings already reported once
  /// Cameras whose depth had no valid measurement on the last frames, already reported.
  std::set<std::string> depth_without_measurement;
  /// ViSP's settings of its own cues, kept for their getters.
  struct VispSettings {
    std::map<std::string, vpMe> moving_edges;
    std::map<std::string, vpKltOpencv> klts;
    std::map<std::string, unsigned int> klt_mask_borders, clipping_flags;
    double klt_threshold_acceptation = 0.5;  ///< ViSP's default
    double good_moving_edges_ratio = 0.4;  ///< ViSP's default
  } visp;
  std::list<vpMbtDistanceCircle*> no_circles;
  std::list<vpMbtDistanceKltCylinder*> no_klt_cylinders;
  std::list<vpMbtDistanceKltPoints*> no_klt_points;

  std::unique_ptr<icgp::ModelEdges> edges;  ///< for display, made on first use
  /// The tracker's renderer, which the display's hidden-line removal uses too.
  std::shared_ptr<icgp::SceneRenderer> renderer = std::make_shared<icgp::SceneRenderer>();

  /// The cues of one of the rig's cameras.
  const icgp::CameraCues& cues_of(const std::string& camera) const {
    for (const icgp::CameraCues& c : cues)
      if (c.camera == camera) return c;
    // Every camera of the rig has an entry once the tracker is built.
    throw vpException(vpException::fatalError, "vpMbIcgTracker: camera '" + camera + "' has no cues");
  }

  void require_initialised(const std::string& call) const {
    if (!tracker)
      throw vpTrackingException(vpTrackingException::initializationError,
                                "vpMbIcgTracker::" + call +
                                    ": not initialised; call loadModel() and initFromPose() first");
  }

  /// A ViSP setting this tracker accepts but cannot honour: said once per tracker.
  void report_without_effect(const std::string& call, const std::string& why) {
    if (reported_without_effect.insert(call).second)
      std::cerr << "vpMbIcgTracker::" << call << ": no effect (" << why << ")\n";
  }

  /// Gives the tracker the poses and joint values the program set for its further bodies.
  void apply_body_settings() {
    for (const auto& [name, pose] : body_poses) tracker->body(name).reference_T_body = pose;
    for (const auto& [name, values] : joint_values) tracker->set_joint_values(name, values);
  }

  /// The cues' tracker must be rebuilt (model, configuration or cameras' types changed).
  void tracker_changed() {
    recovery.reset();
    tracker.reset();
  }
  void model_changed() {
    recovery.reset();
    tracker.reset();
    edges.reset();
    renderer = std::make_shared<icgp::SceneRenderer>();  // the body's mesh is uploaded once
  }
};

namespace icgp::visp_detail {

/// Ends the frame's depth reads when it goes out of scope: the depth readers refer to the
/// caller's clouds, which are only known valid during the call that gave them.
struct EndDepthReads {
  FrameAssembler& assembler;
  ~EndDepthReads() { assembler.end_depth_reads(); }
};

/// One camera's depth in a frame: its size (0 x 0: none this frame) and where a pixel's
/// depth, or its 3D point, comes from.
struct DepthInput {
  std::string camera;
  unsigned int width = 0, height = 0;
  FrameAssembler::DepthReader depth;   ///< Z per pixel, or
  FrameAssembler::PointReader points;  ///< the point per pixel (organised clouds)
  FrameAssembler::ManyPointsReader read_many;  ///< for sources that read scattered pixels faster together
};

/// A point of a cloud as a measurement: one with a coordinate that is NaN or infinite is
/// none (Z 0), whatever its other coordinates say.
inline Eigen::Vector3f measured_point(const Eigen::Vector3f& P) {
  return P.allFinite() ? P : Eigen::Vector3f::Zero();
}

/// Whether `predicate(row, col)` holds for a pixel of a 9 x 9 grid over a width x height
/// image, corners and edges included; stops at the first that does. read_cloud and
/// has_measurement both probe this grid, so the second finds its points in the cache.
template <typename Predicate>
bool any_grid_pixel(unsigned int width, unsigned int height, Predicate predicate) {
  constexpr int kGrid = 9;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      const int row = static_cast<int>((height - 1) * i / (kGrid - 1));
      const int col = static_cast<int>((width - 1) * j / (kGrid - 1));
      if (predicate(row, col)) return true;
    }
  return false;
}

/// An organised cloud as a camera's depth: Z alone when its points lie on the pinhole
/// rays of their pixels (a cloud de-projected without distortion, or made from a depth
/// image), so that the depth cue's search may prune by rays; its points otherwise (a real
/// sensor's cloud de-projected with its distortion). The grid of any_grid_pixel, corners
/// and edges included where distortion is largest, decides; 0.05 px is far below what lens
/// distortion moves an edge pixel. Points with a non-finite coordinate are no measurement.
/// `cloud_point(row, col)` is the cloud's point of a pixel: a callable, not a std::function,
/// so that each pixel the cues read goes through one std::function, not a chain of them.
/// `depth` is not empty (require_depth_size).
template <typename CloudPoint>
void read_cloud(DepthInput& depth, CloudPoint cloud_point, const vpCameraParameters& camera) {
  const auto point_at = [cloud_point](int row, int col) { return measured_point(cloud_point(row, col)); };
  const bool off_ray = any_grid_pixel(depth.width, depth.height, [&](int row, int col) {
    const Eigen::Vector3f P = point_at(row, col);
    if (!(P.z() > 0.f)) return false;
    const double u = camera.get_px() * P.x() / P.z() + camera.get_u0();
    const double v = camera.get_py() * P.y() / P.z() + camera.get_v0();
    return !(std::abs(u - col) <= 0.05 && std::abs(v - row) <= 0.05);
  });
  if (off_ray)
    depth.points = point_at;
  else
    depth.depth = [point_at](int row, int col) { return point_at(row, col).z(); };
}

/// Every camera named in the maps is one of the rig's (checked before anything changes).
template <typename... Maps>
void require_known_cameras(const CameraRig& rig, const std::string& call, const Maps&... maps) {
  (..., [&] {
    for (const auto& entry : maps) rig.at(entry.first, call);
  }());
}

/// Refuses a depth size that is neither 0 x 0 (ViSP's "no depth this frame") nor within
/// [1, kMaxImageSide] on both sides, before anything is read or allocated for it.
inline void require_depth_size(const std::string& call, const DepthInput& depth) {
  if (depth.width == 0 && depth.height == 0) return;
  require_image_size(
      call, [&depth] { return "the depth of camera '" + depth.camera + "' (0 x 0: none this frame)"; }, depth.width,
      depth.height);
}

/// Whether any pixel of `depth` holds a measurement (Z > 0 and finite). The grid that
/// read_cloud has just read first, which finds an object that fills a fair part of the image
/// (a rendered depth measures nothing but the object); then every 8th pixel of every 8th
/// row, which finds one at once in a sensor's frame; only a depth without any is read whole.
inline bool has_measurement(const DepthInput& depth) {
  const auto measured = [&depth](int row, int col) {
    const float z = depth.depth ? depth.depth(row, col) : depth.points(row, col).z();
    return z > 0.f && std::isfinite(z);
  };
  if (any_grid_pixel(depth.width, depth.height, measured)) return true;
  for (const int step : {8, 1})
    for (int row = 0; row < static_cast<int>(depth.height); row += step)
      for (int col = 0; col < static_cast<int>(depth.width); col += step)
        if (measured(row, col)) return true;
  return false;
}

/// Throws vpException::ioError naming `what` and `path` when the file does not exist, is no
/// regular file or cannot be read: before ViSP's parsers or assimp see the path.
void require_file(const std::string& path, const std::string& what);

/// What a failure of icgp's core or of a library under it means in a call (see guarded).
enum class Failure {
  kError,     ///< an error of the call: vpException::fatalError
  kTracking,  ///< the frame could not be tracked: vpTrackingException::fatalError
};

/// Rethrows the exception being handled as the vpException it means, its message kept and
/// prefixed with "vpMbIcgTracker::<call>: ". Call it only from a catch block.
/// vpException (and subclasses) pass unchanged; std::invalid_argument, std::out_of_range and
/// std::domain_error are the caller's values (badValue); std::bad_alloc, std::length_error
/// and OpenCV's out-of-memory error are memoryAllocationError; anything else, yaml-cpp's and
/// OpenCV's other errors included, is `failure`.
[[noreturn]] void rethrow_as_visp_exception(const std::string& call, Failure failure);

/// Runs `body` with every exception it throws made a ViSP one (rethrow_as_visp_exception):
/// ViSP programs catch vpException, and nothing else may leave vpMbIcgTracker. Every public
/// method that reaches icgp's core, OpenCV, yaml-cpp or an allocation sized by its
/// arguments runs through it; nested calls keep the innermost call's name.
template <typename Body>
auto guarded(const std::string& call, Body&& body, Failure failure = Failure::kError) -> decltype(body()) {
  try {
    return body();
  } catch (...) {
    rethrow_as_visp_exception(call, failure);
  }
}

}  // namespace icgp::visp_detail
