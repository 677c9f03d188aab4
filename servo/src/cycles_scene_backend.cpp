// SPDX-License-Identifier: GPL-2.0-or-later
// The Cycles backend: requests to a Blender process (servo/blender/cycles_server.py, built
// into the program) and images back through files in a temporary folder of its own.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "icgp/io/yaml_reader.h"
#include "icgp/servo/blender_process.h"
#include "icgp/servo/cycles_server_script.h"
#include "icgp/visp/conversions.h"
#include "scene_backends.h"

namespace icgp::servo {
namespace {

namespace fs = std::filesystem;

/// A folder of its own under the system's temporary folder, removed with everything in it.
class TemporaryFolder {
 public:
  TemporaryFolder() {
    std::string pattern = (fs::temp_directory_path() / "icgp-cycles-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error(pattern + ": cannot make a temporary folder for Cycles");
    path_ = pattern;
  }
  ~TemporaryFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

/// The shortest text that reads back as the same double, which JSON reads as it is.
std::string json_number(double x) { return yaml::exact_number(x); }

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

template <typename Vector>
std::string json_list(const Vector& v) {
  std::string out = "[";
  for (int i = 0; i < v.size(); ++i) out += (i ? ", " : "") + json_number(v[i]);
  return out + "]";
}

/// 4x4 row-major, as the server reads matrices.
std::string json_matrix(const Pose& a_T_b) {
  const Eigen::Matrix4d m = a_T_b.matrix();
  std::string out = "[";
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out += (r + c ? ", " : "") + json_number(m(r, c));
  return out + "]";
}

template <typename T>
void write_array(const fs::path& file, const T* data, std::size_t count) {
  std::ofstream out(file, std::ios::binary);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(count * sizeof(T)));
  if (!out) throw std::runtime_error(file.string() + ": cannot write a mesh file for Cycles");
}

class CyclesSceneBackend final : public SceneBackend {
 public:
  CyclesSceneBackend(const CyclesSpec& spec, std::uint64_t seed)
      : blender_(write_script(), (folder_.path() / "blender.log").string(), spec.timeout_s), seed_(seed) {
    blender_.request("{\"op\": \"setup\", \"samples\": " + std::to_string(spec.samples) +
                     ", \"light_bounces\": " + std::to_string(spec.light_bounces) +
                     ", \"threads\": " + std::to_string(spec.threads) +
                     ", \"lamp_angle_deg\": " + json_number(kLampAngleDeg) +
                     ", \"geometry_folder\": " + json_string(folder_.path().string()) + "}");
  }

  void set_light(const LightState& light) override { light_ = light; }

  BodyHandle add_body(const Mesh& mesh, std::uint8_t /*id*/) override {
    const BodyHandle handle = static_cast<BodyHandle>(bodies_.size());
    std::string parts;
    for (std::size_t i = 0; i < mesh.parts.size(); ++i) {
      const MeshPart& part = mesh.parts[i];
      if (part.triangles.empty()) continue;
      const std::string stem = (folder_.path() / ("body" + std::to_string(handle) + "_" + std::to_string(i))).string();
      write_array(stem + ".vertices", part.vertices.front().data(), 3 * part.vertices.size());
      write_array(stem + ".triangles", part.triangles.front().data(), 3 * part.triangles.size());
      std::string texture = "null", texcoords = "null";
      if (!part.material.texture_bgr.empty()) {
        texture = json_string(stem + ".png");
        if (!cv::imwrite(stem + ".png", part.material.texture_bgr))
          throw std::runtime_error(stem + ".png: cannot write a texture for Cycles");
      }
      if (!part.texcoords.empty()) {
        write_array(stem + ".texcoords", part.texcoords.front().data(), 2 * part.texcoords.size());
        texcoords = json_string(stem + ".texcoords");
      }
      parts += std::string(parts.empty() ? "" : ", ") + "{\"vertices\": " + json_string(stem + ".vertices") +
               ", \"triangles\": " + json_string(stem + ".triangles") + ", \"texcoords\": " + texcoords +
               ", \"texture\": " + texture + ", \"diffuse\": " + json_list(part.material.diffuse_rgb) +
               ", \"roughness\": " + json_number(part.material.roughness) +
               ", \"metallic\": " + json_number(part.material.metallic) +
               ", \"specular\": " + json_number(part.material.specular) + "}";
    }
    blender_.request("{\"op\": \"body\", \"handle\": " + std::to_string(handle) + ", \"parts\": [" + parts + "]}");
    bodies_.push_back({});
    return handle;
  }

  /// Behind everything, its shadows could fall nowhere the camera sees: an ordinary body.
  BodyHandle add_backdrop(const Mesh& mesh, std::uint8_t id) override { return add_body(mesh, id); }

  void set_body_pose(BodyHandle body, const Pose& world_T_body) override { bodies_.at(body).world_T_body = world_T_body; }
  void set_body_visible(BodyHandle body, bool visible) override { bodies_.at(body).visible = visible; }

  cv::Mat render_color(const Intrinsics& k, const vpHomogeneousMatrix& wMc, const vpHomogeneousMatrix& previous_wMc,
                       double exposure) override {
    const fs::path out = folder_.path() / "color.png";
    std::string lamps;
    const std::vector<Eigen::Vector3d> directions = light_.directions_in_camera(wMc);
    for (std::size_t i = 0; i < directions.size(); ++i)
      lamps += std::string(i ? ", " : "") + "{\"direction_in_camera\": " + json_list(directions[i]) +
               ", \"strength\": " + json_number(light_.lamps[i].strength) + "}";
    std::string request = "{\"op\": \"color\", " + placement(k, to_pose(wMc)) + ", \"lamps\": [" + lamps +
                          "], \"ambient\": " + json_number(light_.ambient) +
                          ", \"seed\": " + std::to_string((seed_ * 1000003u + renders_++) & 0x7fffffffu) +
                          ", \"out\": " + json_string(out.string());
    if (exposure > 0.0)
      request += ", \"exposure_start_world_T_camera\": " + json_matrix(to_pose(pose_along_motion(wMc, previous_wMc, exposure)));
    blender_.request(request + "}");
    cv::Mat color = cv::imread(out.string(), cv::IMREAD_COLOR);
    if (color.cols != k.width || color.rows != k.height)
      throw std::runtime_error(out.string() + ": Cycles' colour image is not the " + std::to_string(k.width) + " x " +
                               std::to_string(k.height) + " asked for");
    return color;
  }

  RenderOutput render_geometry(const Intrinsics& k, const Pose& camera_T_world, bool with_normals) override {
    const fs::path out = folder_.path() / "geometry.f32";
    blender_.request("{\"op\": \"geometry\", " + placement(k, camera_T_world.inverse()) +
                     ", \"out\": " + json_string(out.string()) + "}");
    cv::Mat packed(k.height, k.width, CV_32FC4);
    std::ifstream in(out, std::ios::binary);
    in.read(reinterpret_cast<char*>(packed.data), static_cast<std::streamsize>(packed.total() * packed.elemSize()));
    if (!in || in.peek() != std::char_traits<char>::eof())
      throw std::runtime_error(out.string() + ": Cycles' depth and normals are not a " + std::to_string(k.width) +
                               " x " + std::to_string(k.height) + " image");
    std::vector<cv::Mat> channels;
    cv::split(packed, channels);
    RenderOutput geometry;
    geometry.depth = channels[3];
    if (with_normals) cv::merge(std::vector<cv::Mat>{channels[0], channels[1], channels[2]}, geometry.normals);
    return geometry;
  }

 private:
  struct BodyState {
    Pose world_T_body;
    bool visible = true;
  };

  std::string write_script() const {
    const fs::path file = folder_.path() / "cycles_server.py";
    std::ofstream out(file);
    out << kCyclesServerScript;
    if (!out) throw std::runtime_error(file.string() + ": cannot write the Cycles server script");
    return file.string();
  }

  /// The request's intrinsics, bodies and camera pose.
  std::string placement(const Intrinsics& k, const Pose& world_T_camera) const {
    std::string bodies;
    for (std::size_t i = 0; i < bodies_.size(); ++i)
      bodies += std::string(i ? ", " : "") + "{\"handle\": " + std::to_string(i) +
                ", \"world_T_body\": " + json_matrix(bodies_[i].world_T_body) +
                ", \"visible\": " + (bodies_[i].visible ? "true" : "false") + "}";
    return "\"intrinsics\": [" + json_number(k.fu) + ", " + json_number(k.fv) + ", " + json_number(k.pu) + ", " +
           json_number(k.pv) + ", " + std::to_string(k.width) + ", " + std::to_string(k.height) + "], \"bodies\": [" +
           bodies + "], \"world_T_camera\": " + json_matrix(world_T_camera);
  }

  TemporaryFolder folder_;  ///< first made, last removed: Blender has quit by then
  BlenderProcess blender_;
  std::uint64_t seed_;
  std::uint64_t renders_ = 0;
  LightState light_;
  std::vector<BodyState> bodies_;
};

}  // namespace

std::unique_ptr<SceneBackend> make_cycles_backend(const CyclesSpec& cycles, std::uint64_t seed) {
  return std::make_unique<CyclesSceneBackend>(cycles, seed);
}

}  // namespace icgp::servo
