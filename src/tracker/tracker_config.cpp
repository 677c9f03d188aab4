// SPDX-License-Identifier: GPL-2.0-or-later
// Tracker configuration files. Every parameter is one row of a field table (key, member,
// rule); the reader, its validation and the writer all walk the same tables.
#include "icgp/tracker/tracker_config.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <set>
#include <stdexcept>
#include <type_traits>

namespace icgp {
namespace {

/// Where a value sits, for error messages: the file and the dotted key path.
struct Location {
  std::string file;
  std::string key;  ///< empty: the whole document

  Location child(const std::string& name) const { return {file, key.empty() ? name : key + "." + name}; }
  [[noreturn]] void fail(const std::string& message) const {
    throw std::runtime_error(file + ": " + (key.empty() ? "" : key + ": ") + message);
  }
};

/// What a value must be; `expected` completes the error message "expected ...".
template <typename T>
struct Rule {
  const char* expected;
  bool (*ok)(const T&);
};

template <typename T>
bool any(const T&) {
  return true;
}

bool positive(double v) { return std::isfinite(v) && v > 0.0; }

const Rule<int> kPositiveInt{"a positive integer", [](const int& v) { return v > 0; }};
const Rule<int> kNonNegativeInt{"a non-negative integer", [](const int& v) { return v >= 0; }};
const Rule<double> kPositive{"a positive number", [](const double& v) { return positive(v); }};
const Rule<double> kNonNegative{"a non-negative number", [](const double& v) { return std::isfinite(v) && v >= 0.0; }};
const Rule<double> kFraction{"a number in [0, 1]", [](const double& v) { return v >= 0.0 && v <= 1.0; }};
const Rule<std::vector<int>> kPositiveInts{"a non-empty list of positive integers", [](const std::vector<int>& v) {
  return !v.empty() && std::all_of(v.begin(), v.end(), [](int x) { return x > 0; });
}};
const Rule<std::vector<double>> kPositives{"a non-empty list of positive numbers", [](const std::vector<double>& v) {
  return !v.empty() && std::all_of(v.begin(), v.end(), positive);
}};
const Rule<bool> kBool{"true or false", any<bool>};
const Rule<std::string> kString{"a string", any<std::string>};
const Rule<std::string> kName{"a non-empty string", [](const std::string& v) { return !v.empty(); }};

template <typename T>
T decode(const YAML::Node& node, const Rule<T>& rule, const Location& at) {
  T value{};
  try {
    // `key:` and `key: ~` mean an empty string (yaml-cpp would give "null").
    if (!std::is_same_v<T, std::string> || !node.IsNull()) value = node.as<T>();
  } catch (const YAML::Exception&) {
    at.fail(std::string("expected ") + rule.expected);
  }
  if (!rule.ok(value)) at.fail(std::string("expected ") + rule.expected);
  return value;
}

/// Shortest text that reads back as the same double, with a ".0" on whole numbers.
void emit(YAML::Emitter& out, double v) {
  char text[32];
  std::string s(text, std::to_chars(text, text + sizeof(text), v).ptr);
  if (s.find_first_not_of("-0123456789") == std::string::npos) s += ".0";
  out << s;
}

template <typename T>
void emit(YAML::Emitter& out, const T& v) {
  out << v;
}

template <typename T>
void emit(YAML::Emitter& out, const std::vector<T>& v) {
  out << YAML::Flow << YAML::BeginSeq;
  for (const T& x : v) emit(out, x);
  out << YAML::EndSeq;
}

/// One key of a section: reads its YAML value into S (validated) and writes it back.
template <typename S>
struct Field {
  std::string name;
  std::function<void(const YAML::Node&, S&, const Location&)> read;
  std::function<void(YAML::Emitter&, const S&)> write;
};

template <typename S>
using Fields = std::vector<Field<S>>;

template <typename S>
std::string key_list(const Fields<S>& fields) {
  std::string list;
  for (const Field<S>& f : fields) list += (list.empty() ? "" : ", ") + f.name;
  return list;
}

template <typename S>
void read_map(const YAML::Node& node, const Fields<S>& fields, S& s, const Location& at) {
  if (node.IsNull()) return;
  if (!node.IsMap()) at.fail("expected a map with the keys " + key_list(fields));
  std::set<std::string> seen;
  for (const auto& entry : node) {
    const std::string name = entry.first.Scalar();
    const Location key = at.child(name);
    const auto field = std::find_if(fields.begin(), fields.end(), [&](const Field<S>& f) { return f.name == name; });
    if (field == fields.end())
      key.fail("unknown key (valid keys" + (at.key.empty() ? "" : " of " + at.key) + ": " + key_list(fields) + ")");
    if (!seen.insert(name).second) key.fail("duplicate key");
    field->read(entry.second, s, key);
  }
}

template <typename S>
void write_map(YAML::Emitter& out, const Fields<S>& fields, const S& s) {
  out << YAML::BeginMap;
  for (const Field<S>& f : fields) {
    out << YAML::Key << f.name << YAML::Value;
    f.write(out, s);
  }
  out << YAML::EndMap;
}

/// A value member checked by `rule`.
template <typename S, typename T>
Field<S> field(const char* name, T S::*member, Rule<T> rule) {
  return {name, [member, rule](const YAML::Node& node, S& s, const Location& at) { s.*member = decode(node, rule, at); },
          [member](YAML::Emitter& out, const S& s) { emit(out, s.*member); }};
}

/// A struct member read and written as a nested map of `fields`.
template <typename S, typename T>
Field<S> section(const char* name, T S::*member, const Fields<T>& fields) {
  return {name,
          [member, &fields](const YAML::Node& node, S& s, const Location& at) { read_map(node, fields, s.*member, at); },
          [member, &fields](YAML::Emitter& out, const S& s) { write_map(out, fields, s.*member); }};
}

const Fields<TrackerParams> kTrackerFields = {
    field("n_corr_iterations", &TrackerParams::n_corr_iterations, kPositiveInt),
    field("n_update_iterations", &TrackerParams::n_update_iterations, kPositiveInt),
    field("tikhonov_rotation", &TrackerParams::tikhonov_rotation, kPositive),
    field("tikhonov_translation", &TrackerParams::tikhonov_translation, kPositive),
    field("quality_threshold", &TrackerParams::quality_threshold, kFraction),
};

const Fields<ViewpointModelParams> kModelFields = {
    field("n_divides", &ViewpointModelParams::n_divides,
          Rule<int>{"an integer from 0 to 6", [](const int& v) { return v >= 0 && v <= 6; }}),
    field("sphere_radius", &ViewpointModelParams::sphere_radius, kPositive),
    field("image_size", &ViewpointModelParams::image_size,
          Rule<int>{"an integer of at least 64", [](const int& v) { return v >= 64; }}),
    field("image_margin", &ViewpointModelParams::image_margin, kNonNegativeInt),
    field("n_points", &ViewpointModelParams::n_points, kPositiveInt),
    field("stride_depth_offset", &ViewpointModelParams::stride_depth_offset, kPositive),
    field("max_radius_depth_offset", &ViewpointModelParams::max_radius_depth_offset, kPositive),
    field("min_contour_length", &ViewpointModelParams::min_contour_length, kNonNegativeInt),
    field("normal_chord_offset", &ViewpointModelParams::normal_chord_offset, kPositiveInt),
    field("seed", &ViewpointModelParams::seed, Rule<std::uint64_t>{"a non-negative integer", any<std::uint64_t>}),
};

const Fields<NoiseParams> kNoiseFields = {
    field("estimate", &NoiseParams::estimate, kBool),
    field("robust", &NoiseParams::robust, kBool),
    field("floor", &NoiseParams::floor, kNonNegative),
    field("min_residuals", &NoiseParams::min_residuals, kPositiveInt),
    field("tukey_constant", &NoiseParams::tukey_constant, kPositive),
};

const Fields<RegionParams> kRegionFields = {
    field("color_camera", &RegionParams::color_camera, kName),
    field("depth_camera", &RegionParams::depth_camera, kString),
    field("n_lines_max", &RegionParams::n_lines_max, kPositiveInt),
    field("min_continuous_distance", &RegionParams::min_continuous_distance, kNonNegative),
    field("function_length", &RegionParams::function_length, kPositiveInt),
    field("distribution_length", &RegionParams::distribution_length, kPositiveInt),
    field("function_amplitude", &RegionParams::function_amplitude,
          Rule<double>{"a number between 0 and 0.5 (both excluded)", [](const double& v) { return v > 0.0 && v < 0.5; }}),
    field("function_slope", &RegionParams::function_slope, kNonNegative),
    field("learning_rate", &RegionParams::learning_rate, kPositive),
    field("n_global_iterations", &RegionParams::n_global_iterations, kNonNegativeInt),
    field("subpixel_posterior", &RegionParams::subpixel_posterior, kBool),
    field("scales", &RegionParams::scales, kPositiveInts),
    field("standard_deviations", &RegionParams::standard_deviations, kPositives),
    section("noise", &RegionParams::noise, kNoiseFields),
    field("n_histogram_bins", &RegionParams::n_histogram_bins,
          Rule<int>{"one of 2, 4, 8, 16, 32, 64", [](const int& v) { return v >= 2 && v <= 64 && (v & (v - 1)) == 0; }}),
    field("learning_rate_f", &RegionParams::learning_rate_f, kFraction),
    field("learning_rate_b", &RegionParams::learning_rate_b, kFraction),
    field("unconsidered_line_length", &RegionParams::unconsidered_line_length, kNonNegative),
    field("max_considered_line_length", &RegionParams::max_considered_line_length, kPositive),
    field("measure_occlusions", &RegionParams::measure_occlusions, kBool),
    field("occlusion_radius", &RegionParams::occlusion_radius, kNonNegative),
    field("occlusion_threshold", &RegionParams::occlusion_threshold, kNonNegative),
    field("n_unoccluded_iterations", &RegionParams::n_unoccluded_iterations, kNonNegativeInt),
    field("min_n_unoccluded_lines", &RegionParams::min_n_unoccluded_lines, kNonNegativeInt),
};

const Fields<DepthParams> kDepthFields = {
    field("depth_camera", &DepthParams::depth_camera, kName),
    field("n_points_max", &DepthParams::n_points_max, kPositiveInt),
    field("stride_length", &DepthParams::stride_length, kPositive),
    field("considered_distances", &DepthParams::considered_distances, kPositives),
    field("standard_deviations", &DepthParams::standard_deviations, kPositives),
    section("noise", &DepthParams::noise, kNoiseFields),
    field("measure_occlusions", &DepthParams::measure_occlusions, kBool),
    field("occlusion_radius", &DepthParams::occlusion_radius, kNonNegative),
    field("occlusion_threshold", &DepthParams::occlusion_threshold, kNonNegative),
    field("n_unoccluded_iterations", &DepthParams::n_unoccluded_iterations, kNonNegativeInt),
    field("min_n_unoccluded_points", &DepthParams::min_n_unoccluded_points, kNonNegativeInt),
};

const Fields<TextureParams> kTextureFields = {
    field("color_camera", &TextureParams::color_camera, kName),
    field("depth_camera", &TextureParams::depth_camera, kString),
    field("descriptor", &TextureParams::descriptor,
          Rule<std::string>{"one of orb, brisk, sift, akaze, freak, daisy, oriented_brief", [](const std::string& v) {
                              static const std::set<std::string> known = {"orb",   "brisk", "sift",          "akaze",
                                                                          "freak", "daisy", "oriented_brief"};
                              return known.count(v) > 0;
                            }}),
    field("focused_image_size", &TextureParams::focused_image_size,
          Rule<int>{"an integer of at least 64", [](const int& v) { return v >= 64; }}),
    field("orb_n_features", &TextureParams::orb_n_features, kPositiveInt),
    field("orb_n_levels", &TextureParams::orb_n_levels, kPositiveInt),
    field("orb_scale_factor", &TextureParams::orb_scale_factor,
          Rule<double>{"a number greater than 1", [](const double& v) { return std::isfinite(v) && v > 1.0; }}),
    field("sift_n_octave_layers", &TextureParams::sift_n_octave_layers, kPositiveInt),
    field("sift_contrast_threshold", &TextureParams::sift_contrast_threshold, kPositive),
    field("sift_edge_threshold", &TextureParams::sift_edge_threshold, kPositive),
    field("sift_sigma", &TextureParams::sift_sigma, kPositive),
    field("ratio_test", &TextureParams::ratio_test,
          Rule<double>{"a number in (0, 1]", [](const double& v) { return v > 0.0 && v <= 1.0; }}),
    field("keyframe_orientation_threshold_deg", &TextureParams::keyframe_orientation_threshold_deg, kPositive),
    field("keyframe_max_age", &TextureParams::keyframe_max_age, kNonNegativeInt),
    field("min_keyframe_points", &TextureParams::min_keyframe_points, kNonNegativeInt),
    field("tukey_norm_constant", &TextureParams::tukey_norm_constant, kPositive),
    field("standard_deviations", &TextureParams::standard_deviations, kPositives),
    section("noise", &TextureParams::noise, kNoiseFields),
    field("occlusion_radius", &TextureParams::occlusion_radius, kNonNegative),
    field("occlusion_threshold", &TextureParams::occlusion_threshold, kNonNegative),
};

bool valid_modalities(const std::vector<std::string>& names) {
  static const std::set<std::string> known = {"region", "depth", "texture"};
  const std::set<std::string> distinct(names.begin(), names.end());
  return !names.empty() && distinct.size() == names.size() &&
         std::includes(known.begin(), known.end(), distinct.begin(), distinct.end());
}

bool known_preset(const std::string& name) {
  const std::vector<std::string>& names = tracker_config_presets();
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string preset_list() {
  std::string list;
  for (const std::string& name : tracker_config_presets()) list += (list.empty() ? "" : ", ") + name;
  return list;
}

/// `preset` is read before every other key (load_tracker_config), so here it is only
/// checked and written.
const Fields<TrackerConfig> kConfigFields = {
    {"preset", [](const YAML::Node&, TrackerConfig&, const Location&) {},
     [](YAML::Emitter& out, const TrackerConfig& c) { emit(out, c.preset); }},
    section("tracker", &TrackerConfig::tracker, kTrackerFields),
    field("modalities", &TrackerConfig::modalities,
          Rule<std::vector<std::string>>{"a non-empty list of distinct names from region, depth, texture",
                                         valid_modalities}),
    section("region_model", &TrackerConfig::region_model, kModelFields),
    section("depth_model", &TrackerConfig::depth_model, kModelFields),
    section("region", &TrackerConfig::region, kRegionFields),
    section("depth", &TrackerConfig::depth, kDepthFields),
    section("texture", &TrackerConfig::texture, kTextureFields),
    field("regions", &TrackerConfig::regions,
          Rule<std::vector<std::string>>{"a list of region mesh files",
                                         [](const std::vector<std::string>& files) {
                                           return std::none_of(files.begin(), files.end(),
                                                               [](const std::string& f) { return f.empty(); });
                                         }}),
    field("cache_dir", &TrackerConfig::cache_dir, kString),
};

}  // namespace

const std::vector<std::string>& tracker_config_presets() {
  static const std::vector<std::string> names = {"default", "icg_reference"};
  return names;
}

TrackerConfig tracker_config_preset(const std::string& name) {
  if (!known_preset(name))
    throw std::invalid_argument("unknown tracker configuration preset '" + name + "' (known: " + preset_list() + ")");
  TrackerConfig config;
  config.preset = name;
  if (name == "icg_reference") {
    for (NoiseParams* noise : {&config.region.noise, &config.depth.noise, &config.texture.noise})
      noise->estimate = noise->robust = false;
    config.region.subpixel_posterior = false;
    config.texture.descriptor = "orb";
  }
  return config;
}

TrackerConfig load_tracker_config(const std::string& path) {
  const Location document{path, ""};
  std::error_code error;
  std::ifstream in(path);
  if (!std::filesystem::is_regular_file(path, error) || !in)
    document.fail(std::filesystem::exists(path, error) ? "cannot read the file" : "no such file");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};

  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    document.fail("line " + std::to_string(e.mark.line + 1) + ", column " + std::to_string(e.mark.column + 1) +
                  ": YAML syntax error: " + e.msg);
  }
  TrackerConfig config;
  if (root.IsMap() && root["preset"]) {
    const Location at = document.child("preset");
    const std::string name = decode(root["preset"], kName, at);
    if (!known_preset(name)) at.fail("expected one of " + preset_list() + " (got '" + name + "')");
    config = tracker_config_preset(name);
  }
  read_map(root, kConfigFields, config, document);
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  for (std::string& region : config.regions)
    if (std::filesystem::path(region).is_relative()) region = (folder / region).lexically_normal().string();
  return config;
}

std::string to_yaml(const TrackerConfig& config) {
  YAML::Emitter out;
  write_map(out, kConfigFields, config);
  return std::string(out.c_str()) + "\n";
}

}  // namespace icgp
