// SPDX-License-Identifier: GPL-2.0-or-later
// The cue registry: the built-in cues, and a user's own cue (the example cue of
// docs/architecture.md) registered here and then selected from YAML and through
// vpMbIcgTracker, where it tracks, is counted and is shown, with no line of the tracker,
// the builder, the camera rig or the ViSP class written for it.
#include <catch2/catch.hpp>
#include <fstream>
#include <iterator>

#include "example_position_cue.h"
#include "icgp/tracker/cue_registry.h"
#include "test_temp_dir.h"
#include "vpmbicgtracker_test_setup.h"

using namespace icgp;
using Catch::Matchers::Contains;

namespace {

constexpr double kSigma = 0.001;  // metres: a precise external position sensor, by default

/// What the position sensor measures when a tracker builds its cue: the body origin in
/// the reference camera.
Eigen::Vector3d measured_position;

/// The example cue as a program registers it: it reads no camera, vpMbIcgTracker counts
/// and shows its one correspondence as a KLT point (a marker's centre), and a
/// configuration's `position:` section sets the sensor's standard deviation.
CueEntry position_entry() {
  CueEntry entry;
  entry.name = "position";
  entry.visp_features = VispFeatures::kKlt;
  entry.parameters = {{"standard_deviation", kSigma, 1e-6, 1.0}};
  entry.make = [](const CueContext& c) {
    return std::make_unique<example::PositionCue>(c.body, measured_position,
                                                  cue_parameter(c.config, "position", "standard_deviation"));
  };
  return entry;
}

void register_position_cue() {
  if (!CueRegistry::instance().find("position")) CueRegistry::instance().add(position_entry());
}

/// tests/configs/coarse_models.yaml with `modalities: [region, depth, position]`.
std::string yaml_selecting_position(const test::TempDir& dir) {
  std::ifstream coarse(ICGP_TEST_CONFIGS_DIR "/coarse_models.yaml");
  const std::string text{std::istreambuf_iterator<char>(coarse), std::istreambuf_iterator<char>()};
  const std::string file = dir.file("position.yaml");
  std::ofstream(file) << text << "modalities: [region, depth, position]\n";
  return file;
}

/// Tracks the second of two teabox frames from a start 5 mm off the first's truth, with
/// the sensor measuring the second's truth; returns the error, mm.
double track_second_frame(test::RgbdTeabox& rig) {
  measured_position = rig.frames[1].truth()->translation();
  rig.init_at_truth(Eigen::Vector3d(0.005, 0.0, 0.0));
  rig.input.convert(rig.frames[1]);
  rig.track();
  return translation_error_mm(rig.pose(), *rig.frames[1].truth());
}

/// The KLT points of getFeaturesForDisplay at `pixel` (u, v), within 0.01 px.
int klt_features_at(vpMbIcgTracker& tracker, const Eigen::Vector2d& pixel) {
  int n = 0;
  for (const std::vector<double>& f : tracker.getFeaturesForDisplay())
    if (f[0] == 1.0 && std::abs(f[2] - pixel.x()) < 0.01 && std::abs(f[1] - pixel.y()) < 0.01) ++n;
  return n;
}

}  // namespace

TEST_CASE("cue registry: the built-in cues in order, and what a cue entry must hold") {
  const std::vector<std::string> names = CueRegistry::instance().names();
  REQUIRE(names.size() >= 5);
  CHECK(std::vector<std::string>(names.begin(), names.begin() + 5) ==
        std::vector<std::string>{cue::kRegion, cue::kDepth, cue::kTexture, cue::kFlow, cue::kEdge});
  CHECK(CueRegistry::instance().built_in(cue::kFlow));
  CHECK_FALSE(CueRegistry::instance().built_in("position"));
  CHECK(CueRegistry::instance().find(cue::kDepth)->visp_types == visp_type::kDepth);
  CHECK(CueRegistry::instance().find(cue::kEdge)->visp_features == VispFeatures::kEdge);

  // Unknown until registered: the message lists what is available.
  CHECK_THROWS_WITH(parse_cue_list({"region", "position"}),
                    Contains("modality 'position' is not available (available: region, depth, texture, flow, edge"));
  register_position_cue();
  CHECK(parse_cue_list({"region", "position"}) == std::vector<std::string>{"region", "position"});
  CHECK_THAT(cue_list_expected(), Contains("edge, position"));

  CHECK_THROWS_WITH(CueRegistry::instance().add(position_entry()), Contains("'position' is registered already"));
  CueEntry no_factory;
  no_factory.name = "no-factory";
  CHECK_THROWS_WITH(CueRegistry::instance().add(no_factory), Contains("has no factory"));
  CueEntry no_camera = position_entry();
  no_camera.name = "image-without-camera";
  no_camera.reads_image = true;
  CHECK_THROWS_WITH(CueRegistry::instance().add(no_camera), Contains("reads images or depth but no camera type"));
  CHECK_THROWS_WITH(parse_cue_list({"region", "region"}), Contains("a non-empty list of distinct names"));
}

TEST_CASE("cue registry: a registered cue selected from YAML tracks, is counted and is shown by vpMbIcgTracker") {
  register_position_cue();
  const test::TempDir dir("icgp-cue-registry");
  const std::string yaml = yaml_selecting_position(dir);
  CHECK(load_tracker_config(yaml).modalities == std::vector<std::string>{"region", "depth", "position"});

  test::RgbdTeabox rig(2);
  rig.tracker.loadConfigFile(yaml, false);
  TrackerConfig config = rig.tracker.getTrackerConfig();
  config.cache_dir = ICGP_TEST_CACHE_DIR;
  rig.tracker.setTrackerConfig(config);
  const double error_mm = track_second_frame(rig);
  INFO("error " << error_mm << " mm from a start 5 mm off");
  CHECK(error_mm < 0.5);
  // Its one correspondence is a KLT point's two rows, as ViSP counts them; no other cue of
  // this selection is counted as KLT.
  CHECK(rig.tracker.getNbFeaturesKlt() == 2);
  const Intrinsics& K = rig.frames[1].colors.front().intrinsics;
  CHECK(klt_features_at(rig.tracker, K.project(measured_position)) == 1);
}

TEST_CASE("cue registry: vpMbIcgTracker::addCue registers a cue and fuses it") {
  test::RgbdTeabox rig(2);
  rig.tracker.setModalities({cue::kRegion, cue::kDepth});
  rig.tracker.addCue(position_entry());
  CHECK(rig.tracker.getTrackerConfig().modalities == std::vector<std::string>{"region", "depth", "position"});
  const double error_mm = track_second_frame(rig);
  INFO("error " << error_mm << " mm from a start 5 mm off");
  CHECK(error_mm < 0.5);
  CHECK(rig.tracker.getNbFeaturesKlt() == 2);

  // Without it the same selection counts no KLT point.
  test::RgbdTeabox without(2);
  without.tracker.setModalities({cue::kRegion, cue::kDepth});
  track_second_frame(without);
  CHECK(without.tracker.getNbFeaturesKlt() == 0);

  // A built-in cue's name is refused, as ViSP refuses: with a vpException.
  CueEntry shadow = position_entry();
  shadow.name = cue::kDepth;
  const vpException e = test::vp_exception_of([&] { rig.tracker.addCue(shadow); });
  CHECK_THAT(e.getStringMessage(), Contains("'depth' is a built-in cue"));
}

TEST_CASE("cue registry: a registered cue's parameters are a section of the configuration, read, written and checked") {
  register_position_cue();
  const test::TempDir dir("icgp-cue-parameters");
  const auto read = [&](const std::string& yaml) {
    const std::string file = dir.file("config.yaml");
    std::ofstream(file) << yaml;
    return load_tracker_config(file);
  };
  // The default, until a file sets it.
  CHECK(cue_parameter(TrackerConfig(), "position", "standard_deviation") == kSigma);
  const TrackerConfig config = read("modalities: [region, position]\nposition: {standard_deviation: 0.004}\n");
  CHECK(cue_parameter(config, "position", "standard_deviation") == 0.004);
  CHECK_THAT(to_yaml(config), Contains("position:\n  standard_deviation: 0.004"));
  CHECK(cue_parameter(read(to_yaml(config)), "position", "standard_deviation") == 0.004);  // written as read

  // The factory reads it: the cue's Hessian is −1/σ² of the configured σ.
  Body body{"teabox", Mesh{}, Pose()};
  const std::unique_ptr<Modality> cue = CueRegistry::instance().find("position")->make(CueContext{body, config});
  CHECK(cue->gradient_hessian(0, 0).hessian(3, 3) == Approx(-1.0 / (0.004 * 0.004)));

  // A file's bad values are refused naming the key and the range.
  CHECK_THROWS_WITH(read("position: {standard_deviation: 5}\n"),
                    Contains("position.standard_deviation: expected a number in [1e-06, 1], got 5"));
  CHECK_THROWS_WITH(read("position: {sigma: 0.002}\n"), Contains("standard_deviation"));
  CHECK_THROWS_WITH(cue_parameter(config, "position", "sigma"), Contains("cue 'position' has no parameter 'sigma'"));
  // So are values set in code.
  TrackerConfig in_code;
  in_code.cue_parameters["position"]["standard_deviation"] = 0.0;
  CHECK_THROWS_WITH(validate(in_code, "code"), Contains("code: position.standard_deviation: expected a number in"));
  in_code.cue_parameters = {{"gps", {{"standard_deviation", 1.0}}}};
  CHECK_THROWS_WITH(validate(in_code, "code"), Contains("code: gps: no registered cue of that name takes parameters"));

  // A cue with parameters cannot take a configuration key's name, nor a default out of range.
  CueEntry clash = position_entry();
  clash.name = "tracker";
  CHECK_THROWS_WITH(CueRegistry::instance().add(clash), Contains("where 'tracker' is a key already"));
  CueEntry bad_default = position_entry();
  bad_default.name = "position-2";
  bad_default.parameters.front().default_value = 2.0;
  CHECK_THROWS_WITH(CueRegistry::instance().add(bad_default), Contains("its default is outside its range"));
}
