// SPDX-License-Identifier: GPL-2.0-or-later
// Tracker configuration files: the reference defaults, partial files, the YAML round trip
// and error messages that name the file and the key.
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>

#include "icgp/tracker/tracker_config.h"
#include "test_temp_dir.h"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using icgp::load_tracker_config;
using icgp::to_yaml;
using icgp::TrackerConfig;
using icgp::test::TempDir;

namespace {

/// Every value of a YAML document by its dotted key ("region.scales" -> "[6, 4, 2, 1]").
std::map<std::string, std::string> flatten(const YAML::Node& node, const std::string& prefix = "") {
  std::map<std::string, std::string> values;
  if (node.IsMap()) {
    for (const auto& entry : node) {
      auto nested = flatten(entry.second, prefix + entry.first.Scalar() + ".");
      values.insert(nested.begin(), nested.end());
    }
  } else {
    std::string text = node.Scalar();
    if (node.IsSequence()) {
      text = "[";
      for (const auto& item : node) text += (text.size() > 1 ? ", " : "") + (item.IsScalar() ? item.Scalar() : YAML::Dump(item));
      text += "]";
    }
    values[prefix.substr(0, prefix.size() - 1)] = text;
  }
  return values;
}

std::map<std::string, std::string> flatten_yaml(const std::string& text) { return flatten(YAML::Load(text)); }

/// Every key, none with its default value (written the way to_yaml writes values).
const char* const kEveryKey = R"(preset: icg_reference
tracker:
  n_corr_iterations: 4
  n_update_iterations: 3
  tikhonov_rotation: 500.0
  tikhonov_translation: 10000.0
  quality_threshold: 0.25
modalities: [depth, texture, region]
depth_stand_ins: [edge, flow]
region_model:
  n_divides: 3
  sphere_radius: 1.2
  image_size: 1000
  image_margin: 10
  n_points: 150
  stride_depth_offset: 0.004
  max_radius_depth_offset: 0.04
  min_contour_length: 10
  normal_chord_offset: 2
  seed: 18446744073709551615
depth_model:
  n_divides: 0
  sphere_radius: 0.6
  image_size: 64
  image_margin: 0
  n_points: 100
  stride_depth_offset: 0.001
  max_radius_depth_offset: 0.03
  min_contour_length: 0
  normal_chord_offset: 1
  seed: 11
region:
  color_camera: rgb
  depth_camera: ""
  n_lines_max: 150
  min_continuous_distance: 2.5
  function_length: 7
  distribution_length: 11
  function_amplitude: 0.36
  function_slope: 0.0
  learning_rate: 1.1
  n_global_iterations: 0
  subpixel_posterior: false
  scales: [5, 3, 1]
  standard_deviations: [20.0, 2.0]
  noise:
    estimate: true
    robust: false
    floor: 0.2
    min_residuals: 30
    tukey_constant: 3.0
  n_histogram_bins: 32
  learning_rate_f: 0.1
  learning_rate_b: 1.0
  unconsidered_line_length: 1.0
  max_considered_line_length: 30.0
  measure_occlusions: false
  occlusion_radius: 0.02
  occlusion_threshold: 0.05
  model_occlusions: false
  modeled_occlusion_radius: 0.02
  modeled_occlusion_threshold: 0.01
  occlusion_render_size: 128
  region_checking: true
  n_unoccluded_iterations: 0
  min_n_unoccluded_lines: 5
depth:
  depth_camera: depth
  n_points_max: 300
  stride_length: 0.01
  considered_distances: [0.1, 0.03]
  standard_deviations: [0.04]
  noise:
    estimate: false
    robust: false
    floor: 0.001
    min_residuals: 10
    tukey_constant: 6.0
  measure_occlusions: false
  occlusion_radius: 0.005
  occlusion_threshold: 0.04
  model_occlusions: false
  modeled_occlusion_radius: 0.005
  modeled_occlusion_threshold: 0.02
  occlusion_render_size: 100
  n_unoccluded_iterations: 3
  min_n_unoccluded_points: 7
  dense_when_only_cue: false
  dense_step_x: 3
  dense_step_y: 2
  dense_n_points_max: 800
texture:
  color_camera: left
  depth_camera: ""
  descriptor: sift
  focused_image_size: 256
  orb_n_features: 500
  orb_n_levels: 4
  orb_scale_factor: 1.5
  sift_n_octave_layers: 4
  sift_contrast_threshold: 0.03
  sift_edge_threshold: 12.0
  sift_sigma: 1.6
  ratio_test: 0.8
  keyframe_orientation_threshold_deg: 15.0
  keyframe_max_age: 0
  min_keyframe_points: 5
  tukey_norm_constant: 30.0
  standard_deviations: [10.0, 10.0, 3.0]
  noise:
    estimate: false
    robust: true
    floor: 1.0
    min_residuals: 8
    tukey_constant: 2.0
  occlusion_radius: 0.02
  occlusion_threshold: 0.05
  model_occlusions: false
  modeled_occlusion_radius: 0.03
  modeled_occlusion_threshold: 0.04
  occlusion_render_size: 64
flow:
  max_features: 400
  quality: 0.02
  min_distance: 8.0
  block_size: 5
  use_harris: true
  harris_k: 0.04
  window_size: 9
  pyramid_levels: 2
  mask_border: 3
  forward_backward_threshold: 0.5
  renew_fraction: 0.5
  renew_rotation_deg: 15.0
  min_points: 10
  standard_deviations: [8.0, 2.0]
  noise:
    estimate: false
    robust: false
    floor: 0.2
    min_residuals: 30
    tukey_constant: 3.0
  measure_occlusions: false
  occlusion_radius: 0.02
  occlusion_threshold: 0.05
edge:
  crease_angle_deg: 45.0
  max_view_angle_deg: 80.0
  sample_step: 4.0
  n_points_max: 200
  search_ranges: [6, 3]
  min_contrast: 8.0
  min_points: 10
  standard_deviations: [4.0, 1.0]
  noise:
    estimate: false
    robust: false
    floor: 0.5
    min_residuals: 30
    tukey_constant: 3.0
  resample_angle_deg: 3.0
  render_size: 100
regions: [/models/a/body.obj, /models/a/lid.obj]
bodies:
  - name: lid
    mesh: /models/a/lid.obj
    scale: 0.001
    role: tracked
    parent: main
    origin: {t: [0, 0.05, 0.04], r_deg: [0, 0, 0]}
    joint: revolute
    axis: [1, 0, 0]
    limits_deg: [0, 110]
  - name: hand
    mesh: /models/hand.obj
    scale: 1
    role: occluder
detection:
  recovery: false
  global_search_interval: 3
  view_divides: 1
  roll_step_deg: 15.0
  min_distance: 0.3
  max_distance: 1.2
  template_points: 64
  hypotheses: 9
  accept_quality: 0.7
cache_dir: /tmp/icgp cache
)";

}  // namespace

TEST_CASE("tracker config: defaults are the reference values of ALGORITHMS.md") {
  const TrackerConfig c;
  CHECK(c.tracker.regularisation.tikhonov_rotation == 1000.0);
  CHECK(c.tracker.regularisation.tikhonov_translation == 30000.0);
  CHECK(c.tracker.n_corr_iterations == 5);
  CHECK(c.tracker.n_update_iterations == 2);
  CHECK(c.modalities == std::vector<std::string>{icgp::cue::kRegion, icgp::cue::kDepth, icgp::cue::kTexture});
  for (const icgp::ViewpointModelParams& m : {c.region_model, c.depth_model}) {
    CHECK(m.n_divides == 4);
    CHECK(m.sphere_radius == 0.8);
    CHECK(m.image_size == 2000);
    CHECK(m.image_margin == 20);
    CHECK(m.n_points == 200);
    CHECK(m.stride_depth_offset == 0.002);
    CHECK(m.max_radius_depth_offset == 0.05);
    CHECK(m.min_contour_length == 15);
    CHECK(m.normal_chord_offset == 3);
  }
  CHECK(c.region.n_lines_max == 200);
  CHECK(c.region.min_continuous_distance == 3.0);
  CHECK(c.region.function_length == 8);
  CHECK(c.region.distribution_length == 12);
  CHECK(c.region.function_amplitude == 0.43);
  CHECK(c.region.function_slope == 0.5);
  CHECK(c.region.learning_rate == 1.3);
  CHECK(c.region.n_global_iterations == 1);
  CHECK(c.region.scales == std::vector<int>{6, 4, 2, 1});
  CHECK(c.region.standard_deviations == std::vector<double>{15.0, 5.0, 3.5, 1.5});
  CHECK(c.region.n_histogram_bins == 16);
  CHECK(c.region.learning_rate_f == 0.2);
  CHECK(c.region.learning_rate_b == 0.2);
  CHECK(c.region.unconsidered_line_length == 0.5);
  CHECK(c.region.max_considered_line_length == 20.0);
  CHECK(c.region.occlusion.measure);
  CHECK(c.region.occlusion.radius == 0.01);
  CHECK(c.region.occlusion.threshold == 0.03);
  CHECK(c.depth.n_points_max == 200);
  CHECK(c.depth.stride_length == 0.005);
  CHECK(c.depth.considered_distances == std::vector<double>{0.05, 0.02, 0.01});
  CHECK(c.depth.standard_deviations == std::vector<double>{0.05, 0.03, 0.02});
  CHECK(c.depth.occlusion.measure);
  CHECK(c.depth.occlusion.radius == 0.01);
  CHECK(c.depth.occlusion.threshold == 0.03);
  CHECK(c.texture.occlusion.radius == 0.01);
  CHECK(c.texture.occlusion.threshold == 0.03);
  CHECK(c.cache_dir.empty());
}

TEST_CASE("tracker config: presets") {
  const TrackerConfig defaults;
  CHECK(defaults.preset == "default");
  CHECK(to_yaml(icgp::tracker_config_preset("default")) == to_yaml(defaults));
  CHECK(defaults.depth.noise.estimate);
  CHECK(defaults.texture.noise.estimate);
  CHECK_FALSE(defaults.region.noise.estimate);
  CHECK(defaults.region.noise.robust);
  CHECK(defaults.depth.noise.robust);
  CHECK_FALSE(defaults.texture.noise.robust);  // the papers' Tukey norm of its own
  CHECK(defaults.region.subpixel_posterior);
  CHECK(defaults.texture.descriptor == icgp::Descriptor::kOrientedBrief);

  // icg_reference: the same cues and parameters with the papers' fixed schedules, discrete
  // contour posterior and ORB.
  const TrackerConfig reference = icgp::tracker_config_preset("icg_reference");
  CHECK_FALSE(reference.region.noise.estimate);
  CHECK_FALSE(reference.depth.noise.estimate);
  CHECK_FALSE(reference.texture.noise.estimate);
  CHECK_FALSE(reference.region.noise.robust);
  CHECK_FALSE(reference.depth.noise.robust);
  CHECK_FALSE(reference.region.subpixel_posterior);
  CHECK(reference.texture.descriptor == icgp::Descriptor::kOrb);
  auto expected = flatten_yaml(to_yaml(defaults));
  expected["preset"] = "icg_reference";
  expected["depth.noise.estimate"] = expected["texture.noise.estimate"] = expected["flow.noise.estimate"] = "false";
  expected["region.noise.robust"] = expected["depth.noise.robust"] = expected["flow.noise.robust"] = "false";
  expected["region.subpixel_posterior"] = "false";
  expected["texture.descriptor"] = "orb";
  CHECK(flatten_yaml(to_yaml(reference)) == expected);

  TempDir dir("icgp-config");
  SECTION("a file's other keys are read over its preset, in any order") {
    const TrackerConfig c = load_tracker_config(
        dir.write("over.yaml", "depth:\n  noise: {floor: 0.002}\npreset: icg_reference\n"));
    CHECK(c.preset == "icg_reference");
    CHECK_FALSE(c.depth.noise.estimate);
    CHECK(c.depth.noise.floor == 0.002);
    CHECK(to_yaml(load_tracker_config(dir.write("back.yaml", to_yaml(c)))) == to_yaml(c));
  }
  SECTION("an unknown preset names the file, the key and the known ones") {
    CHECK_THROWS_WITH(load_tracker_config(dir.write("bad.yaml", "preset: icg\n")),
                      Contains("bad.yaml: preset: expected one of default, icg_reference (got 'icg')"));
    CHECK_THROWS_WITH(icgp::tracker_config_preset("fast"), Contains("'fast'") && Contains("icg_reference"));
  }
}

TEST_CASE("tracker config: empty files and empty sections give the defaults") {
  TempDir dir("icgp-config");
  const std::string defaults = to_yaml(TrackerConfig{});
  CHECK(to_yaml(load_tracker_config(dir.write("empty.yaml", ""))) == defaults);
  CHECK(to_yaml(load_tracker_config(dir.write("comments.yaml", "# nothing set\n"))) == defaults);
  CHECK(to_yaml(load_tracker_config(dir.write("sections.yaml", "tracker:\nregion: {}\n"))) == defaults);
}

TEST_CASE("tracker config: a partial file overrides only its keys") {
  TempDir dir("icgp-config");
  const std::string file = dir.write("partial.yaml",
                                     "tracker:\n  n_corr_iterations: 7\n"
                                     "region:\n  scales: [3, 1]\n  function_amplitude: 0.4\n"
                                     "depth_model: {n_points: 50}\n"
                                     "depth_stand_ins: [flow]\n");
  const TrackerConfig c = load_tracker_config(file);
  CHECK(c.tracker.n_corr_iterations == 7);
  CHECK(c.region.scales == std::vector<int>{3, 1});
  CHECK(c.region.function_amplitude == 0.4);
  CHECK(c.depth_model.n_points == 50);
  CHECK(c.region_model.n_points == 200);
  CHECK(c.depth_stand_ins == std::vector<std::string>{"flow"});

  auto expected = flatten_yaml(to_yaml(TrackerConfig{}));
  expected["tracker.n_corr_iterations"] = "7";
  expected["region.scales"] = "[3, 1]";
  expected["region.function_amplitude"] = "0.4";
  expected["depth_model.n_points"] = "50";
  expected["depth_stand_ins"] = "[flow]";
  CHECK(flatten_yaml(to_yaml(c)) == expected);
}

TEST_CASE("tracker config: to_yaml writes every key and round-trips exactly") {
  TempDir dir("icgp-config");
  const auto defaults = flatten_yaml(to_yaml(TrackerConfig{}));
  const auto every_key = flatten_yaml(kEveryKey);
  // The file sets every key to_yaml writes, each to a value other than its default ...
  REQUIRE(every_key.size() == defaults.size());
  for (const auto& [key, value] : defaults) {
    INFO(key);
    REQUIRE(every_key.count(key) == 1);
    CHECK(every_key.at(key) != value);
  }
  // ... so reading it and writing it back proves every key is both read and written.
  const TrackerConfig c = load_tracker_config(dir.write("every.yaml", kEveryKey));
  CHECK(to_yaml(c) == kEveryKey);
  CHECK(c.region.depth_camera.empty());
  // The flat occlusion keys of each section are its OcclusionParams; the descriptor is named.
  CHECK_FALSE(c.region.occlusion.measure);
  CHECK(c.depth.occlusion.radius == 0.005);
  CHECK(c.texture.occlusion.threshold == 0.05);
  CHECK(c.texture.descriptor == icgp::Descriptor::kSift);
  CHECK(c.region_model.seed == 18446744073709551615ull);
  CHECK(c.cache_dir == "/tmp/icgp cache");

  SECTION("doubles keep every bit") {
    TrackerConfig awkward;
    awkward.region.function_slope = 0.1 + 0.2;
    awkward.depth.standard_deviations = {1.0 / 3.0, 1e-300, 1e300};
    awkward.tracker.regularisation.tikhonov_rotation = 123456789.0;
    const TrackerConfig back = load_tracker_config(dir.write("awkward.yaml", to_yaml(awkward)));
    CHECK(back.region.function_slope == awkward.region.function_slope);
    CHECK(back.depth.standard_deviations == awkward.depth.standard_deviations);
    CHECK(back.tracker.regularisation.tikhonov_rotation == awkward.tracker.regularisation.tikhonov_rotation);
  }
}

TEST_CASE("tracker config: docs/configuration.md lists every key with its default") {
  std::ifstream in(ICGP_DOCS_DIR "/configuration.md");
  REQUIRE(in);
  const std::regex section_name("`([\\w.]+)`"), row(R"(^\| `(\w+)` \| `([^`]*)` \|)");
  std::vector<std::string> prefixes;  // of the keys in the current section's table
  std::map<std::string, std::string> documented;
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (line.rfind("## ", 0) == 0) {
      prefixes.clear();
      if (line == "## Top level") prefixes.push_back("");
      for (std::sregex_iterator it(line.begin(), line.end(), section_name), end; it != end; ++it)
        prefixes.push_back((*it)[1].str() + ".");
    } else if (std::regex_search(line, m, row)) {
      for (const std::string& prefix : prefixes) documented[prefix + m[1].str()] = m[2] == "\"\"" ? "" : m[2].str();
    }
  }
  CHECK(documented == flatten_yaml(to_yaml(TrackerConfig{})));
}

TEST_CASE("tracker config: unreadable files and YAML syntax errors name the file") {
  TempDir dir("icgp-config");
  const std::string missing = (dir.path() / "missing.yaml").string();
  CHECK_THROWS_WITH(load_tracker_config(missing), StartsWith(missing + ": ") && Contains("no such file"));
  const std::string folder = dir.path().string();
  CHECK_THROWS_WITH(load_tracker_config(folder), StartsWith(folder + ": ") && Contains("cannot read"));
  const std::string broken = dir.write("broken.yaml", "tracker:\n  n_corr_iterations: [1, 2\nregion: {}\n");
  CHECK_THROWS_WITH(load_tracker_config(broken), StartsWith(broken + ": line ") && Contains("YAML syntax error"));
}

TEST_CASE("tracker config: bad keys, types and values name the file and the full key") {
  struct Case {
    const char* yaml;
    const char* message;  ///< after "<file>: "
  };
  const Case cases[] = {
      {"regoin: {}", "regoin: unknown key (valid keys: preset, tracker, modalities, depth_stand_ins, region_model, depth_model, region, depth, "
                     "texture, flow, edge, regions, bodies, detection, cache_dir)"},
      {"region: {scale: [1]}", "region.scale: unknown key (valid keys of region: color_camera, depth_camera,"},
      {"tracker: {n_corr_iterations: 3, n_corr_iterations: 4}", "tracker.n_corr_iterations: duplicate key"},
      {"- tracker\n- region\n", "expected a map with the keys preset, tracker, modalities,"},
      {"region: 3", "region: expected a map with the keys color_camera,"},
      {"tracker: {n_corr_iterations: 2.5}", "tracker.n_corr_iterations: expected an integer from 1 to 100, got 2.5"},
      {"tracker: {n_corr_iterations: 0}", "tracker.n_corr_iterations: expected an integer from 1 to 100, got 0"},
      {"tracker: {n_update_iterations: 1000000000}", "tracker.n_update_iterations: expected an integer from 1 to 100, got 1000000000"},
      {"tracker: {tikhonov_rotation: -1}", "tracker.tikhonov_rotation: expected a positive number"},
      {"tracker: {quality_threshold: 2}", "tracker.quality_threshold: expected a number in [0, 1]"},
      {"region: {scales: []}", "region.scales: expected a list of 1 to 100 integers from 1 to 64, got []"},
      {"region: {scales: [2, 0]}", "region.scales: expected a list of 1 to 100 integers from 1 to 64, got [2, 0]"},
      {"region: {scales: 6}", "region.scales: expected a list of 1 to 100 integers from 1 to 64, got 6"},
      {"region: {standard_deviations: [15, x]}", "region.standard_deviations: expected a list of 1 to 100 positive numbers, got [15, 'x']"},
      {"region: {function_amplitude: 0.5}", "region.function_amplitude: expected a number between 0 and 0.5"},
      {"region: {learning_rate_f: 1.5}", "region.learning_rate_f: expected a number in [0, 1]"},
      {"region: {measure_occlusions: maybe}", "region.measure_occlusions: expected true or false"},
      {"region: {n_histogram_bins: 12}", "region.n_histogram_bins: expected one of 2, 4, 8, 16, 32, 64"},
      {"region: {color_camera: ''}", "region.color_camera: expected a non-empty string"},
      {"region_model: {n_divides: 7}", "region_model.n_divides: expected an integer from 0 to 6"},
      {"region_model: {seed: -1}", "region_model.seed: expected a non-negative integer"},
      {"depth_model: {image_size: 32}", "depth_model.image_size: expected an integer from 64 to 8192, got 32"},
      {"region_model: {image_size: 100000}", "region_model.image_size: expected an integer from 64 to 8192, got 100000"},
      {"region_model: {n_points: 2000000000}", "region_model.n_points: expected an integer from 1 to 5000, got 2000000000"},
      {"depth: {n_points_max: 3000000000}", "depth.n_points_max: expected an integer from 1 to 5000, got 3000000000"},
      {"region: {n_lines_max: 1e9}", "region.n_lines_max: expected an integer from 1 to 5000, got 1e9"},
      {"texture: {orb_n_features: 100001}", "texture.orb_n_features: expected an integer from 1 to 100000, got 100001"},
      {"depth: {considered_distances: [0.05, -0.01]}", "depth.considered_distances: expected a list of 1 to 100 positive numbers, got [0.05, -0.01]"},
      {"depth: {stride_length: .inf}", "depth.stride_length: expected a positive number"},
      {"depth: {n_unoccluded_iterations: -2}", "depth.n_unoccluded_iterations: expected an integer from 0 to 1000, got -2"},
      {"depth: {dense_step_x: -1}", "depth.dense_step_x: expected an integer from 0 to 8192, got -1"},
      {"depth: {dense_n_points_max: 0}", "depth.dense_n_points_max: expected an integer from 1 to 1000000, got 0"},
      {"texture: {occlusion_radius: -0.01}", "texture.occlusion_radius: expected a non-negative number"},
      {"texture: {descriptor: surf}",
       "texture.descriptor: expected one of orb, brisk, sift, akaze, freak, daisy, oriented_brief"},
      {"modalities: [region, regoin]", "modalities: expected a non-empty list of distinct names from region, depth"},
      {"modalities: [depth, depth]", "modalities: expected a non-empty list of distinct names"},
      {"modalities: []", "modalities: expected a non-empty list of distinct names"},
      {"depth_stand_ins: [flow, depth]", "depth_stand_ins: expected a list of distinct cue names other than depth"},
      {"depth_stand_ins: [edge, edge]", "depth_stand_ins: expected a list of distinct cue names other than depth"},
      {"depth_stand_ins: [flw]", "depth_stand_ins: expected a list of distinct cue names other than depth"},
      {"cache_dir: [a]", "cache_dir: expected a string"},
  };
  TempDir dir("icgp-config");
  const std::string file = (dir.path() / "config.yaml").string();
  for (const Case& c : cases) {
    INFO(c.yaml);
    dir.write("config.yaml", c.yaml);
    CHECK_THROWS_WITH(load_tracker_config(file), StartsWith(file + ": " + c.message));
  }
}

TEST_CASE("tracker config: a configuration made in code gets the checks of a file") {
  for (const std::string& preset : icgp::tracker_config_presets()) CHECK_NOTHROW(icgp::validate(icgp::tracker_config_preset(preset), "code"));
  icgp::TrackerConfig config;
  config.region_model.image_size = 100000;
  CHECK_THROWS_WITH(icgp::validate(config, "code"),
                    StartsWith("code: region_model.image_size: expected an integer from 64 to 8192, got 100000"));
  config = icgp::TrackerConfig();
  config.depth.n_points_max = 2000000000;
  CHECK_THROWS_WITH(icgp::validate(config, "code"),
                    StartsWith("code: depth.n_points_max: expected an integer from 1 to 5000, got 2000000000"));
  config = icgp::TrackerConfig();
  config.tracker.regularisation.tikhonov_rotation = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(icgp::validate(config, "code"), StartsWith("code: tracker.tikhonov_rotation: expected a positive number"));
  config = icgp::TrackerConfig();
  config.region.noise.tukey_constant = 0.0;  // a nested section
  CHECK_THROWS_WITH(icgp::validate(config, "code"), StartsWith("code: region.noise.tukey_constant: expected a positive number, got 0"));
  config = icgp::TrackerConfig();
  config.depth.occlusion.render_size = 8;  // a flat key of a struct member
  CHECK_THROWS_WITH(icgp::validate(config, "code"),
                    StartsWith("code: depth.occlusion_render_size: expected an integer from 16 to 2048, got 8"));
  config = icgp::TrackerConfig();
  config.modalities = {"region", "colour"};
  CHECK_THROWS_WITH(icgp::validate(config, "code"), StartsWith("code: modalities: expected ") && Contains("'colour'"));
  config = icgp::TrackerConfig();
  config.preset = "fastest";
  CHECK_THROWS_WITH(icgp::validate(config, "code"), StartsWith("code: preset: expected one of default, icg_reference"));
}

TEST_CASE("tracker config: bodies made in code get the checks of a file, naming the body and the field") {
  icgp::TrackerConfig config;
  config.bodies = {{"lid", "lid.obj"}, {"handle", "handle.obj"}};
  CHECK_NOTHROW(icgp::validate(config, "code"));
  SECTION("a name given twice") {
    config.bodies[1].name = "lid";
    CHECK_THROWS_WITH(icgp::validate(config, "code"), StartsWith("code: bodies[1].name: expected a name no other body has"));
  }
  SECTION("no mesh") {
    config.bodies[1].mesh.clear();
    CHECK_THROWS_WITH(icgp::validate(config, "code"), StartsWith("code: bodies.handle.mesh: expected a non-empty string"));
  }
  SECTION("a scale of 0") {
    config.bodies[0].scale = 0.0;
    CHECK_THROWS_WITH(icgp::validate(config, "code"), StartsWith("code: bodies.lid.scale: expected a number in (0, 1000000]"));
  }
  SECTION("a joint with limits out of order") {
    icgp::Joint joint;
    joint.parent = "box";
    joint.directions.push_back({icgp::JointDirection::Kind::kRotation, Eigen::Vector3d::UnitZ(), 1.0, -1.0});
    config.bodies[0].joint = joint;
    CHECK_THROWS_WITH(icgp::validate(config, "code"), Contains("body 'lid': joint direction 0: limits: expected min <= max"));
  }
  SECTION("a cycle of parents") {
    icgp::Joint joint;
    joint.parent = "handle";
    config.bodies[0].joint = joint;
    joint.parent = "lid";
    config.bodies[1].joint = joint;
    CHECK_THROWS_WITH(icgp::validate(config, "code"), StartsWith("code: bodies.") && Contains("parent: the parents form a cycle"));
  }
}
