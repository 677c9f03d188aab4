// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"
#include "icgp/base/mesh.h"
#include "icgp/geometry/joint.h"
#include "icgp/render/sensor_effects.h"

namespace icgp {

/// How a synthetic camera moves: it circles a target point on the +Z side of the world
/// (where the background plane faces), looking roughly at the target, with distance,
/// viewing direction, roll and the looked-at point each varying as a smooth random signal.
struct OrbitOptions {
  Eigen::Vector3d target = Eigen::Vector3d::Zero();  ///< world point circled and looked at
  double distance = 0.5;                             ///< mean camera-target distance, metres
  double distance_variation = 0.1;                   ///< metres either side of the mean
  /// Largest swing of the viewing direction away from the world -Z axis, per axis (about
  /// world x and y). Kept well below 90 deg so the background plane stays behind.
  double max_tilt_deg = 35.0;
  double max_roll_deg = 25.0;  ///< rotation about the optical axis
  /// The looked-at point wanders this far (metres) from the target, so the object also
  /// translates in the image instead of staying centred.
  double look_at_wander = 0.02;
  /// Typical frequency of every component, in cycles per second: with the defaults the
  /// camera sweeps its range in about ten seconds.
  double cycles_per_second = 0.1;
  /// Multiplies every frequency: 1 is a calm hand-held motion, 3-5 makes a "fast motion"
  /// sequence with the same range of views.
  double speed = 1.0;
};

/// Seeded smooth random camera motion (OrbitOptions). Each component is a normalised sum
/// of a few sinusoids with random frequencies and phases, so the motion is smooth at any
/// speed, bounded, and a pure function of (options, seed, time).
class OrbitTrajectory {
 public:
  OrbitTrajectory(const OrbitOptions& options, std::uint64_t seed);
  Pose camera_T_world(double seconds) const;

 private:
  /// A smooth signal in [-1, 1].
  struct Signal {
    double frequency[3], phase[3], weight[3];
    double at(double seconds) const;
  };
  OrbitOptions options_;
  Signal distance_, tilt_x_, tilt_y_, roll_, wander_[3];
};

/// A colour camera's exposure: each colour image is the mean of `samples` renders spread
/// evenly over `exposure` of the frame interval, centred on the frame's time, with camera
/// and objects moved along their motion; the ground truth is the pose at that centre (the
/// middle of the exposure). Depth stays a single render at the frame's time.
struct MotionBlur {
  int samples = 1;        ///< renders per colour image; 1 = sharp
  double exposure = 0.5;  ///< fraction of the frame interval the shutter is open, (0, 1]
};

/// A large textured plane behind the objects (at world Z = target.z - distance), so region
/// and texture cues see clutter rather than a flat colour.
struct BackgroundPlane {
  bool enabled = true;
  double distance = 0.4;  ///< metres behind the orbit target
  cv::Mat texture_bgr;    ///< CV_8UC3 image tiled over the plane; empty = procedural clutter
  double tile_size = 0.3; ///< metres covered by one copy of the texture
};


/// How one joint value moves over a sequence: from `from` to `to` and back, smoothly, once
/// per `period` seconds: q(t) = from + (to − from)(1 − cos(2πt / period)) / 2. Radians for
/// rotations, metres for translations.
struct JointTrajectory {
  double from = 0.0;
  double to = 0.0;
  double period = 1.0;  ///< seconds, positive

  double at(double seconds) const;
};

struct SequenceWriterOptions {
  int frame_count = 100;
  double frame_rate = 30.0;
  std::uint64_t seed = 1;
  Intrinsics color_intrinsics;  ///< required: size and calibration of the colour images
  Intrinsics depth_intrinsics;  ///< required: size and calibration of the depth images
  Pose depth_T_color;           ///< colour camera -> depth camera
  /// An optional second colour camera, a stereo pair with the first: rendered exactly as
  /// the colour camera is (same background, lighting, noise model, antialiasing and motion
  /// blur) from stereo_T_color * color_T_world, written to color2/. Off: the sequence is
  /// byte-identical to one written without these fields.
  bool stereo = false;
  Intrinsics stereo_intrinsics;  ///< required when `stereo`: size and calibration of color2/
  Pose stereo_T_color;           ///< colour camera -> stereo camera (ViSP c2_M_c1)
  /// Metres per unit of the 16-bit depth PNGs. 0.1 mm quantises Z to within 0.05 mm, far
  /// below real sensor noise and the tracker's sub-millimetre target, while 16 bits still
  /// reach 6.5 m; depth beyond 65535 units is stored as 0 (out of range, as on a sensor).
  double depth_scale = 1e-4;
  OrbitOptions motion;
  BackgroundPlane background;
  SensorNoise noise;
  /// Multisample antialiasing of the colour images (samples per pixel, 0 = off): object
  /// edges blend into the background over a pixel as on a real camera.
  int antialias_samples = 0;
  MotionBlur motion_blur;
  /// A camera's auto-exposure hunting: every colour image (and the stereo camera's, the
  /// same) is scaled by 1 + gain_variation · sin(2π · 0.4 Hz · t + φ), φ drawn from the
  /// seed, before the sensor noise. In [0, 1); 0 leaves the images untouched.
  double gain_variation = 0.0;
  bool progress = true;  ///< report progress on stderr
};

/// Renders synthetic RGB-D sequences with exact ground truth in the "icgp" layout that
/// Sequence reads:
///
///   sequence.yaml       format, frame count and rate, depth_scale, both cameras'
///                       intrinsics and image sizes, depth_T_color, object names and meshes
///   color/%06d.png      8-bit BGR, from 000000 (lossless, so added noise is kept exactly)
///   color2/%06d.png     with `stereo`: the second colour camera's images, same format;
///                       sequence.yaml then also records stereo_camera and stereo_T_color
///   depth/%06d.png      16-bit, Z = value * depth_scale metres, 0 = no measurement
///   poses/<object>.txt  one line per frame: color_T_object (cMo), 16 numbers row-major,
///                       each in the shortest decimal form that reads back bit-exactly
///   joints/<link>.txt   for each link whose joint has free directions: one line per
///                       frame, the joint's values (radians / metres) in the same form;
///                       sequence.yaml records each link's parent and joint in the
///                       `bodies:` format of io/joint_yaml.h
///
/// The colour camera follows OrbitTrajectory(motion, seed); depth is rendered with the
/// depth intrinsics at depth_T_color * color_T_world, the stereo camera's colour at
/// stereo_T_color * color_T_world (its noise from a generator stream of its own, so adding
/// it changes none of the other files). The same options and seed give
/// byte-identical files (own random generators, independent of the standard library's
/// distributions); changing the noise does not change the trajectory or background.
class SequenceWriter {
 public:
  /// Throws std::invalid_argument for invalid options.
  explicit SequenceWriter(SequenceWriterOptions options);

  /// Adds an object at world_T_object. `name` ([A-Za-z0-9_.-], unique) labels its ground
  /// truth; `mesh_path` is recorded in sequence.yaml (empty: the mesh's source when it is
  /// a file). `spin` (rad/s, a rotation vector in the object's frame) turns the object about
  /// its origin at a constant rate: at time t its pose is world_T_object · exp(t · spin).
  /// `velocity` (m/s, world frame) moves it as a whole: at time t its pose is
  /// (t · velocity) ∘ world_T_object · exp(t · spin), the translation added in the world.
  void add_object(const std::string& name, const Mesh& mesh, const Pose& world_T_object = Pose(),
                  const std::string& mesh_path = "", const Eigen::Vector3d& spin = Eigen::Vector3d::Zero(),
                  const Eigen::Vector3d& velocity = Eigen::Vector3d::Zero());
  /// Adds a link: an object hanging from an object added before it (joint.parent) by
  /// `joint`, whose values follow `trajectory` (one per free direction, each within its
  /// direction's limits): at time t its pose is parent(t) · joint.parent_T_link(q(t)).
  /// Throws std::invalid_argument naming the link for a missing parent, an invalid joint
  /// or a trajectory that leaves the limits.
  void add_link(const std::string& name, const Mesh& mesh, Joint joint, std::vector<JointTrajectory> trajectory,
                const std::string& mesh_path = "");

  /// The colour camera pose of frame `index` (at its time, the middle of its exposure).
  Pose color_T_world(int index) const;
  /// The instant (seconds) of render `sample` of a colour image whose frame is at
  /// `frame_seconds` (MotionBlur): frame_seconds itself for a sharp image.
  double exposure_time(double frame_seconds, int sample) const;

  /// Renders every frame into `dir`. The folder is created when absent; an existing one
  /// must be empty or hold an earlier icgp sequence, whose files are replaced (other
  /// folders are refused so a mistyped path cannot wipe unrelated data). Needs a headless
  /// OpenGL context (throws RenderError without one).
  void write(const std::string& dir) const;

 private:
  struct Object {
    std::string name;
    Mesh mesh;
    Pose world_T_object;
    std::string mesh_path;
    Eigen::Vector3d spin = Eigen::Vector3d::Zero();
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
    /// A link: its joint, the index of its parent (an earlier object) and its trajectory.
    std::optional<Joint> joint;
    std::size_t parent = 0;
    std::vector<JointTrajectory> trajectory;

    std::vector<double> joint_values_at(double seconds) const;
  };
  void check_new_name(const std::string& name, const Mesh& mesh) const;
  /// Every object's world pose at `seconds`, parents before their links.
  std::vector<Pose> world_T_objects_at(double seconds) const;

  SequenceWriterOptions options_;
  OrbitTrajectory trajectory_;
  std::vector<Object> objects_;
};

}  // namespace icgp
