// SPDX-License-Identifier: GPL-2.0-or-later
// Detection without a given pose (docs/detection.md): the orientation quantisation against
// analytic directions and a step edge, the textured box found in a rendered RGB-D frame
// against its ground truth, also by its keypoints in a grey image without depth, a pose a
// few millimetres off aligned onto its texture, nothing found in frames without it (the
// clutter alone, blank), the labelled can found at its label's turn about its axis, and a
// textureless mug beside a copy of itself not found (which is the body is a guess), and the
// two-colour box found where a box of its shape in one colour is not, and a box turned a
// quarter about its long axis, which depth fits and its contour refutes, not verified.
#include <catch2/catch.hpp>

#include <cstdio>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "icgp/detection/body_detector.h"
#include "icgp/detection/orientation_responses.h"
#include "icgp/detection/shape_templates.h"
#include "icgp/detection/template_matcher.h"
#include "icgp/modality/depth_modality.h"
#include "icgp/modality/region_modality.h"
#include "icgp/detection/texture_alignment.h"
#include "icgp/detection/verified_ranking.h"
#include "icgp/eval/metrics.h"
#include "icgp/io/mesh_loader.h"
#include "icgp/tracker/tracker_builder.h"
#include "test_scene.h"
#include "test_temp_dir.h"

namespace icgp {
namespace {

/// A 1 mm speck: a scene of the clutter alone, where the object would be.
Mesh speck() {
  MeshPart part;
  part.vertices = {{0.f, 0.f, 0.f}, {0.001f, 0.f, 0.f}, {0.f, 0.001f, 0.f}};
  part.triangles = {{0, 1, 2}};
  Mesh mesh;
  mesh.source = "speck";
  mesh.parts.push_back(part);
  return mesh;
}

/// `found` is a detection within 5 mm and 5 degrees of `truth`; prints its errors after `label`.
void check_found_within_5mm_5deg(const Detection& found, const Pose& truth, const char* label) {
  INFO("why not: " << found.why_not);
  REQUIRE(found.found);
  const double t = translation_error_mm(found.reference_T_body, truth);
  const double r = rotation_error_deg(found.reference_T_body, truth);
  std::printf("%s: %.2f mm, %.2f deg, quality %.3f, %d candidates, %d refined\n", label, t, r, found.quality,
              found.candidates, found.refined);
  CHECK(t < 5.0);
  CHECK(r < 5.0);
}

TEST_CASE("orientation responses: bins of analytic directions, modulo 180 degrees") {
  CHECK(OrientationResponses::bin_of(1.f, 0.f) == 0);
  CHECK(OrientationResponses::bin_of(-1.f, 0.f) == 0);  // the same orientation, other polarity
  CHECK(OrientationResponses::bin_of(1.f, 1.1f) == 2);   // just past 45 degrees
  CHECK(OrientationResponses::bin_of(0.f, 1.f) == 4);
  CHECK(OrientationResponses::bin_of(0.f, -1.f) == 4);
  CHECK(OrientationResponses::bin_of(-1.f, 1.1f) == 5);  // just short of 135 degrees
}

TEST_CASE("orientation responses: a vertical step edge answers orientation 0 near it and nothing far from it") {
  cv::Mat image(64, 64, CV_8UC3, cv::Scalar::all(40));
  image.colRange(32, 64).setTo(cv::Scalar::all(200));
  OrientationResponses responses;
  responses.compute(image);
  const cv::Mat& spread = responses.spread();
  CHECK(spread.at<std::uint8_t>(30, 31) == 1);  // bit of bin 0 only
  CHECK(spread.at<std::uint8_t>(30, 33) == 1);
  CHECK(spread.at<std::uint8_t>(30, 10) == 0);
  CHECK(spread.at<std::uint8_t>(30, 50) == 0);
  // Grid position (col 8, row 7) at phase (0, 2) is pixel (32, 30): full response to bin 0.
  const int k = 7 * responses.grid_cols() + 8;
  CHECK(responses.linear(0, 0, 2)[k] == OrientationResponses::kMaxResponse);
  CHECK(responses.linear(4, 0, 2)[k] == 0);

  // Where the mask excludes pixels (a known other body over the object, ViSP's mask), the
  // same edge answers nothing; elsewhere it answers as before.
  cv::Mat usable(64, 64, CV_8UC1, cv::Scalar(255));
  usable.rowRange(0, 32).setTo(0);
  responses.compute(image, usable);
  CHECK(responses.spread().at<std::uint8_t>(30, 31) == 0);
  CHECK(responses.spread().at<std::uint8_t>(40, 31) == 1);
  CHECK(responses.linear(0, 0, 2)[k] == 0);
  CHECK(responses.linear(0, 0, 0)[10 * responses.grid_cols() + 8] == OrientationResponses::kMaxResponse);
}

/// An RGB-D rig as the tests render it (colour Camera1 and depth Camera2 of 640x480, 2.5 cm
/// apart, over the test scene's clutter) and a detector of `mesh_path` with every cue, on
/// the coarse test models cached in a folder of its own.
struct RgbdDetection {
  static TrackerConfig config(const std::string& cache_dir) {
    TrackerConfig config = load_tracker_config(ICGP_TEST_DATA_DIR "/../configs/coarse_models.yaml");
    config.cache_dir = cache_dir;
    config.region.color_camera = "Camera1";
    config.region.depth_camera = "Camera2";
    config.depth.depth_camera = "Camera2";
    config.texture.color_camera = "Camera1";
    config.texture.depth_camera = "Camera2";
    return config;
  }

  static Intrinsics intrinsics() { return {600.0, 600.0, 319.5, 239.5, 640, 480}; }
  static Pose depth_T_color() { return {Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.025, 0.0, 0.0)}; }

  RgbdDetection(const std::string& mesh_path, const std::string& cache_prefix)
      : RgbdDetection(load_mesh(mesh_path), cache_prefix) {}
  RgbdDetection(Mesh body_mesh, const std::string& cache_prefix)
      : cache(cache_prefix),
        mesh(std::move(body_mesh)),
        scene(mesh, intrinsics(), intrinsics(), depth_T_color()),
        tracker_config(config(cache.path().string())),
        detector(tracker_config, mesh, "object", configured_cameras(tracker_config)) {}

  test::TempDir cache;
  Mesh mesh;
  test::SceneRenderer scene;
  TrackerConfig tracker_config;
  BodyDetector detector;
};

TEST_CASE("verified ranking: the look decides among close fits, the fit among alike looks") {
  const VerifiedRanking with_depth{0.25, 0.05};
  // A box turned a quarter fits its contour and depth better than the right pose, and looks
  // nothing like the image: the look ranks them.
  CHECK(rank_verified({{0.96, 0.40}, {0.90, 0.93}}, with_depth) == std::vector<std::size_t>{1, 0});
  // The two-colour box in the realistic servo cell (multi_region, seed 1, trial 73): a pose
  // 14 mm and a quarter turn off looked a little better than the right one and its symmetric
  // twin, and fitted far worse: the right pose first, its twin next.
  CHECK(rank_verified({{0.631, 0.944}, {0.829, 0.930}, {0.837, 0.928}}, with_depth) ==
        std::vector<std::size_t>{2, 1, 0});
  // Beyond the margin a pose does not compete on look; the rest follow by fit.
  CHECK(rank_verified({{0.50, 0.99}, {0.90, 0.70}, {0.40, 0.10}}, with_depth) == std::vector<std::size_t>{1, 0, 2});
  // Without depth the look alone ranks (clutter shaped like a can fits better).
  const VerifiedRanking without_depth{std::numeric_limits<double>::infinity(), 0.0};
  CHECK(rank_verified({{0.85, 0.95}, {0.61, 0.986}}, without_depth) == std::vector<std::size_t>{1, 0});
  // A plain shape (no appearance): the fit alone.
  CHECK(rank_verified({{0.7, 0.0}, {0.9, 0.0}, {0.8, 0.0}}, with_depth) == std::vector<std::size_t>{1, 2, 0});
  CHECK(rank_verified({}, with_depth).empty());
}

TEST_CASE("detection: the textured box is found in an RGB-D frame within 5 mm and 5 degrees, not in a blank one") {
  RgbdDetection rig(ICGP_MODELS_DIR "/textured_box/textured_box.obj", "icgp-detection-cache");
  BodyDetector& detector = rig.detector;

  const Pose truth = Pose::from_rotation_vector(Eigen::Vector3d(0.5, -0.6, 0.3), Eigen::Vector3d(0.03, -0.02, 0.45));
  const Frame frame = rig.scene.render(truth);
  check_found_within_5mm_5deg(detector.detect(frame), truth, "detection");

  // The same clutter of coloured squares without the box (a 1 mm speck in its place): a
  // painted square is no box, since nothing stands out of the plane.
  const Mesh nothing = speck();
  test::SceneRenderer clutter(nothing, RgbdDetection::intrinsics(), RgbdDetection::intrinsics(),
                              RgbdDetection::depth_T_color());
  for (const double z : {0.35, 0.45, 0.6}) {
    const Detection none = detector.detect(clutter.render(Pose(truth.rotation(), Eigen::Vector3d(0.0, 0.0, z))));
    INFO("clutter plane " << z + 0.3 << " m away");
    CHECK_FALSE(none.found);
  }

  Frame blank = frame;
  for (ColorImage& c : blank.colors) c.image = cv::Mat(c.image.size(), c.image.type(), cv::Scalar::all(0));
  for (DepthImage& d : blank.depths) d.depth = cv::Mat(d.depth.size(), CV_32F, cv::Scalar(0.f));
  const Detection none = detector.detect(blank);
  CHECK_FALSE(none.found);
  CHECK_FALSE(none.why_not.empty());
}

TEST_CASE("detection: templates made as the searches reach them match as those made at once") {
  RgbdDetection rig(ICGP_MODELS_DIR "/textured_box/textured_box.obj", "icgp-detection-lazy-cache");
  const std::unique_ptr<Tracker> tracker = build_tracker(rig.tracker_config, rig.mesh, "object");
  std::vector<const ViewpointModel*> regions;
  const ViewpointModel* depth = nullptr;
  for (const Modality* m : tracker->modalities("object")) {
    if (const auto* region = dynamic_cast<const RegionModality*>(m)) regions.push_back(&region->model());
    if (const auto* d = dynamic_cast<const DepthModality*>(m)) depth = &d->model();
  }
  const ShapeTemplates at_once(rig.mesh, regions, depth, 2, 15.0, 64);
  const ShapeTemplates on_demand(rig.mesh, regions, depth, 2, 15.0, 64, ShapeTemplates::Filling::kOnDemand);
  const auto made = [](const ShapeTemplates& t) {
    return std::count_if(t.templates().begin(), t.templates().end(), [](const auto& x) { return !x.contour.empty(); });
  };
  REQUIRE(on_demand.templates().size() == at_once.templates().size());
  CHECK(made(on_demand) == 0);

  // A search near the box as a camera sees it: the views it may reach are filled, few of all.
  const Pose truth = Pose::from_rotation_vector(Eigen::Vector3d(0.5, -0.6, 0.3), Eigen::Vector3d(0.03, -0.02, 0.45));
  const Frame frame = rig.scene.render(truth);
  OrientationPyramid pyramid_a(frame.colors.front()), pyramid_b(frame.colors.front());
  SearchWindow window;
  window.near = truth;
  window.radius_px = 40.0;
  window.min_distance = 0.35;
  window.max_distance = 0.55;
  window.max_rotation = 30.0 * kPi / 180.0;
  const std::vector<PoseCandidate> a = TemplateMatcher(at_once).match(pyramid_a, window, 0.5, 20);
  const std::vector<PoseCandidate> b = TemplateMatcher(on_demand).match(pyramid_b, window, 0.5, 20);
  INFO(made(on_demand) << " of " << made(at_once) << " templates made");
  CHECK(made(on_demand) > 0);
  CHECK(made(on_demand) < made(at_once) / 4);
  REQUIRE(!a.empty());
  REQUIRE(a.size() == b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK(a[i].template_index == b[i].template_index);
    CHECK(a[i].score == b[i].score);
    CHECK((a[i].camera_T_body.matrix() - b[i].camera_T_body.matrix()).norm() == 0.0);
  }
  // Every template made on demand is the one made at once; the closest view is the same.
  for (std::size_t i = 0; i < at_once.templates().size(); ++i)
    if (!on_demand.templates()[i].contour.empty())
      CHECK(on_demand.templates()[i].contour.size() == at_once.templates()[i].contour.size());
  CHECK(on_demand.closest_view(truth).direction == at_once.closest_view(truth).direction);
}

TEST_CASE("detection: the textured box is found by its keypoints in a grey image without depth") {
  const test::TempDir cache("icgp-detection-grey-cache");
  TrackerConfig config = load_tracker_config(ICGP_TEST_DATA_DIR "/../configs/coarse_models.yaml");
  config.cache_dir = cache.path().string();
  config.modalities = {cue::kRegion, cue::kTexture};
  const Mesh mesh = load_mesh(ICGP_MODELS_DIR "/textured_box/textured_box.obj");
  const Intrinsics color_k{600.0, 600.0, 319.5, 239.5, 640, 480};
  test::SceneRenderer scene(mesh, color_k, color_k, Pose());
  config.region.color_camera = "Camera1";
  config.texture.color_camera = "Camera1";
  BodyDetector detector(config, mesh, "object", configured_cameras(config));

  // Two views: the box face-on and turned, at two distances; the image grey, no depth.
  for (const Pose& truth :
       {Pose::from_rotation_vector(Eigen::Vector3d(0.4, 0.5, -0.2), Eigen::Vector3d(-0.02, 0.03, 0.5)),
        Pose::from_rotation_vector(Eigen::Vector3d(2.0, 0.3, -0.5), Eigen::Vector3d(0.04, 0.0, 0.55))}) {
    Frame frame = scene.render(truth);
    frame.depths.clear();
    for (ColorImage& c : frame.colors) cv::cvtColor(c.image, c.image, cv::COLOR_BGR2GRAY);
    check_found_within_5mm_5deg(detector.detect(frame), truth, "grey detection");
  }

  // The scene's clutter of coloured squares without the box, grey and without depth: the
  // contour of a square fits the box's, but no pose's render looks enough like the image.
  const Mesh nothing = speck();
  test::SceneRenderer clutter(nothing, color_k, color_k, Pose());
  for (const double z : {0.35, 0.45, 0.6}) {
    Frame frame = clutter.render(Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.0, z)));
    frame.depths.clear();
    for (ColorImage& c : frame.colors) cv::cvtColor(c.image, c.image, cv::COLOR_BGR2GRAY);
    const Detection none = detector.detect(frame);
    INFO("clutter plane " << z + 0.3 << " m away; why not: " << none.why_not);
    CHECK_FALSE(none.found);
    CHECK_FALSE(none.why_not.empty());
  }
}

TEST_CASE("detection: texture alignment pulls a pose a few millimetres off onto the textured box in a grey image") {
  const Mesh mesh = load_mesh(ICGP_MODELS_DIR "/textured_box/textured_box.obj");
  const Intrinsics color_k{600.0, 600.0, 319.5, 239.5, 640, 480};
  test::SceneRenderer scene(mesh, color_k, color_k, Pose());
  const Pose truth = Pose::from_rotation_vector(Eigen::Vector3d(0.4, 0.5, -0.2), Eigen::Vector3d(-0.02, 0.03, 0.6));
  cv::Mat grey;
  cv::cvtColor(scene.render(truth).colors.front().image, grey, cv::COLOR_BGR2GRAY);
  SceneRenderer renderer;
  TextureAlignment alignment(renderer, Body{"object", mesh, Pose()});
  // 4 mm across and 10 mm along the line of sight, 2 degrees: what a monocular contour
  // leaves (the shift along the line of sight barely changes the image).
  const Pose start = truth * Pose::from_rotation_vector(Eigen::Vector3d(0.0, 0.035, 0.0), Eigen::Vector3d(0.004, 0.0, 0.0));
  const Pose off(start.rotation(), start.translation() + Eigen::Vector3d(0.0, 0.0, 0.010));
  REQUIRE(translation_error_mm(off, truth) > 5.0);
  const std::optional<Pose> aligned = alignment.align(grey, color_k, Pose(), off);
  REQUIRE(aligned);
  const double t = translation_error_mm(*aligned, truth), r = rotation_error_deg(*aligned, truth);
  std::printf("texture alignment: from %.2f mm %.2f deg to %.2f mm %.2f deg\n", translation_error_mm(off, truth),
              rotation_error_deg(off, truth), t, r);
  CHECK(t < 1.5);
  CHECK(r < 0.5);
}

TEST_CASE("detection: the labelled can, whose shape fits any turn about its axis, is found at its label's turn") {
  RgbdDetection rig(ICGP_MODELS_DIR "/labelled_can/object.obj", "icgp-detection-can-cache");
  BodyDetector& detector = rig.detector;

  // Seen from the side, a little from above: the contour and the depth say nothing of the
  // turn about the can's (y) axis; only the label does.
  const Pose truth = Pose::from_rotation_vector(Eigen::Vector3d(0.35, 0.9, 0.05), Eigen::Vector3d(0.02, 0.01, 0.5));
  const Frame frame = rig.scene.render(truth);
  check_found_within_5mm_5deg(detector.detect(frame), truth, "labelled can");

  // Lost at a pose turned 15 degrees about its axis and 1 cm off: the local search turns it
  // back by the label, where the shape's fit alone would leave it turned.
  const Pose lost_at = Pose(truth.rotation(), truth.translation() + Eigen::Vector3d(0.01, 0.0, 0.0)) *
                       Pose::from_rotation_vector(Eigen::Vector3d(0.0, deg_to_rad(15.0), 0.0), Eigen::Vector3d::Zero());
  REQUIRE(rotation_error_deg(lost_at, truth) > 14.0);
  check_found_within_5mm_5deg(detector.search_near(frame, lost_at), truth, "labelled can, near a turned pose");
}

TEST_CASE("detection: a textureless body beside a copy of itself is not found, and alone it is") {
  RgbdDetection rig(ICGP_MODELS_DIR "/textureless_mug/textureless_mug.obj", "icgp-detection-mug-cache");
  // Seen from the side of its handle, a little from above; the copy 14 cm to its right,
  // turned the same way.
  const Pose truth = Pose::from_rotation_vector(Eigen::Vector3d(1.9, 0.0, 0.0), Eigen::Vector3d(-0.06, 0.0, 0.45));
  const Renderer::BodyHandle copy = rig.scene.renderer().add_body(rig.mesh, 3);
  rig.scene.renderer().set_body_pose(copy, Pose(truth.rotation(), truth.translation() + Eigen::Vector3d(0.14, 0.0, 0.0)));

  // Which of the two is the body is a guess: "not found", and the reason says so.
  const Detection two = rig.detector.detect(rig.scene.render(truth));
  INFO("why not: " << two.why_not);
  CHECK_FALSE(two.found);
  CHECK_THAT(two.why_not, Catch::Contains("two places"));

  rig.scene.renderer().set_body_visible(copy, false);
  check_found_within_5mm_5deg(rig.detector.detect(rig.scene.render(truth)), truth, "the mug without its copy");
}

TEST_CASE("detection: the two-colour box is found, and a box of its shape painted one colour is not") {
  RgbdDetection rig(ICGP_MODELS_DIR "/two_region/object.obj", "icgp-detection-two-colour-cache");
  // From the side and a little above: the lid's colour and the body's both show.
  const Pose truth = Pose::from_rotation_vector(Eigen::Vector3d(0.4, 0.5, 0.1), Eigen::Vector3d(0.02, -0.01, 0.5));
  const Detection found = rig.detector.detect(rig.scene.render(truth));
  INFO("why not: " << found.why_not);
  REQUIRE(found.found);
  CHECK(translation_error_mm(found.reference_T_body, truth) < 5.0);

  // Its shape in one colour, the body's mean: the grey levels of its shaded faces
  // correlate with the two-colour render, its colours do not differ where the box's do.
  Mesh one_colour = rig.mesh;
  for (MeshPart& part : one_colour.parts) part.material.diffuse_rgb = Eigen::Vector3f(0.45f, 0.35f, 0.4f);
  test::SceneRenderer painted(one_colour, RgbdDetection::intrinsics(), RgbdDetection::intrinsics(),
                              RgbdDetection::depth_T_color());
  const Detection look_alike = rig.detector.detect(painted.render(truth));
  INFO("why not: " << look_alike.why_not);
  CHECK_FALSE(look_alike.found);
}

TEST_CASE("detection: a box turned a quarter about its long axis, which its depth fits, is not verified") {
  // The view of textureless_pbvs, seed 2, trial 41, where the detector took the two-colour
  // box turned a quarter about its x axis (100 mm; 80 x 60 mm across it), 14.5 mm off: its
  // visible faces lie on the real box's, so depth fits it (0.92 of its points) while the
  // region cue's contour refutes it (0.44, under the loss bar of 0.5). The box in one
  // colour, so that no check of its look can refuse the turn in the cues' place.
  Mesh one_colour = load_mesh(ICGP_MODELS_DIR "/two_region/object.obj");
  for (MeshPart& part : one_colour.parts) part.material.diffuse_rgb = Eigen::Vector3f(0.45f, 0.35f, 0.4f);
  RgbdDetection rig(one_colour, "icgp-detection-quarter-turn-cache");
  Eigen::Matrix3d rotation;
  rotation << 0.8334, 0.5519, 0.0296, 0.4216, -0.6003, -0.6797, -0.3573, 0.5789, -0.7329;
  const Pose truth(Eigen::Quaterniond(rotation).normalized().toRotationMatrix(), Eigen::Vector3d(-0.022, 0.011, 0.45));
  const Pose quarter_turn =
      truth * Pose::from_rotation_vector(Eigen::Vector3d(deg_to_rad(90.0), 0.0, 0.0), Eigen::Vector3d(-0.0025, -0.0103, -0.0099));
  REQUIRE(rotation_error_deg(quarter_turn, truth) > 89.0);
  const Frame frame = rig.scene.render(truth);

  // Searched for near the quarter turn, as a recovery searches where the body was lost:
  // the right pose or nothing, never the turn (before, the turn at quality 0.64).
  const Detection near = rig.detector.search_near(frame, quarter_turn);
  if (near.found) {
    check_found_within_5mm_5deg(near, truth, "box near its quarter turn");
  } else {
    std::printf("box near its quarter turn: not found (%s)\n", near.why_not.c_str());
  }
  // In the whole image the right pose is found.
  check_found_within_5mm_5deg(rig.detector.detect(frame), truth, "box in one colour");
}

}  // namespace
}  // namespace icgp
