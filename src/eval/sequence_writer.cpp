// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/eval/sequence_writer.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "icgp/base/camera_names.h"
#include "icgp/render/renderer.h"
#include "icgp/render/scene_props.h"
#include "icgp/render/sensor_effects.h"
#include "icgp/base/splitmix64.h"
#include "icgp/io/joint_yaml.h"

namespace icgp {

namespace fs = std::filesystem;

namespace {

/// The writer's generator streams (seeded_stream purposes), one per frame for noise;
/// purpose 2 is the background clutter's (procedural_clutter_texture).
enum Stream : std::uint64_t { kTrajectoryStream = 1, kNoiseStream = 3, kStereoNoiseStream = 4, kGainStream = 5 };

/// How fast a hunting auto-exposure swings (SequenceWriterOptions::gain_variation): a few
/// seconds per cycle, as a camera readjusting to a changing view.
constexpr double kGainCyclesPerSecond = 0.4;

/// Shortest decimal form of `value` that parses back to the same double.
std::string exact(double value) {
  char text[40];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (std::strtod(text, nullptr) == value) break;
  }
  return text;
}

void require(bool condition, const std::string& message) {
  if (!condition) throw std::invalid_argument("SequenceWriter: " + message);
}

/// Widest angle between the optical axis and the ray through an image corner.
double half_diagonal_fov(const Intrinsics& k) {
  double widest = 0.0;
  for (const double u : {-0.5, k.width - 0.5})
    for (const double v : {-0.5, k.height - 0.5})
      widest = std::max(widest, std::atan(std::hypot((u - k.pu) / k.fu, (v - k.pv) / k.fv)));
  return widest;
}

/// Half the side of a plane that fills every view of the orbit: camera offset from the
/// target axis plus how far the widest ray travels sideways before reaching the plane.
/// Rays steeper than 80 deg from the plane normal are not covered (they would need an
/// unbounded plane and meet it beyond any depth range anyway).
double background_half_extent(const SequenceWriterOptions& o) {
  const OrbitOptions& m = o.motion;
  const double max_tilt = deg_to_rad(m.max_tilt_deg);
  const double tilt = std::acos(std::cos(max_tilt) * std::cos(max_tilt));
  const double far = m.distance + m.distance_variation;
  const double near = m.distance - m.distance_variation;
  const double wander = m.look_at_wander * std::sqrt(3.0);
  double fov = std::max(half_diagonal_fov(o.color_intrinsics), half_diagonal_fov(o.depth_intrinsics));
  double offset = o.depth_T_color.translation().norm();  // of the other cameras from the colour one
  if (o.stereo) {
    fov = std::max(fov, half_diagonal_fov(o.stereo_intrinsics));
    offset = std::max(offset, o.stereo_T_color.translation().norm());
  }
  const double ray = std::min(tilt + fov + std::atan(wander / near), deg_to_rad(80.0));
  return far * std::sin(tilt) + offset + wander + (far + o.background.distance) * std::tan(ray);
}


cv::Mat quantise_depth(const cv::Mat& depth, double scale) {
  cv::Mat stored(depth.size(), CV_16UC1);
  for (int r = 0; r < depth.rows; ++r)
    for (int c = 0; c < depth.cols; ++c) {
      const double units = std::round(depth.at<float>(r, c) / scale);
      stored.at<std::uint16_t>(r, c) = units > 0.0 && units <= 65535.0 ? std::uint16_t(units) : 0;
    }
  return stored;
}

void write_image(const fs::path& path, const cv::Mat& image) {
  if (!cv::imwrite(path.string(), image)) throw std::runtime_error(path.string() + ": cannot write image");
}

std::string yaml_camera(const std::string& name, const Intrinsics& k) {
  return "{name: " + name + ", width: " + std::to_string(k.width) + ", height: " + std::to_string(k.height) +
         ", fu: " + exact(k.fu) + ", fv: " + exact(k.fv) + ", pu: " + exact(k.pu) + ", pv: " + exact(k.pv) + "}";
}

std::string yaml_quoted(const std::string& text) {
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') quoted += '\\';
    quoted += c;
  }
  return quoted + "\"";
}

/// The 16 entries of the pose's 4x4 matrix, row-major, joined by `separator`.
std::string row_major(const Pose& pose, const std::string& separator) {
  const Eigen::Matrix4d m = pose.matrix();
  std::string line;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) line += (line.empty() ? "" : separator) + exact(m(r, c));
  return line;
}

/// A link's joint as the keys of its `objects:` entry (io/joint_yaml.h), each line indented
/// by `indent` to sit under the entry's name.
std::string yaml_joint(const Joint& joint, const std::string& indent) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  write_joint(out, joint);
  out << YAML::EndMap;
  std::istringstream lines(out.c_str());
  std::string text, line;
  while (std::getline(lines, line)) text += indent + line + "\n";
  return text;
}

/// Creates `dir`, or empties it when it holds an earlier icgp sequence; anything else is
/// refused so a mistyped path cannot delete unrelated files.
void prepare_folder(const fs::path& dir, bool stereo, bool joints) {
  if (fs::exists(dir)) {
    if (!fs::is_directory(dir)) throw std::runtime_error(dir.string() + ": exists and is not a folder");
    if (!fs::is_empty(dir)) {
      if (!fs::is_regular_file(dir / "sequence.yaml"))
        throw std::runtime_error(dir.string() + ": refusing to write into a non-empty folder that does not hold an "
                                               "icgp sequence (no sequence.yaml)");
      for (const char* name : {"sequence.yaml", "color", "color2", "depth", "poses", "joints"}) fs::remove_all(dir / name);
    }
  }
  for (const char* name : {"color", "depth", "poses"}) fs::create_directories(dir / name);
  if (stereo) fs::create_directories(dir / "color2");
  if (joints) fs::create_directories(dir / "joints");
}

/// The mesh file sequence.yaml names: `mesh_path`, else the mesh's source when it is a file.
std::string recorded_mesh_path(const Mesh& mesh, const std::string& mesh_path) {
  if (mesh_path.empty() && fs::is_regular_file(mesh.source)) return fs::absolute(mesh.source).string();
  return mesh_path;
}

bool is_file_name_safe(const std::string& name) {
  return !name.empty() && name[0] != '.' && std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '_' || c == '-' || c == '.';
  });
}

}  // namespace

double OrbitTrajectory::Signal::at(double seconds) const {
  double sum = 0.0, total_weight = 0.0;
  for (int k = 0; k < 3; ++k) {
    sum += weight[k] * std::sin(2.0 * kPi * frequency[k] * seconds + phase[k]);
    total_weight += weight[k];
  }
  return sum / total_weight;
}

OrbitTrajectory::OrbitTrajectory(const OrbitOptions& options, std::uint64_t seed) : options_(options) {
  require(options.distance > 0.0 && options.distance_variation >= 0.0 &&
              options.distance_variation < options.distance,
          "orbit distance must be positive and larger than its variation");
  require(options.max_tilt_deg >= 0.0 && options.max_tilt_deg <= 60.0, "max_tilt_deg must be in [0, 60]");
  require(options.cycles_per_second > 0.0 && options.speed > 0.0, "cycles_per_second and speed must be positive");
  require(options.look_at_wander >= 0.0, "look_at_wander must not be negative");
  SplitMix64 random = seeded_stream(seed, kTrajectoryStream);
  const double base = options.cycles_per_second * options.speed;
  for (Signal* signal : {&distance_, &tilt_x_, &tilt_y_, &roll_, &wander_[0], &wander_[1], &wander_[2]})
    for (int k = 0; k < 3; ++k) {
      signal->frequency[k] = base * random.uniform(0.5, 1.5);
      signal->phase[k] = random.uniform(0.0, 2.0 * kPi);
      signal->weight[k] = random.uniform(0.5, 1.0);
    }
}

Pose OrbitTrajectory::camera_T_world(double seconds) const {
  const OrbitOptions& o = options_;
  const double distance = o.distance + o.distance_variation * distance_.at(seconds);
  const double ax = deg_to_rad(o.max_tilt_deg) * tilt_x_.at(seconds);
  const double ay = deg_to_rad(o.max_tilt_deg) * tilt_y_.at(seconds);
  const Eigen::Vector3d towards_camera(std::cos(ay) * std::sin(ax), std::sin(ay), std::cos(ay) * std::cos(ax));
  const Eigen::Vector3d position = o.target + distance * towards_camera;
  const Eigen::Vector3d look_at =
      o.target + o.look_at_wander * Eigen::Vector3d(wander_[0].at(seconds), wander_[1].at(seconds), wander_[2].at(seconds));

  // Camera axes (x right, y down, z forward) with world +Y up in the image before roll;
  // z never nears +-Y because the tilt is bounded.
  const Eigen::Vector3d z = (look_at - position).normalized();
  const Eigen::Vector3d x = Eigen::Vector3d(0.0, -1.0, 0.0).cross(z).normalized();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d world_R_camera;
  world_R_camera << x, y, z;
  const Eigen::Matrix3d roll =
      Eigen::AngleAxisd(deg_to_rad(o.max_roll_deg) * roll_.at(seconds), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return Pose(world_R_camera * roll, position).inverse();
}

SequenceWriter::SequenceWriter(SequenceWriterOptions options)
    : options_(std::move(options)), trajectory_(options_.motion, options_.seed) {
  const SequenceWriterOptions& o = options_;
  require(o.frame_count > 0, "frame_count must be positive");
  require(o.frame_rate > 0.0, "frame_rate must be positive");
  require(o.depth_scale > 0.0, "depth_scale must be positive");
  o.color_intrinsics.validate("SequenceWriter: color_intrinsics");
  o.depth_intrinsics.validate("SequenceWriter: depth_intrinsics");
  if (o.stereo) o.stereo_intrinsics.validate("SequenceWriter: stereo_intrinsics");
  require(o.noise.color_sigma >= 0.0 && o.noise.depth_sigma_at_1m >= 0.0, "noise sigmas must not be negative");
  require(o.noise.depth_dropout >= 0.0 && o.noise.depth_dropout < 1.0, "depth_dropout must be in [0, 1)");
  require(o.noise.grazing_angle_deg > 0.0, "grazing_angle_deg must be positive (90 or more: no grazing holes)");
  require(o.noise.depth_edge_holes_px >= 0, "depth_edge_holes_px must not be negative");
  require(o.antialias_samples >= 0, "antialias_samples must not be negative (0 = off)");
  require(o.motion_blur.samples >= 1, "motion_blur.samples must be at least 1 (1 = sharp)");
  require(o.motion_blur.exposure > 0.0 && o.motion_blur.exposure <= 1.0, "motion_blur.exposure must be in (0, 1]");
  require(o.gain_variation >= 0.0 && o.gain_variation < 1.0, "gain_variation must be in [0, 1)");
  require(!o.background.enabled || (o.background.distance > 0.0 && o.background.tile_size > 0.0),
          "background distance and tile_size must be positive");
  require(o.background.texture_bgr.empty() || o.background.texture_bgr.type() == CV_8UC3,
          "background texture must be CV_8UC3");
}

double JointTrajectory::at(double seconds) const {
  return from + (to - from) * (1.0 - std::cos(2.0 * kPi * seconds / period)) / 2.0;
}

std::vector<double> SequenceWriter::Object::joint_values_at(double seconds) const {
  std::vector<double> q;
  for (const JointTrajectory& value : trajectory) q.push_back(value.at(seconds));
  return q;
}

std::vector<Pose> SequenceWriter::world_T_objects_at(double seconds) const {
  std::vector<Pose> poses;
  for (const Object& object : objects_) {
    if (object.joint) {
      poses.push_back(poses[object.parent] * object.joint->parent_T_link(object.joint_values_at(seconds)));
    } else {
      const Pose spun = object.world_T_object * Pose::from_rotation_vector(seconds * object.spin, Eigen::Vector3d::Zero());
      // Only a moving object is translated: adding a zero would turn a -0 into 0 and change
      // the files of sequences written before objects could move.
      poses.push_back(object.velocity.isZero() ? spun
                                               : Pose(spun.rotation(), spun.translation() + seconds * object.velocity));
    }
  }
  return poses;
}

void SequenceWriter::check_new_name(const std::string& name, const Mesh& mesh) const {
  require(is_file_name_safe(name), "object name '" + name + "' must be non-empty [A-Za-z0-9_.-] (it names a file)");
  require(std::none_of(objects_.begin(), objects_.end(), [&](const Object& o) { return o.name == name; }),
          "object name '" + name + "' is used twice");
  require(!mesh.empty(), "mesh of object '" + name + "' has no triangles");
  require(objects_.size() < 254, "at most 254 objects");
}

void SequenceWriter::add_object(const std::string& name, const Mesh& mesh, const Pose& world_T_object,
                                const std::string& mesh_path, const Eigen::Vector3d& spin,
                                const Eigen::Vector3d& velocity) {
  check_new_name(name, mesh);
  require(spin.allFinite(), "spin of object '" + name + "' must be finite");
  require(velocity.allFinite(), "velocity of object '" + name + "' must be finite");
  Object object;
  object.name = name;
  object.mesh = mesh;
  object.world_T_object = world_T_object;
  object.mesh_path = recorded_mesh_path(mesh, mesh_path);
  object.spin = spin;
  object.velocity = velocity;
  objects_.push_back(std::move(object));
}

void SequenceWriter::add_link(const std::string& name, const Mesh& mesh, Joint joint,
                              std::vector<JointTrajectory> trajectory, const std::string& mesh_path) {
  check_new_name(name, mesh);
  try {
    validate(joint, name);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("SequenceWriter: ") + e.what());
  }
  const auto parent = std::find_if(objects_.begin(), objects_.end(), [&](const Object& o) { return o.name == joint.parent; });
  require(parent != objects_.end(), "link '" + name + "': parent '" + joint.parent + "' is not an object added before it");
  require(static_cast<int>(trajectory.size()) == joint.size(),
          "link '" + name + "': " + std::to_string(trajectory.size()) + " trajectories for a joint of " +
              std::to_string(joint.size()) + " directions");
  for (int k = 0; k < joint.size(); ++k) {
    const JointTrajectory& value = trajectory[k];
    const JointDirection& direction = joint.directions[k];
    const std::string at = "link '" + name + "': trajectory of direction " + std::to_string(k);
    require(std::isfinite(value.from) && std::isfinite(value.to), at + " must be finite");
    require(value.period > 0.0 && std::isfinite(value.period), at + ": period must be positive");
    // q(t) sweeps [min(from, to), max(from, to)].
    require(std::min(value.from, value.to) >= direction.min && std::max(value.from, value.to) <= direction.max,
            at + " leaves the joint's limits");
  }
  Object object;
  object.name = name;
  object.mesh = mesh;
  object.mesh_path = recorded_mesh_path(mesh, mesh_path);
  object.parent = static_cast<std::size_t>(parent - objects_.begin());
  object.joint = std::move(joint);
  object.trajectory = std::move(trajectory);
  objects_.push_back(std::move(object));
}

Pose SequenceWriter::color_T_world(int index) const { return trajectory_.camera_T_world(index / options_.frame_rate); }

double SequenceWriter::exposure_time(double frame_seconds, int sample) const {
  const MotionBlur& blur = options_.motion_blur;
  // Sample centres of `samples` equal slices of the exposure: symmetric about the frame's
  // time, so their mean pose is the ground truth's.
  const double offset = ((sample + 0.5) / blur.samples - 0.5) * blur.exposure / options_.frame_rate;
  return frame_seconds + offset;
}

void SequenceWriter::write(const std::string& dir_name) const {
  const SequenceWriterOptions& o = options_;
  require(!objects_.empty(), "add at least one object before writing");
  const fs::path dir(dir_name);
  const auto moves = [](const Object& object) { return object.joint && object.joint->size() > 0; };
  prepare_folder(dir, o.stereo, std::any_of(objects_.begin(), objects_.end(), moves));

  Renderer renderer;
  std::vector<Renderer::BodyHandle> bodies;
  for (std::size_t i = 0; i < objects_.size(); ++i) bodies.push_back(renderer.add_body(objects_[i].mesh, std::uint8_t(i + 1)));
  if (o.background.enabled) {
    const cv::Mat texture =
        o.background.texture_bgr.empty() ? procedural_clutter_texture(o.seed) : o.background.texture_bgr;
    const Eigen::Vector3d& target = o.motion.target;
    renderer.add_body(tiled_plane(texture, background_half_extent(o), o.background.tile_size, target.head<2>(),
                                  target.z() - o.background.distance),
                      255);
  }

  std::ofstream yaml(dir / "sequence.yaml");
  yaml << "# icgp RGB-D sequence written by icgp::SequenceWriter. color/%06d.png: 8-bit BGR;\n"
          "# depth/%06d.png: 16-bit, Z = value * depth_scale metres, 0 = no measurement;\n"
          "# poses/<object>.txt: one line per frame, color_T_object as 16 numbers row-major.\n"
       << "format: icgp-sequence\nversion: 1\n"
       << "frame_count: " << o.frame_count << "\nframe_rate: " << exact(o.frame_rate)
       << "\ndepth_scale: " << exact(o.depth_scale) << "\nseed: " << o.seed << "\n"
       << "color_camera: " << yaml_camera(kColorCamera, o.color_intrinsics) << "\n"
       << "depth_camera: " << yaml_camera(kDepthCamera, o.depth_intrinsics) << "\n"
       << "depth_T_color: [" << row_major(o.depth_T_color, ", ") << "]\n";
  if (o.stereo)
    yaml << "# stereo: color2/%06d.png, a second colour camera at stereo_T_color * color_T_world.\n"
         << "stereo_camera: " << yaml_camera(kStereoCamera, o.stereo_intrinsics) << "\n"
         << "stereo_T_color: [" << row_major(o.stereo_T_color, ", ") << "]\n";
  yaml << "objects:\n";
  for (const Object& object : objects_) {
    yaml << "  - name: " << object.name << "\n";
    if (!object.mesh_path.empty()) yaml << "    mesh: " << yaml_quoted(object.mesh_path) << "\n";
    if (object.joint) yaml << yaml_joint(*object.joint, "    ");
  }
  yaml.close();
  if (!yaml) throw std::runtime_error((dir / "sequence.yaml").string() + ": cannot write");

  std::vector<std::ofstream> pose_files;
  for (const Object& object : objects_) pose_files.emplace_back(dir / "poses" / (object.name + ".txt"));
  std::vector<std::ofstream> joint_files(objects_.size());
  for (std::size_t k = 0; k < objects_.size(); ++k)
    if (moves(objects_[k])) joint_files[k].open(dir / "joints" / (objects_[k].name + ".txt"));

  renderer.set_color_antialiasing(o.antialias_samples);
  const auto place_objects = [&](double seconds) {
    const std::vector<Pose> poses = world_T_objects_at(seconds);
    for (std::size_t k = 0; k < objects_.size(); ++k) renderer.set_body_pose(bodies[k], poses[k]);
  };
  const double gain_phase = 2.0 * M_PI * seeded_stream(o.seed, kGainStream).uniform();
  char name[32];
  for (int i = 0; i < o.frame_count; ++i) {
    const double seconds = i / o.frame_rate;
    // A colour camera's exposure; the stereo camera's is the colour camera's (a synchronised pair).
    const auto expose = [&](const Intrinsics& intrinsics, const Pose& camera_T_color) {
      return average_color_renders(o.motion_blur.samples, [&](int sample) {
        const double t = exposure_time(seconds, sample);
        place_objects(t);
        return renderer.render(intrinsics, camera_T_color * trajectory_.camera_T_world(t), kRenderColor).color;
      });
    };
    cv::Mat color = expose(o.color_intrinsics, Pose());
    cv::Mat stereo_color;
    if (o.stereo) stereo_color = expose(o.stereo_intrinsics, o.stereo_T_color);

    // Depth and ground truth at the frame's time, the middle of the exposure.
    const Pose camera_T_world = color_T_world(i);
    place_objects(seconds);
    const std::vector<Pose> world_T_objects = world_T_objects_at(seconds);
    cv::Mat depth = render_sensor_depth(renderer, o.depth_intrinsics, o.depth_T_color * camera_T_world, o.noise);
    if (o.gain_variation > 0.0) {
      const double gain = 1.0 + o.gain_variation * std::sin(2.0 * M_PI * kGainCyclesPerSecond * seconds + gain_phase);
      color.convertTo(color, -1, gain);
      if (o.stereo) stereo_color.convertTo(stereo_color, -1, gain);
    }
    SensorNoiseDraws noise(seeded_stream(o.seed, kNoiseStream, std::uint64_t(i)).next());
    noise.add_color_noise(color, o.noise.color_sigma);
    noise.add_depth_noise(depth, o.noise);
    if (o.stereo) {
      SensorNoiseDraws stereo_noise(seeded_stream(o.seed, kStereoNoiseStream, std::uint64_t(i)).next());
      stereo_noise.add_color_noise(stereo_color, o.noise.color_sigma);
    }

    std::snprintf(name, sizeof name, "%06d.png", i);
    write_image(dir / "color" / name, color);
    if (o.stereo) write_image(dir / "color2" / name, stereo_color);
    write_image(dir / "depth" / name, quantise_depth(depth, o.depth_scale));
    for (std::size_t k = 0; k < objects_.size(); ++k) {
      pose_files[k] << row_major(camera_T_world * world_T_objects[k], " ") << "\n";
      if (!moves(objects_[k])) continue;
      std::string values;
      for (const double q : objects_[k].joint_values_at(seconds)) values += (values.empty() ? "" : " ") + exact(q);
      joint_files[k] << values << "\n";
    }

    if (o.progress && ((i + 1) * 10 / o.frame_count != i * 10 / o.frame_count || i + 1 == o.frame_count))
      std::cerr << "icgp sequence writer: " << dir.string() << ": frame " << i + 1 << "/" << o.frame_count << "\n";
  }
  for (std::size_t k = 0; k < objects_.size(); ++k) {
    if (!pose_files[k].flush())
      throw std::runtime_error((dir / "poses" / (objects_[k].name + ".txt")).string() + ": cannot write");
    if (moves(objects_[k]) && !joint_files[k].flush())
      throw std::runtime_error((dir / "joints" / (objects_[k].name + ".txt")).string() + ": cannot write");
  }
}

}  // namespace icgp
