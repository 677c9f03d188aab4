// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/servo/rgbd_simulator.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <visp3/core/vpImageConvert.h>

#include "icgp/base/pose.h"
#include "icgp/render/egl_context.h"
#include "icgp/render/scene_props.h"
#include "icgp/render/sensor_effects.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/servo/scene_backend.h"
#include "icgp/servo/true_object.h"
#include "icgp/visp/conversions.h"
#include "camera_response.h"

namespace icgp::servo {
namespace {

/// The passing occluder's flat grey.
const Eigen::Vector3f kOccluderColor(0.55f, 0.5f, 0.45f);

/// Where each pixel of an image through a lens of radial distortion k1 (x_d = x (1 + k1 r²))
/// looks in the pinhole image of the same intrinsics: the maps of cv::remap. The
/// undistorted point is found by fixed-point iteration; a pixel where the lens model folds
/// over (1 + k1 r² near 0, far out in a wide image) maps outside the image, to black.
std::pair<cv::Mat, cv::Mat> lens_maps(const Intrinsics& k, double k1) {
  cv::Mat map_u(k.height, k.width, CV_32F), map_v(k.height, k.width, CV_32F);
  for (int row = 0; row < k.height; ++row)
    for (int col = 0; col < k.width; ++col) {
      const double xd = (col - k.pu) / k.fu, yd = (row - k.pv) / k.fv;
      double x = xd, y = yd;
      bool folds = false;
      for (int i = 0; i < 50 && !folds; ++i) {
        const double factor = 1.0 + k1 * (x * x + y * y);
        folds = factor < 0.25;
        x = xd / factor;
        y = yd / factor;
      }
      map_u.at<float>(row, col) = folds ? -1.f : static_cast<float>(k.fu * x + k.pu);
      map_v.at<float>(row, col) = folds ? -1.f : static_cast<float>(k.fv * y + k.pv);
    }
  return {map_u, map_v};
}

}  // namespace

struct RgbdSimulator::Impl {
  Scenario scenario;  ///< with the true calibration: what the images are made with
  TrueCalibration truth;
  CameraSpec nominal;  ///< the calibration the sensor reports
  /// The colour lens's distortion as cv::remap maps; empty without. The image through the
  /// lens is made in `through_lens`, kept from frame to frame.
  cv::Mat lens_map_u, lens_map_v, through_lens;
  cv::Mat vignetting;  ///< vignetting_gains of the colour lens; empty without
  AutoExposure exposure;
  std::unique_ptr<SceneBackend> scene;
  SceneBackend::BodyHandle object{}, occluder{}, gripper{};  ///< occluder, gripper: when the scenario has one
  vpHomogeneousMatrix world_T_camera_start, world_T_object_start;
  SensorNoiseDraws noise;  ///< frame drops, colour and depth noise, in that order per capture
  RgbdCapture capture;
  bool has_capture = false;

  Impl(const Scenario& s, const TrueCalibration& truth, const vpHomogeneousMatrix& wMc, const vpHomogeneousMatrix& wMo,
       std::uint64_t seed)
      : scenario(s),
        truth(truth),
        nominal(s.camera),
        exposure(s.camera.auto_exposure),
        world_T_camera_start(wMc),
        world_T_object_start(wMo),
        noise(seed) {
    scenario.camera.color = truth.color;
    scenario.camera.depth = truth.depth;
    scenario.camera.depth_T_color = truth.depth_T_color;
    scene = make_scene_backend(scenario, seed);
    if (truth.color_k1 != 0.0) std::tie(lens_map_u, lens_map_v) = lens_maps(truth.color, truth.color_k1);
    if (s.camera.vignetting > 0.0) vignetting = vignetting_gains(truth.color, s.camera.vignetting);
  }

  void add_background(std::uint64_t seed) {
    const BackgroundSpec& b = scenario.background;
    if (!b.enabled) return;
    cv::Mat texture;
    if (b.texture.empty()) {
      texture = procedural_clutter_texture(seed);
    } else {
      texture = cv::imread(b.texture, cv::IMREAD_COLOR);
      if (texture.empty()) throw std::runtime_error(b.texture + ": cannot read the background image");
    }
    // Perpendicular to the initial optical axis, `distance` behind the object, facing the
    // camera, and wide enough to fill the view from twice as far.
    const vpHomogeneousMatrix cMo = world_T_camera_start.inverse() * world_T_object_start;
    const double depth = cMo[2][3] + b.distance;
    const Intrinsics& k = scenario.camera.color;
    const double half_extent = 2.0 * depth * std::max(k.width / k.fu, k.height / k.fv) + 0.2;
    const vpHomogeneousMatrix c_M_plane(vpTranslationVector(cMo[0][3], cMo[1][3], depth),
                                        vpRotationMatrix(vpThetaUVector(kPi, 0, 0)));
    const SceneBackend::BodyHandle plane = scene->add_backdrop(tiled_plane(texture, half_extent, 0.3), 2);
    scene->set_body_pose(plane, to_pose(world_T_camera_start * c_M_plane));
  }

  void place_occluder(double time) {
    if (!scenario.occluder) return;
    const OccluderSpec& o = *scenario.occluder;
    const bool present = time >= o.start;
    scene->set_body_visible(occluder, present);
    if (!present) return;
    const Eigen::Vector3d p = o.start_position_in_camera + (time - o.start) * o.velocity_in_camera;
    scene->set_body_pose(occluder, to_pose(world_T_camera_start * vpHomogeneousMatrix(p.x(), p.y(), p.z(), 0, 0, 0)));
  }

  /// Depth as a real sensor gives it: missing at grazing angles, at discontinuities and at
  /// random, and noisy with sigma growing as Z^2.
  cv::Mat render_depth(const vpHomogeneousMatrix& wMc) {
    const NoiseSpec& n = scenario.camera.noise;
    const Intrinsics& k = scenario.camera.depth;
    const Pose depth_T_world = scenario.camera.depth_T_color * to_pose(wMc.inverse());
    cv::Mat depth = sensor_depth(scene->render_geometry(k, depth_T_world, n.grazing_angle_deg < 90.0), k, n);
    noise.add_depth_noise(depth, n);
    return depth;
  }

  void store_depth(const cv::Mat& depth) {
    RgbdCapture& c = capture;
    c.depth_raw.resize(static_cast<unsigned int>(depth.rows), static_cast<unsigned int>(depth.cols));
    cv::Mat raw(depth.rows, depth.cols, CV_16UC1, c.depth_raw.bitmap);
    // Out of the 16-bit range (beyond 6.5 m at 0.1 mm) is "no measurement", as on a sensor.
    cv::Mat units = depth / c.depth_scale;
    units.setTo(0.f, units > 65535.f);
    units.convertTo(raw, CV_16UC1);
  }
};

RgbdSimulator::RgbdSimulator(const Scenario& scenario, const vpHomogeneousMatrix& world_T_camera,
                             const vpHomogeneousMatrix& world_T_object, std::uint64_t seed)
    : RgbdSimulator(scenario, nominal_calibration(scenario), world_T_camera, world_T_object, seed) {}

RgbdSimulator::RgbdSimulator(const Scenario& scenario, const TrueCalibration& truth,
                             const vpHomogeneousMatrix& world_T_camera, const vpHomogeneousMatrix& world_T_object,
                             std::uint64_t seed)
    // Whole frames render faster on llvmpipe's raster threads; the choice must come before
    // the process's first render (a tracker made earlier has chosen for the process).
    : impl_((choose_software_raster_threads(SoftwareRasterThreads::kPerCore),
             std::make_unique<Impl>(scenario, truth, world_T_camera, world_T_object, seed))) {
  Impl& d = *impl_;
  d.object = d.scene->add_body(true_object_mesh(scenario.object, seed), 1);
  d.add_background(seed);
  if (scenario.occluder) d.occluder = d.scene->add_body(box_mesh(scenario.occluder->size, kOccluderColor), 3);
  if (scenario.grasp) d.gripper = d.scene->add_body(load_any_mesh(scenario.grasp->gripper_model), 4);
}

RgbdSimulator::~RgbdSimulator() = default;

vpHomogeneousMatrix RgbdSimulator::world_T_object(double time) const {
  const ObjectSpec& o = impl_->scenario.object;
  const double moving = std::clamp(time - o.motion_start, 0.0, o.motion_duration);
  const Eigen::Vector3d shift = moving * o.linear_velocity;
  const vpHomogeneousMatrix moved = vpHomogeneousMatrix(shift.x(), shift.y(), shift.z(), 0, 0, 0) * impl_->world_T_object_start;
  if (o.removed_for <= 0.0 || time < o.removed_at) return moved;
  // Out of the scene: a kilometre away, beyond every view and depth range.
  if (time < o.removed_at + o.removed_for) return vpHomogeneousMatrix(0, 0, 1000.0, 0, 0, 0) * moved;
  return moved * to_homogeneous_matrix(o.put_back);
}

bool RgbdSimulator::object_present(double time) const {
  const ObjectSpec& o = impl_->scenario.object;
  return o.removed_for <= 0.0 || time < o.removed_at || time >= o.removed_at + o.removed_for;
}

RgbdCapture& RgbdSimulator::capture(double time, const vpHomogeneousMatrix& wMc, const vpHomogeneousMatrix& previous_wMc,
                                    const std::optional<vpHomogeneousMatrix>& held_object,
                                    const std::optional<vpHomogeneousMatrix>& gripper) {
  Impl& d = *impl_;
  RgbdCapture& c = d.capture;
  if (d.scenario.grasp.has_value() != gripper.has_value())
    throw std::invalid_argument(d.scenario.grasp ? "RgbdSimulator::capture: a grasp scenario needs the gripper's pose"
                                                 : "RgbdSimulator::capture: a gripper's pose, but the scenario has none");
  const vpHomogeneousMatrix wMo = held_object ? *held_object : world_T_object(time);
  c.time = time;
  c.cMo_true = wMc.inverse() * wMo;
  c.cMg_true = gripper ? std::optional<vpHomogeneousMatrix>(wMc.inverse() * *gripper) : std::nullopt;
  c.dropped = d.has_capture && d.noise.uniform() < d.scenario.camera.noise.frame_drop;
  if (c.dropped) return c;  // the tracker gets nothing new: the images stay the last ones

  d.scene->set_body_pose(d.object, to_pose(wMo));
  if (gripper) d.scene->set_body_pose(d.gripper, to_pose(*gripper));
  d.place_occluder(time);
  d.scene->set_light(light_at(d.scenario.lighting, time, to_pose(d.world_T_camera_start).rotation()));
  cv::Mat color = d.scene->render_color(d.scenario.camera.color, wMc, previous_wMc, d.scenario.camera.noise.motion_blur);
  // Light through the lens, then the sensor's exposure of it.
  if (!d.vignetting.empty()) scale_linear_light(color, d.vignetting, 1.0);
  d.exposure.expose(color, time);
  if (!d.lens_map_u.empty()) {
    // The lens bends the image before the sensor's noise; what it brings in from beyond
    // the pinhole's field of view is black.
    cv::remap(color, d.through_lens, d.lens_map_u, d.lens_map_v, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
    color = d.through_lens;
  }
  d.noise.add_color_noise(color, d.scenario.camera.noise.color_sigma);
  to_vp_image(color, c.color);
  vpImageConvert::convert(c.color, c.grey);
  d.store_depth(d.render_depth(wMc));
  d.has_capture = true;
  return c;
}

const TrueCalibration& RgbdSimulator::true_calibration() const { return impl_->truth; }

vpCameraParameters RgbdSimulator::color_camera() const { return to_camera_parameters(impl_->nominal.color); }
vpCameraParameters RgbdSimulator::depth_camera() const { return to_camera_parameters(impl_->nominal.depth); }
vpHomogeneousMatrix RgbdSimulator::depth_M_color() const { return to_homogeneous_matrix(impl_->nominal.depth_T_color); }

}  // namespace icgp::servo
