// SPDX-License-Identifier: GPL-2.0-or-later
// The "icgp" layout, what SequenceWriter writes: found by its sequence.yaml, which holds
// the cameras, depth_T_color, the depth scale and the objects. color/%06d.png,
// depth/%06d.png (uint16, Z = value * depth_scale), ground truth poses/<object>.txt (one
// line of 16 row-major numbers per frame); when the YAML has stereo_camera and
// stereo_T_color, a second colour camera's color2/%06d.png; links (objects with a parent
// and a joint, io/joint_yaml.h) whose joint has free directions have their joint values in
// joints/<object>.txt (Frame::joint_truth).
#include "built_in_layouts.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>

#include "depth_codecs.h"
#include "icgp/io/joint_yaml.h"
#include "icgp/io/yaml_reader.h"
#include "sequence_files.h"

namespace icgp {

namespace fs = std::filesystem;

namespace {

/// A camera of sequence.yaml: {fu, fv, pu, pv, width, height} (other keys, such as the
/// writer's camera name, are not read).
Intrinsics yaml_camera(const yaml::Value& value) {
  const yaml::Map camera(value);
  Intrinsics k;
  k.fu = camera.required("fu").as(yaml::kPositive);
  k.fv = camera.required("fv").as(yaml::kPositive);
  k.pu = camera.required("pu").as(yaml::kNumber);
  k.pv = camera.required("pv").as(yaml::kNumber);
  k.width = camera.required("width").as(yaml::kPositiveInt);
  k.height = camera.required("height").as(yaml::kPositiveInt);
  return k;
}

/// A rigid transform of sequence.yaml: 16 row-major numbers.
Pose yaml_transform(const yaml::Value& value) {
  const yaml::Rule<std::vector<double>> sixteen{"a list of 16 numbers (4x4 row-major)",
                                                [](const std::vector<double>& v) { return v.size() == 16; }};
  return pose_from_row_major(value.as(sixteen), value.at.file, value.at.key + ": ");
}

/// One line per frame of 16 row-major numbers (reference_T_object).
std::vector<Pose> read_pose_lines(const fs::path& file, int frame_count) {
  require_file(file, "ground-truth poses");
  std::ifstream in(file);
  std::vector<Pose> poses;
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    if (is_blank(line)) continue;
    const std::string where = "line " + std::to_string(line_no) + ": ";
    poses.push_back(pose_from_row_major(parse_numbers(line, 16, file, line_no), file, where));
  }
  if (static_cast<int>(poses.size()) != frame_count)
    fail(file, "has " + std::to_string(poses.size()) + " poses, expected one per frame (" +
                   std::to_string(frame_count) + ")");
  return poses;
}

/// One line per frame of the joint's `size` values.
std::vector<std::vector<double>> read_joint_lines(const fs::path& file, int frame_count, std::size_t size) {
  require_file(file, "ground-truth joint values");
  std::ifstream in(file);
  std::vector<std::vector<double>> values;
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    if (is_blank(line)) continue;
    values.push_back(parse_numbers(line, size, file, line_no));
  }
  if (static_cast<int>(values.size()) != frame_count)
    fail(file, "has " + std::to_string(values.size()) + " lines of joint values, expected one per frame (" +
                   std::to_string(frame_count) + ")");
  return values;
}

/// The joint of an object entry, checked against the objects listed before it: a link's
/// parent comes first, so the objects form trees (no cycle can be written).
std::optional<Joint> read_object_joint(const yaml::Map& fields, const yaml::Value& entry, const std::string& name,
                                       const std::vector<SequenceObject>& earlier) {
  std::optional<Joint> joint = read_joint(fields);
  if (!joint) return joint;
  const yaml::Location parent = entry.at.child("parent");
  if (std::none_of(earlier.begin(), earlier.end(), [&](const SequenceObject& o) { return o.name == joint->parent; }))
    parent.fail("'" + joint->parent + "' is not an object listed before '" + name + "'");
  try {
    validate(*joint, name);
  } catch (const std::invalid_argument& e) {
    entry.at.fail(e.what());
  }
  return joint;
}

class IcgpLayout : public SequenceLayout {
 public:
  fs::path color_file(int i) const override { return dir_ / "color" / numbered("", i, 6, ".png"); }
  fs::path depth_file(int i) const override { return dir_ / "depth" / numbered("", i, 6, ".png"); }
  fs::path stereo_color_file(int i) const override { return dir_ / "color2" / numbered("", i, 6, ".png"); }
  cv::Mat read_depth(int i) const override { return read_png_depth(depth_file(i), depth_scale_); }
  std::map<std::string, Pose> read_ground_truth(int i) const override {
    std::map<std::string, Pose> truth;
    for (const auto& [object, poses] : poses_) truth.emplace(object, poses[i]);
    return truth;
  }
  std::map<std::string, std::vector<double>> read_joint_truth(int i) const override {
    std::map<std::string, std::vector<double>> truth;
    for (const auto& [object, values] : joint_values_) truth.emplace(object, values[i]);
    return truth;
  }
  std::string size_origin() const override { return "size in sequence.yaml"; }

  static SequenceLayoutEntry::Opened open(const fs::path& dir, const SequenceOptions&) {
    // Any keys: the writer adds some (the seed, the cameras' names) that reading needs not.
    const yaml::Map root(yaml::load_file((dir / "sequence.yaml").string()));
    root.required("format").as(yaml::Rule<std::string>{
        "icgp-sequence", [](const std::string& format) { return format == "icgp-sequence"; }});
    root.required("version").as(
        yaml::Rule<int>{"1 (the version this reader knows)", [](const int& version) { return version == 1; }});

    auto layout = std::make_shared<IcgpLayout>();
    layout->dir_ = dir;
    SequenceDescription d;
    d.frame_count = root.required("frame_count").as(yaml::kPositiveInt);
    d.frame_rate = root.required("frame_rate").as(yaml::kPositive);
    layout->depth_scale_ = root.required("depth_scale").as(yaml::kPositive);
    d.color_intrinsics = yaml_camera(root.required("color_camera"));
    d.depth_intrinsics = yaml_camera(root.required("depth_camera"));
    d.depth_T_color = yaml_transform(root.required("depth_T_color"));
    // The optional stereo camera: both keys or neither.
    if (root.get("stereo_camera") || root.get("stereo_T_color")) {
      d.stereo = true;
      d.stereo_intrinsics = yaml_camera(root.required("stereo_camera"));
      d.stereo_T_color = yaml_transform(root.required("stereo_T_color"));
    }

    if (const std::optional<yaml::Value> objects = root.get("objects"))
      for (const yaml::Value& entry : objects->elements("a list of objects")) {
        const yaml::Map fields(entry);
        SequenceObject object;
        object.name = fields.required("name").as(yaml::kNonEmptyString);
        if (const std::optional<yaml::Value> mesh = fields.get("mesh")) {
          const fs::path mesh_path = mesh->as(yaml::kNonEmptyString);
          object.mesh_path = (mesh_path.is_absolute() ? mesh_path : dir / mesh_path).string();
        }
        object.joint = read_object_joint(fields, entry, object.name, d.objects);
        layout->poses_[object.name] = read_pose_lines(dir / "poses" / (object.name + ".txt"), d.frame_count);
        if (object.joint && object.joint->size() > 0)
          layout->joint_values_[object.name] = read_joint_lines(dir / "joints" / (object.name + ".txt"), d.frame_count,
                                                                object.joint->directions.size());
        d.objects.push_back(object);
      }
    d.has_ground_truth = !d.objects.empty();
    for (int i = 0; i < d.frame_count; ++i) {
      require_file(layout->color_file(i), "colour image of frame " + std::to_string(i));
      require_file(layout->depth_file(i), "depth image of frame " + std::to_string(i));
      if (d.stereo) require_file(layout->stereo_color_file(i), "stereo colour image of frame " + std::to_string(i));
    }
    return {d, layout};
  }

 private:
  fs::path dir_;
  double depth_scale_ = 0.0;
  std::map<std::string, std::vector<Pose>> poses_;
  std::map<std::string, std::vector<std::vector<double>>> joint_values_;
};

}  // namespace

SequenceLayoutEntry icgp_layout() {
  return {"icgp", "sequence.yaml", [](const fs::path& dir) { return fs::is_regular_file(dir / "sequence.yaml"); },
          IcgpLayout::open};
}

}  // namespace icgp
