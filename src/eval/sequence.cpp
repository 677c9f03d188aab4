// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/eval/sequence.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <stdexcept>

#include "depth_codecs.h"
#include "icgp/base/camera_names.h"
#include "icgp/io/joint_yaml.h"
#include "icgp/io/yaml_reader.h"
#include "sequence_files.h"

namespace icgp {

namespace fs = std::filesystem;

namespace {

/// Depth in place: 0 wherever there is no trustworthy measurement.
void clear_invalid_depth(cv::Mat& depth, double max_depth) {
  const float max_z = static_cast<float>(max_depth);
  depth.forEach<float>([max_z](float& z, const int*) {
    if (!(z > 0.f && z <= max_z)) z = 0.f;  // also catches NaN
  });
}

void check_size(const cv::Mat& image, const Intrinsics& expected, const fs::path& file, const std::string& what,
                const std::string& origin) {
  if (image.cols != expected.width || image.rows != expected.height)
    fail(file, what + " is " + size_text(image.cols, image.rows) + " but expected " +
                   size_text(expected.width, expected.height) + " (" + origin + ")");
}

/// A principal point outside the image means the images are not the size the intrinsics
/// were calibrated for (depth frames of half the size, say).
void check_principal_point(const fs::path& dir, const Intrinsics& k, const std::string& what) {
  if (!(k.pu >= -0.5 && k.pu <= k.width - 0.5 && k.pv >= -0.5 && k.pv <= k.height - 0.5))
    fail(dir, what + " intrinsics put the principal point at (" + std::to_string(k.pu) + ", " + std::to_string(k.pv) +
                  "), outside the " + size_text(k.width, k.height) + " " + what +
                  " images (expected images of the size the intrinsics were calibrated for)");
}

// ---------------------------------------------------------------------------------------
// Layouts

/// Everything open() learns about a sequence besides how to read its frames.
struct Description {
  std::string layout;
  int frame_count = 0;
  double frame_rate = 0.0;
  Intrinsics color_intrinsics, depth_intrinsics;
  Pose depth_T_color;
  bool stereo = false;
  Intrinsics stereo_intrinsics;
  Pose stereo_T_color;
  std::vector<SequenceObject> objects;
  bool has_ground_truth = false;
};

}  // namespace

/// Reads the frame files of one layout. Sizes are checked by the caller.
class Sequence::Layout {
 public:
  virtual ~Layout() = default;
  virtual fs::path color_file(int index) const = 0;
  virtual fs::path depth_file(int index) const = 0;
  /// The second colour camera's image (layouts that have one).
  virtual fs::path stereo_color_file(int) const { return {}; }
  /// Metres as stored, invalid values not yet cleared; CV_32FC1.
  virtual cv::Mat read_depth(int index) const = 0;
  virtual std::map<std::string, Pose> read_ground_truth(int index) const = 0;
  /// The joint values of each link (layouts that have links).
  virtual std::map<std::string, std::vector<double>> read_joint_truth(int) const { return {}; }
  /// Where the expected image sizes came from, for messages.
  virtual std::string size_origin() const = 0;
};

namespace {

struct IntrinsicsFiles {
  fs::path color, depth;
};

/// The `<name>.xml` files of `folder` that have a `<name>_depth.xml` beside them.
std::vector<IntrinsicsFiles> xml_pairs_in(const fs::path& folder) {
  std::vector<IntrinsicsFiles> pairs;
  if (!fs::is_directory(folder)) return pairs;
  for (const auto& entry : fs::directory_iterator(folder)) {
    const fs::path& p = entry.path();
    if (p.extension() != ".xml") continue;
    const std::string stem = p.stem().string();
    if (stem.size() > 6 && stem.compare(stem.size() - 6, 6, "_depth") == 0) continue;
    const fs::path depth = folder / (stem + "_depth.xml");
    if (fs::is_regular_file(depth)) pairs.push_back({p, depth});
  }
  std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) { return a.color < b.color; });
  return pairs;
}

/// Relative option paths may be relative to the working directory or to the sequence.
fs::path resolve_option_path(const std::string& path, const fs::path& dir) {
  const fs::path given(path);
  if (given.is_absolute() || fs::exists(given)) return given;
  return dir / given;
}

IntrinsicsFiles find_intrinsics_files(const fs::path& dir, const SequenceOptions& options) {
  if (!options.color_intrinsics_file.empty()) {
    IntrinsicsFiles files;
    files.color = resolve_option_path(options.color_intrinsics_file, dir);
    files.depth = options.depth_intrinsics_file.empty()
                      ? files.color.parent_path() / (files.color.stem().string() + "_depth.xml")
                      : resolve_option_path(options.depth_intrinsics_file, dir);
    require_file(files.color, "colour intrinsics file (SequenceOptions::color_intrinsics_file)");
    require_file(files.depth, "depth intrinsics file (SequenceOptions::depth_intrinsics_file, or <stem>_depth.xml "
                              "beside the colour one)");
    return files;
  }
  if (!options.depth_intrinsics_file.empty())
    fail(dir, "SequenceOptions::depth_intrinsics_file is set but color_intrinsics_file is not");

  std::vector<IntrinsicsFiles> candidates = xml_pairs_in(dir);
  if (candidates.empty() && fs::is_directory(dir / "models")) {
    std::vector<fs::path> model_folders;
    for (const auto& entry : fs::directory_iterator(dir / "models"))
      if (entry.is_directory()) model_folders.push_back(entry.path());
    std::sort(model_folders.begin(), model_folders.end());
    for (const auto& folder : model_folders) {
      const auto pairs = xml_pairs_in(folder);
      candidates.insert(candidates.end(), pairs.begin(), pairs.end());
    }
  }
  if (candidates.size() == 1) return candidates.front();
  if (candidates.empty())
    fail(dir, "no intrinsics found: looked for a <name>.xml + <name>_depth.xml pair (ViSP <camera> blocks) in the "
              "folder and in models/*/; set SequenceOptions::color_intrinsics_file and depth_intrinsics_file");
  std::string list;
  for (const auto& c : candidates) list += "\n  " + c.color.string() + " + " + c.depth.filename().string();
  fail(dir, "ambiguous intrinsics, " + std::to_string(candidates.size()) + " candidate pairs:" + list +
                "\nchoose one with SequenceOptions::color_intrinsics_file and depth_intrinsics_file");
}

/// ViSP models of the sequence: the top-level .cao files, else the .cao named like the
/// colour intrinsics file beside it (models/cube/cube.xml -> models/cube/cube.cao).
std::vector<SequenceObject> find_visp_objects(const fs::path& dir, const fs::path& color_xml) {
  std::vector<SequenceObject> objects;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".cao") objects.push_back({entry.path().stem().string(), entry.path().string()});
  std::sort(objects.begin(), objects.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  const fs::path beside = color_xml.parent_path() / (color_xml.stem().string() + ".cao");
  if (objects.empty() && fs::is_regular_file(beside)) objects.push_back({color_xml.stem().string(), beside.string()});
  return objects;
}

/// Calibration shared by the ViSP layouts: XML intrinsics, depth_M_color.txt, image sizes
/// from the first colour and depth images.
void describe_visp_calibration(const fs::path& dir, const SequenceOptions& options, const Sequence::Layout& files,
                               Description& d) {
  if (!options.read_camera_xml)
    fail(dir, "a " + d.layout + " sequence keeps its intrinsics in ViSP XML files, which the core library does not "
              "read: set SequenceOptions::read_camera_xml, e.g. to icgp::read_visp_camera_xml of icgp::visp "
              "(icgp/visp/visp_camera_xml.h; icgp::visp_sequence_options() sets it)");
  const IntrinsicsFiles xml = find_intrinsics_files(dir, options);
  d.color_intrinsics = options.read_camera_xml(xml.color.string());
  d.depth_intrinsics = options.read_camera_xml(xml.depth.string());
  require_file(dir / "depth_M_color.txt", "colour-to-depth transform");
  d.depth_T_color = read_pose_matrix_file((dir / "depth_M_color.txt").string());
  const cv::Mat color = read_color_image(files.color_file(0));
  d.color_intrinsics.width = color.cols;
  d.color_intrinsics.height = color.rows;
  const cv::Mat depth = files.read_depth(0);
  d.depth_intrinsics.width = depth.cols;
  d.depth_intrinsics.height = depth.rows;
  d.color_intrinsics.validate(xml.color.string());
  d.depth_intrinsics.validate(xml.depth.string());
  d.objects = find_visp_objects(dir, xml.color);
  d.frame_rate = options.frame_rate;
}

class VispBlenderLayout : public Sequence::Layout {
 public:
  explicit VispBlenderLayout(fs::path dir) : dir_(std::move(dir)) { enable_openexr_decoding(); }
  fs::path color_file(int i) const override { return dir_ / "images" / numbered("", i + 1, 4, ".jpg"); }
  fs::path depth_file(int i) const override { return dir_ / "depth" / numbered("Image", i + 1, 4, ".exr"); }
  fs::path pose_file(int i) const { return dir_ / "camera_poses" / numbered("Camera_", i + 1, 3, ".txt"); }
  cv::Mat read_depth(int i) const override { return read_exr_depth(depth_file(i)); }
  std::map<std::string, Pose> read_ground_truth(int i) const override {
    if (object_.empty()) return {};
    return {{object_, read_pose_matrix_file(pose_file(i).string())}};
  }
  std::string size_origin() const override { return "size of the first frame"; }

  static std::pair<Description, std::shared_ptr<const Sequence::Layout>> open(const fs::path& dir,
                                                                             const SequenceOptions& options) {
    Description d;
    d.layout = "visp-blender";
    d.frame_count = count_numbered_files(dir / "images", "", 4, ".jpg", 1);
    d.has_ground_truth = fs::is_directory(dir / "camera_poses");
    auto layout = std::make_shared<VispBlenderLayout>(dir);
    describe_visp_calibration(dir, options, *layout, d);
    if (options.blender_principal_point) {
      // Blender puts the principal point at the sensor's centre, the pixel-edge coordinate
      // (W/2, H/2); in ViSP's convention (pixel centres at integers) that is
      // ((W-1)/2, (H-1)/2), half a pixel left of and above the XML's W/2, H/2. Rendering the
      // ground truth shows it: the depth images match to 0.01 mm with the shift and are off
      // by 0.2-0.35 mm without (docs/accuracy.md).
      for (Intrinsics* k : {&d.color_intrinsics, &d.depth_intrinsics}) {
        k->pu -= 0.5;
        k->pv -= 0.5;
      }
    }
    if (d.has_ground_truth) {
      if (d.objects.size() != 1)
        fail(dir, "camera_poses/ holds the ground truth of one object, named after the top-level .cao file, but "
                  "found " + std::to_string(d.objects.size()) + " .cao files");
      layout->object_ = d.objects.front().name;
    }
    for (int i = 0; i < d.frame_count; ++i) {
      require_file(layout->depth_file(i), "depth image of frame " + std::to_string(i));
      if (d.has_ground_truth) require_file(layout->pose_file(i), "ground-truth pose of frame " + std::to_string(i));
    }
    return {d, layout};
  }

 private:
  fs::path dir_;
  std::string object_;
};

class VispRealsenseLayout : public Sequence::Layout {
 public:
  explicit VispRealsenseLayout(fs::path dir) : dir_(std::move(dir)) {}
  fs::path color_file(int i) const override { return dir_ / numbered("color_image_", i, 4, ".jpg"); }
  fs::path depth_file(int i) const override { return dir_ / numbered("depth_image_", i, 4, ".bin"); }
  cv::Mat read_depth(int i) const override { return read_realsense_bin_depth(depth_file(i)); }
  std::map<std::string, Pose> read_ground_truth(int) const override { return {}; }
  std::string size_origin() const override { return "size of the first frame"; }

  static std::pair<Description, std::shared_ptr<const Sequence::Layout>> open(const fs::path& dir,
                                                                             const SequenceOptions& options) {
    Description d;
    d.layout = "visp-realsense";
    d.frame_count = count_numbered_files(dir, "color_image_", 4, ".jpg", 0);
    auto layout = std::make_shared<VispRealsenseLayout>(dir);
    describe_visp_calibration(dir, options, *layout, d);
    for (int i = 0; i < d.frame_count; ++i)
      require_file(layout->depth_file(i), "depth file of frame " + std::to_string(i));
    return {d, layout};
  }

 private:
  fs::path dir_;
};

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

class IcgpLayout : public Sequence::Layout {
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

  static std::pair<Description, std::shared_ptr<const Sequence::Layout>> open(const fs::path& dir,
                                                                             const SequenceOptions&) {
    // Any keys: the writer adds some (the seed, the cameras' names) that reading needs not.
    const yaml::Map root(yaml::load_file((dir / "sequence.yaml").string()));
    root.required("format").as(yaml::Rule<std::string>{
        "icgp-sequence", [](const std::string& format) { return format == "icgp-sequence"; }});
    root.required("version").as(
        yaml::Rule<int>{"1 (the version this reader knows)", [](const int& version) { return version == 1; }});

    auto layout = std::make_shared<IcgpLayout>();
    layout->dir_ = dir;
    Description d;
    d.layout = "icgp";
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


Sequence Sequence::open(const std::string& dir_name, const SequenceOptions& options) {
  const fs::path dir(dir_name);
  if (!fs::exists(dir)) fail(dir, "sequence folder does not exist");
  if (!fs::is_directory(dir)) fail(dir, "not a folder");
  if (!(options.max_depth > 0.0)) fail(dir, "SequenceOptions::max_depth must be positive");
  if (!(options.frame_rate > 0.0)) fail(dir, "SequenceOptions::frame_rate must be positive");

  std::pair<Description, std::shared_ptr<const Layout>> opened;
  if (fs::is_regular_file(dir / "sequence.yaml"))
    opened = IcgpLayout::open(dir, options);
  else if (fs::is_directory(dir / "images") && fs::is_directory(dir / "depth"))
    opened = VispBlenderLayout::open(dir, options);
  else if (fs::is_regular_file(dir / "color_image_0000.jpg"))
    opened = VispRealsenseLayout::open(dir, options);
  else
    fail(dir, "unknown sequence layout: looked for sequence.yaml (icgp), images/ + depth/ folders (visp-blender) "
              "and color_image_0000.jpg (visp-realsense)");

  const Description& d = opened.first;
  check_principal_point(dir, d.color_intrinsics, "colour");
  if (!options.grey_without_depth) check_principal_point(dir, d.depth_intrinsics, "depth");
  if (d.stereo) check_principal_point(dir, d.stereo_intrinsics, "stereo colour");
  if (!d.depth_T_color.matrix().allFinite()) fail(dir, "the colour-to-depth transform is not finite");
  Sequence s;
  s.directory_ = dir.string();
  s.layout_ = d.layout;
  s.frame_count_ = d.frame_count;
  s.frame_rate_ = d.frame_rate;
  s.max_depth_ = options.max_depth;
  s.grey_without_depth_ = options.grey_without_depth;
  s.color_intrinsics_ = d.color_intrinsics;
  s.depth_intrinsics_ = d.depth_intrinsics;
  s.depth_T_color_ = d.depth_T_color;
  s.has_stereo_ = d.stereo;
  s.stereo_intrinsics_ = d.stereo_intrinsics;
  s.stereo_T_color_ = d.stereo_T_color;
  s.objects_ = d.objects;
  s.has_ground_truth_ = d.has_ground_truth;
  s.files_ = opened.second;
  return s;
}

Frame Sequence::load(int index) const {
  if (index < 0 || index >= frame_count_)
    throw std::out_of_range(directory_ + ": frame " + std::to_string(index) + " out of range [0, " +
                            std::to_string(frame_count_) + ")");
  Frame frame;
  frame.index = index;
  frame.timestamp = index / frame_rate_;

  const auto add_color = [&](const char* camera, const Intrinsics& intrinsics, const Pose& camera_T_color,
                              const fs::path& file, const char* what) {
    ColorImage color;
    color.camera = camera;
    color.intrinsics = intrinsics;
    color.camera_T_reference = camera_T_color;
    color.image = read_color_image(file);
    check_size(color.image, intrinsics, file, what, files_->size_origin());
    if (grey_without_depth_) cv::cvtColor(color.image, color.image, cv::COLOR_BGR2GRAY);
    frame.colors.push_back(std::move(color));
  };
  add_color(kColorCamera, color_intrinsics_, Pose(), files_->color_file(index), "colour image");
  if (has_stereo_)
    add_color(kStereoCamera, stereo_intrinsics_, stereo_T_color_, files_->stereo_color_file(index), "stereo colour image");
  frame.ground_truth = files_->read_ground_truth(index);
  frame.joint_ground_truth = files_->read_joint_truth(index);
  if (grey_without_depth_) return frame;

  DepthImage depth;
  depth.camera = kDepthCamera;
  depth.intrinsics = depth_intrinsics_;
  depth.camera_T_reference = depth_T_color_;
  depth.depth = files_->read_depth(index);
  check_size(depth.depth, depth_intrinsics_, files_->depth_file(index), "depth image", files_->size_origin());
  clear_invalid_depth(depth.depth, max_depth_);
  frame.depths.push_back(std::move(depth));
  return frame;
}

}  // namespace icgp
