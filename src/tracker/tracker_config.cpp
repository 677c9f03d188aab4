// SPDX-License-Identifier: GPL-2.0-or-later
// Tracker configuration files. Every parameter is one row of a field table (key, member,
// rule); the reader, the writer and the check of a configuration made in code all walk the
// same tables.
#include "icgp/tracker/tracker_config.h"

#include "body_config_yaml.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>

#include "icgp/base/resource_limits.h"
#include "icgp/io/yaml_reader.h"
#include "icgp/modality/cue_kind.h"
#include "icgp/tracker/cue_registry.h"

namespace icgp {
namespace {

using yaml::any;
using yaml::kBool;
using yaml::kFraction;
using yaml::kNonEmptyString;
using yaml::kNonNegative;
using yaml::kPositive;
using yaml::kString;
using yaml::Rule;

/// The tracker configuration's wording, which docs/configuration.md quotes: "expected …,
/// got <value>", unknown keys listed as "valid keys of <section>".
const yaml::Wording kWording{"file", /*echo_value=*/true, yaml::KeyListWording::kValidKeysOf};

/// An integer from Lo to Hi. The upper bounds of counts keep a file from asking for
/// unbounded memory or time (docs/configuration.md lists them); they are far above any
/// value that tracks better.
template <int Lo, int Hi>
Rule<int> int_range() {
  static const std::string text = "an integer from " + std::to_string(Lo) + " to " + std::to_string(Hi);
  return {text.c_str(), [](const int& v) { return v >= Lo && v <= Hi; }};
}

/// Lists indexed by the correspondence iteration need no more entries than iterations.
constexpr std::size_t kMaxIterationListSize = 100;

bool positive(double v) { return std::isfinite(v) && v > 0.0; }

const Rule<std::vector<int>> kScales{"a list of 1 to 100 integers from 1 to 64", [](const std::vector<int>& v) {
  return !v.empty() && v.size() <= kMaxIterationListSize &&
         std::all_of(v.begin(), v.end(), [](int x) { return x > 0 && x <= 64; });
}};
const Rule<std::vector<double>> kPositives{"a list of 1 to 100 positive numbers", [](const std::vector<double>& v) {
  return !v.empty() && v.size() <= kMaxIterationListSize && std::all_of(v.begin(), v.end(), positive);
}};
const Rule<double> kSphereRadius{"a positive number of at most 100 (metres)",
                                 [](const double& v) { return positive(v) && v <= 100.0; }};

/// Shortest text that reads back as the same double, with a ".0" on whole numbers.
void emit(YAML::Emitter& out, double v) {
  std::string s = yaml::exact_number(v);
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

/// One key of a section: reads its YAML value into S (validated), writes it back, and
/// checks the value a program set by the same rule, failing at the section's `at`.
template <typename S>
struct Field {
  std::string name;
  std::function<void(const yaml::Value&, S&)> read;
  std::function<void(YAML::Emitter&, const S&)> write;
  std::function<void(const S&, const yaml::Location& at)> check;
};

/// Fails as reading `value` from a file would: "<key>: expected <rule>, got <value>".
template <typename T>
void check_value(const T& value, const Rule<T>& rule, const yaml::Location& at) {
  if (!rule.ok(value)) yaml::Value{YAML::Node(value), at}.expected(rule.expected);
}

template <typename S>
using Fields = std::vector<Field<S>>;

/// Reads the keys of a section the file gives, each by its field, in the file's order.
template <typename S>
void read_map(const yaml::Value& value, const Fields<S>& fields, S& s) {
  std::vector<std::string> names;
  for (const Field<S>& f : fields) names.push_back(f.name);
  yaml::for_each_entry(value, names, [&](const std::string& name, const yaml::Value& v) {
    std::find_if(fields.begin(), fields.end(), [&](const Field<S>& f) { return f.name == name; })->read(v, s);
  });
}

template <typename S>
void check_map(const Fields<S>& fields, const S& s, const yaml::Location& at) {
  for (const Field<S>& f : fields) f.check(s, at);
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
  return {name, [member, rule](const yaml::Value& v, S& s) { s.*member = v.as(rule); },
          [member](YAML::Emitter& out, const S& s) { emit(out, s.*member); },
          [name, member, rule](const S& s, const yaml::Location& at) { check_value(s.*member, rule, at.child(name)); }};
}

/// A member of a struct member under a key of the section itself (the flat keys of
/// OcclusionParams: region.occlusion_radius is RegionParams::occlusion.radius).
template <typename S, typename M, typename T>
Field<S> field(const char* name, M S::*outer, T M::*inner, Rule<T> rule) {
  return {name, [outer, inner, rule](const yaml::Value& v, S& s) { (s.*outer).*inner = v.as(rule); },
          [outer, inner](YAML::Emitter& out, const S& s) { emit(out, (s.*outer).*inner); },
          [name, outer, inner, rule](const S& s, const yaml::Location& at) {
            check_value((s.*outer).*inner, rule, at.child(name));
          }};
}

/// A struct member read and written as a nested map of `fields`.
template <typename S, typename T>
Field<S> section(const char* name, T S::*member, const Fields<T>& fields) {
  return {name, [member, &fields](const yaml::Value& v, S& s) { read_map(v, fields, s.*member); },
          [member, &fields](YAML::Emitter& out, const S& s) { write_map(out, fields, s.*member); },
          [name, member, &fields](const S& s, const yaml::Location& at) { check_map(fields, s.*member, at.child(name)); }};
}

/// An enumerator member, written and read by its name (to_string).
template <typename S, typename E, std::size_t N>
Field<S> choice(const char* name, E S::*member, const std::array<E, N>& values) {
  return {name, [member, values](const yaml::Value& v, S& s) { s.*member = v.choice(yaml::named(values)); },
          [member](YAML::Emitter& out, const S& s) { emit(out, to_string(s.*member)); },
          [](const S&, const yaml::Location&) {}};  // an enumerator set in code is one of its values
}

const Fields<TrackerParams> kTrackerFields = {
    field("n_corr_iterations", &TrackerParams::n_corr_iterations, int_range<1, 100>()),
    field("n_update_iterations", &TrackerParams::n_update_iterations, int_range<1, 100>()),
    field("tikhonov_rotation", &TrackerParams::regularisation, &OptimizerParams::tikhonov_rotation, kPositive),
    field("tikhonov_translation", &TrackerParams::regularisation, &OptimizerParams::tikhonov_translation, kPositive),
    field("quality_threshold", &TrackerParams::quality_threshold, kFraction),
};

const Fields<DetectionParams> kDetectionFields = {
    field("recovery", &DetectionParams::recovery, kBool),
    field("global_search_interval", &DetectionParams::global_search_interval, int_range<1, 1000>()),
    field("view_divides", &DetectionParams::view_divides, int_range<0, 3>()),
    field("roll_step_deg", &DetectionParams::roll_step_deg,
          Rule<double>{"a number from 5 to 180 (degrees)", [](const double& v) { return v >= 5.0 && v <= 180.0; }}),
    field("min_distance", &DetectionParams::min_distance, kSphereRadius),
    field("max_distance", &DetectionParams::max_distance, kSphereRadius),
    field("template_points", &DetectionParams::template_points, int_range<8, 200>()),
    field("hypotheses", &DetectionParams::hypotheses, int_range<1, 50>()),
    field("accept_quality", &DetectionParams::accept_quality, kFraction),
};

const Fields<ViewpointModelParams> kModelFields = {
    field("n_divides", &ViewpointModelParams::n_divides,
          Rule<int>{"an integer from 0 to 6", [](const int& v) { return v >= 0 && v <= 6; }}),
    field("sphere_radius", &ViewpointModelParams::sphere_radius, kSphereRadius),
    field("image_size", &ViewpointModelParams::image_size, int_range<64, ViewpointModelParams::kMaxImageSize>()),
    field("image_margin", &ViewpointModelParams::image_margin, int_range<0, ViewpointModelParams::kMaxImageSize / 2>()),
    field("n_points", &ViewpointModelParams::n_points, int_range<1, ViewpointModelParams::kMaxPoints>()),
    field("stride_depth_offset", &ViewpointModelParams::stride_depth_offset, kPositive),
    field("max_radius_depth_offset", &ViewpointModelParams::max_radius_depth_offset, kPositive),
    field("min_contour_length", &ViewpointModelParams::min_contour_length, int_range<0, 100000>()),
    field("normal_chord_offset", &ViewpointModelParams::normal_chord_offset, int_range<1, 100>()),
    field("seed", &ViewpointModelParams::seed, Rule<std::uint64_t>{"a non-negative integer", any<std::uint64_t>}),
};

const Fields<NoiseParams> kNoiseFields = {
    field("estimate", &NoiseParams::estimate, kBool),
    field("robust", &NoiseParams::robust, kBool),
    field("floor", &NoiseParams::floor, kNonNegative),
    field("min_residuals", &NoiseParams::min_residuals, int_range<1, 1000000>()),
    field("tukey_constant", &NoiseParams::tukey_constant, kPositive),
};

const Fields<RegionParams> kRegionFields = {
    field("color_camera", &RegionParams::color_camera, kNonEmptyString),
    field("depth_camera", &RegionParams::depth_camera, kString),
    field("n_lines_max", &RegionParams::n_lines_max, int_range<1, 5000>()),
    field("min_continuous_distance", &RegionParams::min_continuous_distance, kNonNegative),
    field("function_length", &RegionParams::function_length, int_range<1, 100>()),
    field("distribution_length", &RegionParams::distribution_length, int_range<1, 100>()),
    field("function_amplitude", &RegionParams::function_amplitude,
          Rule<double>{"a number between 0 and 0.5 (both excluded)", [](const double& v) { return v > 0.0 && v < 0.5; }}),
    field("function_slope", &RegionParams::function_slope, kNonNegative),
    field("learning_rate", &RegionParams::learning_rate, kPositive),
    field("n_global_iterations", &RegionParams::n_global_iterations, int_range<0, 100>()),
    field("subpixel_posterior", &RegionParams::subpixel_posterior, kBool),
    field("scales", &RegionParams::scales, kScales),
    field("standard_deviations", &RegionParams::standard_deviations, kPositives),
    section("noise", &RegionParams::noise, kNoiseFields),
    field("n_histogram_bins", &RegionParams::n_histogram_bins,
          Rule<int>{"one of 2, 4, 8, 16, 32, 64", [](const int& v) { return v >= 2 && v <= 64 && (v & (v - 1)) == 0; }}),
    field("learning_rate_f", &RegionParams::learning_rate_f, kFraction),
    field("learning_rate_b", &RegionParams::learning_rate_b, kFraction),
    field("unconsidered_line_length", &RegionParams::unconsidered_line_length, kNonNegative),
    field("max_considered_line_length", &RegionParams::max_considered_line_length, kPositive),
    field("measure_occlusions", &RegionParams::occlusion, &OcclusionParams::measure, kBool),
    field("occlusion_radius", &RegionParams::occlusion, &OcclusionParams::radius, kNonNegative),
    field("occlusion_threshold", &RegionParams::occlusion, &OcclusionParams::threshold, kNonNegative),
    field("model_occlusions", &RegionParams::occlusion, &OcclusionParams::model, kBool),
    field("modeled_occlusion_radius", &RegionParams::occlusion, &OcclusionParams::modeled_radius, kNonNegative),
    field("modeled_occlusion_threshold", &RegionParams::occlusion, &OcclusionParams::modeled_threshold, kNonNegative),
    field("occlusion_render_size", &RegionParams::occlusion, &OcclusionParams::render_size, int_range<16, 2048>()),
    field("region_checking", &RegionParams::region_checking, kBool),
    field("n_unoccluded_iterations", &RegionParams::n_unoccluded_iterations, int_range<0, 1000>()),
    field("min_n_unoccluded_lines", &RegionParams::min_n_unoccluded_lines, int_range<0, 5000>()),
};

const Fields<DepthParams> kDepthFields = {
    field("depth_camera", &DepthParams::depth_camera, kNonEmptyString),
    field("n_points_max", &DepthParams::n_points_max, int_range<1, 5000>()),
    field("stride_length", &DepthParams::stride_length, kPositive),
    field("considered_distances", &DepthParams::considered_distances, kPositives),
    field("standard_deviations", &DepthParams::standard_deviations, kPositives),
    section("noise", &DepthParams::noise, kNoiseFields),
    field("measure_occlusions", &DepthParams::occlusion, &OcclusionParams::measure, kBool),
    field("occlusion_radius", &DepthParams::occlusion, &OcclusionParams::radius, kNonNegative),
    field("occlusion_threshold", &DepthParams::occlusion, &OcclusionParams::threshold, kNonNegative),
    field("model_occlusions", &DepthParams::occlusion, &OcclusionParams::model, kBool),
    field("modeled_occlusion_radius", &DepthParams::occlusion, &OcclusionParams::modeled_radius, kNonNegative),
    field("modeled_occlusion_threshold", &DepthParams::occlusion, &OcclusionParams::modeled_threshold, kNonNegative),
    field("occlusion_render_size", &DepthParams::occlusion, &OcclusionParams::render_size, int_range<16, 2048>()),
    field("n_unoccluded_iterations", &DepthParams::n_unoccluded_iterations, int_range<0, 1000>()),
    field("min_n_unoccluded_points", &DepthParams::min_n_unoccluded_points, int_range<0, 5000>()),
    field("dense_when_only_cue", &DepthParams::dense, &DenseDepthParams::when_only_cue, kBool),
    field("dense_step_x", &DepthParams::dense, &DenseDepthParams::step_x, int_range<0, kMaxImageSide>()),
    field("dense_step_y", &DepthParams::dense, &DenseDepthParams::step_y, int_range<0, kMaxImageSide>()),
    field("dense_n_points_max", &DepthParams::dense, &DenseDepthParams::n_points_max, int_range<1, 1000000>()),
};

const Fields<TextureParams> kTextureFields = {
    field("color_camera", &TextureParams::color_camera, kNonEmptyString),
    field("depth_camera", &TextureParams::depth_camera, kString),
    choice("descriptor", &TextureParams::descriptor, kDescriptors),
    field("focused_image_size", &TextureParams::focused_image_size, int_range<64, ViewpointModelParams::kMaxImageSize>()),
    field("orb_n_features", &TextureParams::orb_n_features, int_range<1, 100000>()),
    field("orb_n_levels", &TextureParams::orb_n_levels, int_range<1, 32>()),
    field("orb_scale_factor", &TextureParams::orb_scale_factor,
          Rule<double>{"a number greater than 1", [](const double& v) { return std::isfinite(v) && v > 1.0; }}),
    field("sift_n_octave_layers", &TextureParams::sift_n_octave_layers, int_range<1, 16>()),
    field("sift_contrast_threshold", &TextureParams::sift_contrast_threshold, kPositive),
    field("sift_edge_threshold", &TextureParams::sift_edge_threshold, kPositive),
    field("sift_sigma", &TextureParams::sift_sigma, kPositive),
    field("ratio_test", &TextureParams::ratio_test,
          Rule<double>{"a number in (0, 1]", [](const double& v) { return v > 0.0 && v <= 1.0; }}),
    field("keyframe_orientation_threshold_deg", &TextureParams::keyframe_orientation_threshold_deg, kPositive),
    field("keyframe_max_age", &TextureParams::keyframe_max_age, int_range<0, 1000000>()),
    field("min_keyframe_points", &TextureParams::min_keyframe_points, int_range<0, 100000>()),
    field("tukey_norm_constant", &TextureParams::tukey_norm_constant, kPositive),
    field("standard_deviations", &TextureParams::standard_deviations, kPositives),
    section("noise", &TextureParams::noise, kNoiseFields),
    field("occlusion_radius", &TextureParams::occlusion, &OcclusionParams::radius, kNonNegative),
    field("occlusion_threshold", &TextureParams::occlusion, &OcclusionParams::threshold, kNonNegative),
    field("model_occlusions", &TextureParams::occlusion, &OcclusionParams::model, kBool),
    field("modeled_occlusion_radius", &TextureParams::occlusion, &OcclusionParams::modeled_radius, kNonNegative),
    field("modeled_occlusion_threshold", &TextureParams::occlusion, &OcclusionParams::modeled_threshold, kNonNegative),
    field("occlusion_render_size", &TextureParams::occlusion, &OcclusionParams::render_size, int_range<16, 2048>()),
};

const Fields<FlowParams> kFlowFields = {
    field("max_features", &FlowParams::max_features, int_range<0, 100000>()),
    field("quality", &FlowParams::quality, kFraction),
    field("min_distance", &FlowParams::min_distance, kNonNegative),
    field("block_size", &FlowParams::block_size, int_range<1, 31>()),
    field("use_harris", &FlowParams::use_harris, kBool),
    field("harris_k", &FlowParams::harris_k, kPositive),
    // Lucas–Kanade needs a window wider than the derivative's kernel (OpenCV: above 2).
    field("window_size", &FlowParams::window_size, int_range<3, 101>()),
    field("pyramid_levels", &FlowParams::pyramid_levels, int_range<0, 8>()),
    field("mask_border", &FlowParams::mask_border, int_range<0, 100>()),
    field("forward_backward_threshold", &FlowParams::forward_backward_threshold, kPositive),
    field("renew_fraction", &FlowParams::renew_fraction, kFraction),
    field("renew_rotation_deg", &FlowParams::renew_rotation_deg, kPositive),
    field("min_points", &FlowParams::min_points, int_range<0, 100000>()),
    field("standard_deviations", &FlowParams::standard_deviations, kPositives),
    section("noise", &FlowParams::noise, kNoiseFields),
    field("measure_occlusions", &FlowParams::occlusion, &OcclusionParams::measure, kBool),
    field("occlusion_radius", &FlowParams::occlusion, &OcclusionParams::radius, kNonNegative),
    field("occlusion_threshold", &FlowParams::occlusion, &OcclusionParams::threshold, kNonNegative),
};

const Fields<EdgeParams> kEdgeFields = {
    field("crease_angle_deg", &EdgeParams::crease_angle_deg, Rule<double>{"a number of degrees in (0, 180)", [](const double& v) {
            return std::isfinite(v) && v > 0.0 && v < 180.0;
          }}),
    field("max_view_angle_deg", &EdgeParams::max_view_angle_deg, Rule<double>{"a number of degrees in (0, 90]", [](const double& v) {
            return std::isfinite(v) && v > 0.0 && v <= 90.0;
          }}),
    field("sample_step", &EdgeParams::sample_step, kPositive),
    field("n_points_max", &EdgeParams::n_points_max, int_range<1, 100000>()),
    field("search_ranges", &EdgeParams::search_ranges, kScales),
    field("min_contrast", &EdgeParams::min_contrast, kNonNegative),
    field("min_points", &EdgeParams::min_points, int_range<0, 100000>()),
    field("standard_deviations", &EdgeParams::standard_deviations, kPositives),
    section("noise", &EdgeParams::noise, kNoiseFields),
    field("resample_angle_deg", &EdgeParams::resample_angle_deg, kNonNegative),
    field("render_size", &EdgeParams::render_size, int_range<16, 2048>()),
};

/// The registered cues' names, at least one, none twice (the registry's list, read each time).
Rule<std::vector<std::string>> cue_list_rule() { return {cue_list_expected(), valid_cue_list}; }

/// Registered cues' names other than depth's, none twice; empty allowed.
Rule<std::vector<std::string>> stand_in_list_rule() {
  return {"a list of distinct cue names other than depth (a cue cannot stand in for itself)",
          [](const std::vector<std::string>& names) {
            return names.empty() || (valid_cue_list(names) && !has_cue(names, cue::kDepth));
          }};
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
    {"preset", [](const yaml::Value&, TrackerConfig&) {},
     [](YAML::Emitter& out, const TrackerConfig& c) { emit(out, c.preset); },
     [](const TrackerConfig& c, const yaml::Location& at) {
       if (!known_preset(c.preset)) at.child("preset").fail("expected one of " + preset_list() + " (got '" + c.preset + "')");
     }},
    section("tracker", &TrackerConfig::tracker, kTrackerFields),
    {"modalities",
     [](const yaml::Value& v, TrackerConfig& c) { c.modalities = parse_cue_list(v.as(cue_list_rule())); },
     [](YAML::Emitter& out, const TrackerConfig& c) { emit(out, c.modalities); },
     [](const TrackerConfig& c, const yaml::Location& at) {
       check_value(c.modalities, cue_list_rule(), at.child("modalities"));
     }},
    field("depth_stand_ins", &TrackerConfig::depth_stand_ins, stand_in_list_rule()),
    section("region_model", &TrackerConfig::region_model, kModelFields),
    section("depth_model", &TrackerConfig::depth_model, kModelFields),
    section("region", &TrackerConfig::region, kRegionFields),
    section("depth", &TrackerConfig::depth, kDepthFields),
    section("texture", &TrackerConfig::texture, kTextureFields),
    section("flow", &TrackerConfig::flow, kFlowFields),
    section("edge", &TrackerConfig::edge, kEdgeFields),
    field("regions", &TrackerConfig::regions,
          Rule<std::vector<std::string>>{"a list of region mesh files",
                                         [](const std::vector<std::string>& files) {
                                           return std::none_of(files.begin(), files.end(),
                                                               [](const std::string& f) { return f.empty(); });
                                         }}),
    {"bodies", [](const yaml::Value& v, TrackerConfig& c) { c.bodies = read_body_configs(v); },
     [](YAML::Emitter& out, const TrackerConfig& c) { write_body_configs(out, c.bodies); },
     [](const TrackerConfig& c, const yaml::Location& at) { check_body_configs(c.bodies, at.child("bodies")); }},
    section("detection", &TrackerConfig::detection, kDetectionFields),
    field("cache_dir", &TrackerConfig::cache_dir, yaml::kString),
};

/// The section of a registered cue with parameters: its keys read as numbers in their
/// ranges into TrackerConfig::cue_parameters, every key written (the default where unset).
Field<TrackerConfig> cue_section(const CueEntry& registered) {
  const CueEntry cue = registered;  // the registry's entries may move as cues are added
  return {cue.name,
          [cue](const yaml::Value& section, TrackerConfig& c) {
            std::vector<std::string> keys;
            for (const CueParameter& p : cue.parameters) keys.push_back(p.key);
            yaml::for_each_entry(section, keys, [&](const std::string& key, const yaml::Value& v) {
              const CueParameter& p = *cue.parameter(key);
              const std::optional<double> value = yaml::convert<double>(v.node);
              if (!value || !p.accepts(*value)) v.expected(p.expected());
              c.cue_parameters[cue.name][key] = *value;
            });
          },
          [cue](YAML::Emitter& out, const TrackerConfig& c) {
            out << YAML::BeginMap;
            for (const CueParameter& p : cue.parameters) {
              out << YAML::Key << p.key << YAML::Value;
              const double value = cue_parameter(c, cue.name, p.key);
              if (p.integer)
                out << static_cast<long long>(value);
              else
                emit(out, value);
            }
            out << YAML::EndMap;
          },
          [cue](const TrackerConfig& c, const yaml::Location& at) {
            const auto given = c.cue_parameters.find(cue.name);
            if (given == c.cue_parameters.end()) return;
            for (const auto& [key, value] : given->second) {
              const CueParameter* p = cue.parameter(key);
              if (!p) at.child(cue.name).child(key).fail("cue '" + cue.name + "' has no such parameter");
              if (!p->accepts(value)) yaml::Value{YAML::Node(value), at.child(cue.name).child(key)}.expected(p->expected());
            }
          }};
}

/// The configuration's fields: the fixed ones, then a section per registered cue with
/// parameters.
Fields<TrackerConfig> config_fields() {
  Fields<TrackerConfig> fields = kConfigFields;
  for (const CueEntry& cue : CueRegistry::instance().entries())
    if (!cue.parameters.empty()) fields.push_back(cue_section(cue));
  return fields;
}

/// Cue parameters set in code for a cue that is not registered, or has no parameters.
void check_cue_parameter_sections(const TrackerConfig& config, const yaml::Location& at) {
  for (const auto& [cue, values] : config.cue_parameters) {
    const CueEntry* entry = CueRegistry::instance().find(cue);
    if (!entry || entry->parameters.empty())
      at.child(cue).fail("no registered cue of that name takes parameters (cues: " + registered_cue_names() + ")");
  }
}

}  // namespace

const std::vector<std::string>& tracker_config_keys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> names;
    for (const Field<TrackerConfig>& f : kConfigFields) names.push_back(f.name);
    return names;
  }();
  return keys;
}

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
    for (NoiseParams* noise : {&config.region.noise, &config.depth.noise, &config.texture.noise, &config.flow.noise})
      noise->estimate = noise->robust = false;
    config.region.subpixel_posterior = false;
    config.texture.descriptor = Descriptor::kOrb;
  }
  return config;
}

namespace {

/// The keys of `root` read over `config` (a `preset` key starts again from that preset),
/// relative mesh paths resolved against `folder`.
TrackerConfig read_over(const yaml::Value& root, const std::filesystem::path& folder, TrackerConfig config) {
  if (root.node.IsMap() && root.node["preset"]) {
    const yaml::Value preset{root.node["preset"], root.at.child("preset")};
    const std::string name = preset.as(yaml::kNonEmptyString);
    if (!known_preset(name)) preset.at.fail("expected one of " + preset_list() + " (got '" + name + "')");
    config = tracker_config_preset(name);
  }
  read_map(root, config_fields(), config);
  auto resolve = [&](std::string& file) {
    if (std::filesystem::path(file).is_relative()) file = (folder / file).lexically_normal().string();
  };
  // Only the lists this document wrote (each replaces the base's whole): the base's paths
  // were resolved against the folder they came from.
  const bool map = root.node.IsMap();
  if (map && root.node["regions"])
    for (std::string& region : config.regions) resolve(region);
  if (map && root.node["bodies"])
    for (BodyConfig& body : config.bodies) resolve(body.mesh);
  return config;
}

}  // namespace

TrackerConfig load_tracker_config(const std::string& path, const TrackerConfig& base) {
  return read_over(yaml::load_file(path, kWording), std::filesystem::path(path).parent_path(), base);
}

TrackerConfig read_tracker_config(const std::string& yaml_text, const std::string& source, const std::string& folder,
                                  const TrackerConfig& base) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw yaml::Error(source + ": not valid YAML: " + e.msg);
  }
  return read_over(yaml::Value{root, yaml::Location{source, "", kWording}}, folder, base);
}

void validate(const TrackerConfig& config, const std::string& source) {
  const yaml::Location document{source, "", kWording};
  check_cue_parameter_sections(config, document);
  check_map(config_fields(), config, document);
}

std::string to_yaml(const TrackerConfig& config) {
  YAML::Emitter out;
  write_map(out, config_fields(), config);
  return std::string(out.c_str()) + "\n";
}

}  // namespace icgp
