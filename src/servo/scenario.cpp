// SPDX-License-Identifier: GPL-2.0-or-later
// Servo scenario files. Every section is read through a Section, which rejects unknown and
// duplicate keys; every value through a small typed reader whose error says what was
// expected and what the file holds: "<file>: <field>: expected <what>, got <value>".
#include "icgp/servo/scenario.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <set>
#include <utility>

namespace icgp::servo {
namespace {

namespace fs = std::filesystem;

/// The value as the file wrote it, for error messages: numbers as they are, other text
/// quoted, lists in brackets.
std::string describe(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  if (node.IsScalar()) {
    double number = 0.0;
    const bool numeric = YAML::convert<double>::decode(node, number);
    return numeric ? node.Scalar() : "'" + node.Scalar() + "'";
  }
  if (node.IsSequence()) {
    std::string text;
    for (const auto& item : node) text += (text.empty() ? "" : ", ") + describe(item);
    return "[" + text + "]";
  }
  return "a map";
}

std::string join(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
  return text;
}

/// Where a value sits: the file and the dotted field path ("camera.noise.depth_dropout").
struct Location {
  std::string file;
  std::string key;  ///< empty: the whole document

  Location child(const std::string& name) const { return {file, key.empty() ? name : key + "." + name}; }
  Location element(std::size_t index) const { return {file, key + "[" + std::to_string(index) + "]"}; }
  [[noreturn]] void fail(const std::string& message) const {
    throw ScenarioError(file + ": " + (key.empty() ? "" : key + ": ") + message);
  }
};

/// A value of the file and where it is.
struct Value {
  YAML::Node node;
  Location at;

  [[noreturn]] void expected(const std::string& what) const { at.fail("expected " + what + ", got " + describe(node)); }
};

/// A map whose keys are all among `keys` (checked on construction). Empty (`key:`) = no keys.
class Section {
 public:
  Section(const Value& value, std::initializer_list<const char*> keys)
      : at_(value.at), keys_(keys.begin(), keys.end()) {
    if (value.node.IsNull()) return;
    if (!value.node.IsMap()) value.expected("a map with the keys " + join(keys_));
    std::set<std::string> seen;
    for (const auto& entry : value.node) {
      const std::string name = entry.first.IsScalar() ? entry.first.Scalar() : describe(entry.first);
      if (std::find(keys_.begin(), keys_.end(), name) == keys_.end())
        at_.child(name).fail("unknown key (expected one of " + join(keys_) + ")");
      if (!seen.insert(name).second) at_.child(name).fail("duplicate key");
      values_.emplace_back(name, entry.second);
    }
  }

  /// The value of `key`, if the file gives one.
  std::optional<Value> get(const std::string& key) const {
    for (const auto& [name, node] : values_)
      if (name == key) return Value{node, at_.child(key)};
    return std::nullopt;
  }
  Value required(const std::string& key) const {
    if (std::optional<Value> value = get(key)) return *value;
    at_.child(key).fail("required");
  }
  const Location& at() const { return at_; }

 private:
  Location at_;
  std::vector<std::string> keys_;
  std::vector<std::pair<std::string, YAML::Node>> values_;
};

/// What a number must be; `expected` completes "expected ...".
struct Rule {
  const char* expected;
  bool (*ok)(double);
};

const Rule kNumber{"a number", [](double v) { return std::isfinite(v); }};
const Rule kPositive{"a positive number", [](double v) { return std::isfinite(v) && v > 0.0; }};
const Rule kNonNegative{"a non-negative number", [](double v) { return std::isfinite(v) && v >= 0.0; }};
const Rule kProbability{"a number in [0, 1)", [](double v) { return v >= 0.0 && v < 1.0; }};
const Rule kFraction{"a number in [0, 1]", [](double v) { return v >= 0.0 && v <= 1.0; }};
const Rule kAngleUpTo90{"a number in (0, 90]", [](double v) { return v > 0.0 && v <= 90.0; }};

double number(const Value& v, const Rule& rule = kNumber) {
  double x = 0.0;
  if (!v.node.IsScalar() || !YAML::convert<double>::decode(v.node, x) || !rule.ok(x)) v.expected(rule.expected);
  return x;
}

int integer(const Value& v, int minimum) {
  int x = 0;
  if (!v.node.IsScalar() || !YAML::convert<int>::decode(v.node, x) || x < minimum)
    v.expected(minimum == 0 ? "a non-negative integer" : "a positive integer");
  return x;
}

bool boolean(const Value& v) {
  bool x = false;
  if (!v.node.IsScalar() || !YAML::convert<bool>::decode(v.node, x)) v.expected("true or false");
  return x;
}

/// A string; `key:` alone is the empty string.
std::string text(const Value& v, bool non_empty = false) {
  if (v.node.IsNull() && !non_empty) return "";
  if (!v.node.IsScalar() || (non_empty && v.node.Scalar().empty()))
    v.expected(non_empty ? "a non-empty string" : "a string");
  return v.node.Scalar();
}

/// A list of exactly N numbers, each following `rule`.
template <int N>
Eigen::Matrix<double, N, 1> numbers(const Value& v, const Rule& rule = kNumber) {
  const std::string what = "a list of " + std::to_string(N) + " " +
                           (&rule == &kNumber ? std::string("numbers") : std::string(rule.expected).substr(2) + "s");
  if (!v.node.IsSequence() || v.node.size() != static_cast<std::size_t>(N)) v.expected(what);
  Eigen::Matrix<double, N, 1> x;
  for (int i = 0; i < N; ++i)
    if (!v.node[i].IsScalar() || !YAML::convert<double>::decode(v.node[i], x[i]) || !rule.ok(x[i])) v.expected(what);
  return x;
}

/// One of the names of `options`.
template <typename E>
E choice(const Value& v, const std::vector<std::pair<std::string, E>>& options) {
  std::vector<std::string> names;
  for (const auto& [name, value] : options) {
    if (v.node.IsScalar() && v.node.Scalar() == name) return value;
    names.push_back(name);
  }
  v.expected("one of " + join(names));
}

/// {t: [x, y, z] metres, r_deg: [ux, uy, uz] θu degrees}.
Pose pose(const Value& v) {
  const Section s(v, {"t", "r_deg"});
  const Eigen::Vector3d t = numbers<3>(s.required("t"));
  const Eigen::Vector3d r = numbers<3>(s.required("r_deg")) * kDegree;
  return Pose::from_rotation_vector(r, t);
}

/// A camera-object pose: the object must be in front of the camera.
Pose object_pose(const Value& v) {
  const Pose cMo = pose(v);
  if (!(cMo.translation().z() > 0.0)) {
    const Value t = Section(v, {"t", "r_deg"}).required("t");
    t.at.fail("the object must be in front of the camera (z > 0), got " + describe(t.node));
  }
  return cMo;
}

/// {width, height, focal} or {fu, fv, pu, pv, width, height}. Keys not given keep the value
/// of `base`, except the principal point, which is the image centre unless given.
Intrinsics intrinsics(const Value& v, const Intrinsics& base) {
  const Section s(v, {"width", "height", "focal", "fu", "fv", "pu", "pv"});
  Intrinsics k = base;
  if (auto x = s.get("width")) k.width = integer(*x, 1);
  if (auto x = s.get("height")) k.height = integer(*x, 1);
  if (auto x = s.get("focal")) {
    if (s.get("fu") || s.get("fv")) x->at.fail("give either focal or fu and fv, not both");
    k.fu = k.fv = number(*x, kPositive);
  }
  if (auto x = s.get("fu")) k.fu = number(*x, kPositive);
  if (auto x = s.get("fv")) k.fv = number(*x, kPositive);
  const Intrinsics centred = Intrinsics::centred(k.width, k.height, 1.0);
  k.pu = s.get("pu") ? number(*s.get("pu")) : centred.pu;
  k.pv = s.get("pv") ? number(*s.get("pv")) : centred.pv;
  return k;
}

/// A file named relative to the scenario's folder (or absolute) that must exist.
std::string existing_file(const Value& v, const fs::path& scenario_dir) {
  const std::string reference = text(v, true);
  const fs::path file = (scenario_dir / reference).lexically_normal();
  std::error_code error;
  if (!fs::is_regular_file(file, error)) v.expected("an existing file (tried " + file.string() + ")");
  return file.string();
}

/// The model candidates of resolve_model_path, in order; the first existing one wins.
std::vector<fs::path> model_candidates(const std::string& reference, const std::string& scenario_dir,
                                       const std::string& models_dir) {
  std::vector<fs::path> candidates;
  if (fs::path(reference).is_relative() && !models_dir.empty()) {
    candidates.push_back(fs::path(models_dir) / reference / (reference + ".obj"));
    candidates.push_back(fs::path(models_dir) / reference / "object.obj");
  }
  candidates.push_back(fs::path(scenario_dir) / reference);
  for (fs::path& candidate : candidates) candidate = candidate.lexically_normal();
  return candidates;
}

std::optional<std::string> find_model(const std::vector<fs::path>& candidates) {
  std::error_code error;
  for (const fs::path& candidate : candidates)
    if (fs::is_regular_file(candidate, error)) return candidate.string();
  return std::nullopt;
}

std::string tried(const std::vector<fs::path>& candidates) {
  std::vector<std::string> names;
  for (const fs::path& candidate : candidates) names.push_back(candidate.string());
  return "tried " + join(names);
}

std::string model(const Value& v, const std::string& scenario_dir, const std::string& models_dir) {
  const std::string reference = text(v, true);
  const std::vector<fs::path> candidates = model_candidates(reference, scenario_dir, models_dir);
  if (std::optional<std::string> file = find_model(candidates)) return *file;
  v.expected("a model folder of " + models_dir + " or an existing mesh file (" + tried(candidates) + ")");
}

// ---- Sections ---------------------------------------------------------------------------

void read_arm(const Value& v, ArmSpec& arm) {
  const Section s(v, {"initial_joints_deg", "eMo"});
  if (auto x = s.get("initial_joints_deg")) arm.initial_joints = numbers<6>(*x) * kDegree;
  if (auto x = s.get("eMo")) arm.eMo = pose(*x);
}

void read_object(const Value& v, ObjectSpec& object, const std::string& scenario_dir, const std::string& models_dir) {
  const Section s(v, {"model", "regions", "motion"});
  object.model = model(s.required("model"), scenario_dir, models_dir);
  if (auto x = s.get("regions")) {
    if (!x->node.IsSequence()) x->expected("a list of region meshes");
    for (std::size_t i = 0; i < x->node.size(); ++i)
      object.regions.push_back(model({x->node[i], x->at.element(i)}, scenario_dir, models_dir));
  }
  if (auto x = s.get("motion")) {
    const Section motion(*x, {"velocity", "start", "duration"});
    if (auto y = motion.get("velocity")) object.linear_velocity = numbers<3>(*y);
    if (auto y = motion.get("start")) object.motion_start = number(*y, kNonNegative);
    if (auto y = motion.get("duration")) object.motion_duration = number(*y, kNonNegative);
  }
}

OccluderSpec read_occluder(const Value& v) {
  const Section s(v, {"size", "start_position", "velocity", "start"});
  OccluderSpec occluder;
  if (auto x = s.get("size")) occluder.size = numbers<3>(*x, kNonNegative);
  if (auto x = s.get("start_position")) occluder.start_position_in_camera = numbers<3>(*x);
  if (auto x = s.get("velocity")) occluder.velocity_in_camera = numbers<3>(*x);
  if (auto x = s.get("start")) occluder.start = number(*x, kNonNegative);
  return occluder;
}

void read_background(const Value& v, BackgroundSpec& background, const fs::path& scenario_dir) {
  const Section s(v, {"enabled", "texture", "distance"});
  if (auto x = s.get("enabled")) background.enabled = boolean(*x);
  if (auto x = s.get("texture"))
    if (!x->node.IsNull()) background.texture = existing_file(*x, scenario_dir);
  if (auto x = s.get("distance")) background.distance = number(*x, kNonNegative);
}

void read_lighting(const Value& v, LightingSpec& lighting) {
  const Section s(v, {"direction", "ambient", "diffuse"});
  if (auto x = s.get("direction")) {
    lighting.direction_in_camera = numbers<3>(*x);
    if (!(lighting.direction_in_camera.norm() > 0.0)) x->expected("a non-zero direction");
  }
  if (auto x = s.get("ambient")) lighting.ambient = number(*x, kFraction);
  if (auto x = s.get("diffuse")) lighting.diffuse = number(*x, kFraction);
}

void read_noise(const Value& v, NoiseSpec& noise) {
  const Section s(v, {"color_sigma", "depth_sigma_at_1m", "depth_dropout", "grazing_angle_deg", "edge_dropout_px",
                      "motion_blur", "frame_drop"});
  if (auto x = s.get("color_sigma")) noise.color_sigma = number(*x, kNonNegative);
  if (auto x = s.get("depth_sigma_at_1m")) noise.depth_sigma_at_1m = number(*x, kNonNegative);
  if (auto x = s.get("depth_dropout")) noise.depth_dropout = number(*x, kProbability);
  if (auto x = s.get("grazing_angle_deg")) noise.grazing_angle_deg = number(*x, kAngleUpTo90);
  if (auto x = s.get("edge_dropout_px")) noise.edge_dropout_px = integer(*x, 0);
  if (auto x = s.get("motion_blur")) noise.motion_blur = number(*x, kFraction);
  if (auto x = s.get("frame_drop")) noise.frame_drop = number(*x, kProbability);
}

void read_camera(const Value& v, CameraSpec& camera) {
  const Section s(v, {"color", "depth", "depth_T_color", "rate_hz", "noise"});
  if (auto x = s.get("color")) camera.color = intrinsics(*x, camera.color);
  camera.depth = camera.color;
  if (auto x = s.get("depth")) camera.depth = intrinsics(*x, camera.color);
  if (auto x = s.get("depth_T_color")) camera.depth_T_color = pose(*x);
  if (auto x = s.get("rate_hz")) camera.rate_hz = number(*x, kPositive);
  if (auto x = s.get("noise")) read_noise(*x, camera.noise);
}

void read_tracker(const Value& v, TrackerSpec& tracker, const fs::path& scenario_dir) {
  const Section s(v, {"type", "modalities", "config", "visp_configuration"});
  if (auto x = s.get("type"))
    tracker.kind = choice<TrackerKind>(
        *x, {{"icgp", TrackerKind::kIcgp}, {"visp", TrackerKind::kVisp}, {"oracle", TrackerKind::kOracle}});
  if (auto x = s.get("modalities")) {
    const std::string what = "a non-empty list of distinct names from region, depth, texture";
    if (!x->node.IsSequence() || x->node.size() == 0) x->expected(what);
    for (const auto& item : x->node) {
      const std::string name = item.IsScalar() ? item.Scalar() : "";
      const bool known = name == "region" || name == "depth" || name == "texture";
      if (!known || std::count(tracker.modalities.begin(), tracker.modalities.end(), name) > 0) x->expected(what);
      tracker.modalities.push_back(name);
    }
  }
  if (auto x = s.get("config"))
    if (!x->node.IsNull()) tracker.config = existing_file(*x, scenario_dir);
  if (auto x = s.get("visp_configuration")) {
    const std::vector<std::string> names = {"edge + dense depth", "KLT + dense depth", "edge + KLT + dense depth",
                                            "edge + KLT (no depth)"};
    std::vector<std::pair<std::string, std::string>> options;
    for (const std::string& name : names) options.emplace_back(name, name);
    tracker.visp_configuration = choice<std::string>(*x, options);
  }
}

void read_gain(const Value& v, GainSpec& gain) {
  if (v.node.IsScalar()) {
    gain.at_zero = gain.at_infinity = number(v, kPositive);
    return;
  }
  if (!v.node.IsMap()) v.expected("a positive number or a map with the keys at_zero, at_infinity, slope_at_zero");
  const Section s(v, {"at_zero", "at_infinity", "slope_at_zero"});
  if (auto x = s.get("at_zero")) gain.at_zero = number(*x, kPositive);
  if (auto x = s.get("at_infinity")) gain.at_infinity = number(*x, kPositive);
  if (auto x = s.get("slope_at_zero")) gain.slope_at_zero = number(*x, kPositive);
}

void read_control(const Value& v, ControlSpec& control) {
  const Section s(v, {"law", "gain", "max_linear_velocity", "max_angular_velocity_deg", "max_joint_velocity_deg"});
  if (auto x = s.get("law"))
    control.law = choice<ControlLawKind>(*x, {{"pbvs", ControlLawKind::kPbvs}, {"ibvs", ControlLawKind::kIbvs}});
  if (auto x = s.get("gain")) read_gain(*x, control.gain);
  if (auto x = s.get("max_linear_velocity")) control.max_linear_velocity = number(*x, kPositive);
  if (auto x = s.get("max_angular_velocity_deg")) control.max_angular_velocity = number(*x, kPositive) * kDegree;
  if (auto x = s.get("max_joint_velocity_deg")) control.max_joint_velocity = number(*x, kPositive) * kDegree;
}

void read_stop(const Value& v, StopSpec& stop) {
  const Section s(v, {"translation_mm", "rotation_deg", "settle_time", "max_time"});
  if (auto x = s.get("translation_mm")) stop.converged_translation = number(*x, kNonNegative) * 1e-3;
  if (auto x = s.get("rotation_deg")) stop.converged_rotation = number(*x, kNonNegative) * kDegree;
  if (auto x = s.get("settle_time")) stop.settle_time = number(*x, kNonNegative);
  if (auto x = s.get("max_time")) stop.max_time = number(*x, kPositive);
}

void read_trials(const Value& v, TrialSpec& trials) {
  const Section s(v, {"translation_mm", "rotation_deg"});
  if (auto x = s.get("translation_mm")) trials.translation = number(*x, kNonNegative) * 1e-3;
  if (auto x = s.get("rotation_deg")) trials.rotation = number(*x, kNonNegative) * kDegree;
}

}  // namespace

std::string resolve_model_path(const std::string& reference, const std::string& scenario_dir,
                               const std::string& models_dir) {
  if (reference.empty()) throw ScenarioError("empty model reference");
  const std::vector<fs::path> candidates = model_candidates(reference, scenario_dir, models_dir);
  if (std::optional<std::string> file = find_model(candidates)) return *file;
  throw ScenarioError("'" + reference + "': no such model (" + tried(candidates) + ")");
}

Scenario load_scenario(const std::string& path, const std::string& models_dir) {
  const Location document{path, ""};
  std::error_code error;
  if (!fs::exists(path, error)) throw ScenarioError(path + ": no such scenario file");
  std::ifstream in(path);
  if (!fs::is_regular_file(path, error) || !in) document.fail("cannot read the scenario file");
  const std::string content{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};

  YAML::Node root;
  try {
    root = YAML::Load(content);
  } catch (const YAML::ParserException& e) {
    document.fail("line " + std::to_string(e.mark.line + 1) + ", column " + std::to_string(e.mark.column + 1) +
                  ": YAML syntax error: " + e.msg);
  }

  const fs::path folder = fs::path(path).parent_path();
  const Section s({root, document}, {"name", "description", "robot", "arm", "object", "occluder", "background",
                                     "lighting", "camera", "start", "desired", "tracker", "control", "stop", "trials", "seed"});
  Scenario scenario;
  scenario.file = path;
  scenario.name = fs::path(path).stem().string();
  if (auto x = s.get("name")) scenario.name = text(*x, true);
  if (auto x = s.get("description")) scenario.description = text(*x);
  if (auto x = s.get("robot"))
    scenario.robot = choice<RobotKind>(*x, {{"free_flying", RobotKind::kFreeFlyingCamera},
                                            {"viper850_eye_in_hand", RobotKind::kViper850EyeInHand},
                                            {"viper850_eye_to_hand", RobotKind::kViper850EyeToHand}});
  if (auto x = s.get("arm")) read_arm(*x, scenario.arm);
  read_object(s.required("object"), scenario.object, folder.string(), models_dir);
  if (auto x = s.get("occluder")) scenario.occluder = read_occluder(*x);
  if (auto x = s.get("background")) read_background(*x, scenario.background, folder);
  if (auto x = s.get("lighting")) read_lighting(*x, scenario.lighting);
  if (auto x = s.get("camera")) read_camera(*x, scenario.camera);
  scenario.initial_cMo = object_pose(s.required("start"));
  scenario.desired_cMo = object_pose(s.required("desired"));
  if (auto x = s.get("tracker")) read_tracker(*x, scenario.tracker, folder);
  if (auto x = s.get("control")) read_control(*x, scenario.control);
  if (auto x = s.get("stop")) read_stop(*x, scenario.stop);
  if (auto x = s.get("trials")) read_trials(*x, scenario.trials);
  if (auto x = s.get("seed")) {
    unsigned seed = 0;
    if (!x->node.IsScalar() || !YAML::convert<unsigned>::decode(x->node, seed)) x->expected("a non-negative integer");
    scenario.seed = seed;
  }
  return scenario;
}

}  // namespace icgp::servo
