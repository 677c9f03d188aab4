// SPDX-License-Identifier: GPL-2.0-or-later
// Sequences of several bodies: independent motions, links driven along joint trajectories,
// their ground truth read back through Sequence, the make-sequence scene files and their
// errors, and the two scenes of scenes/.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>

#include "icgp/eval/sequence.h"
#include "icgp/eval/sequence_scene.h"
#include "icgp/eval/sequence_writer.h"
#include "icgp/io/mesh_loader.h"
#include "icgp/render/renderer.h"
#include "test_meshes.h"
#include "test_temp_dir.h"

using namespace icgp;
using Catch::Matchers::Contains;
using icgp::test::TempDir;
namespace fs = std::filesystem;

namespace {

const std::string kModels = ICGP_MODELS_DIR;
const std::string kScenes = ICGP_SCENES_DIR;

SequenceWriterOptions tiny_options(int frames) {
  SequenceWriterOptions options;
  options.frame_count = frames;
  options.color_intrinsics = options.depth_intrinsics = Intrinsics::centred(160, 120, 150.0);
  options.progress = false;
  return options;
}

double pose_difference(const Pose& a, const Pose& b) { return (a.matrix() - b.matrix()).norm(); }

/// A base box moving and spinning, an arm on a revolute joint, a slider on the arm with
/// two directions and a cap fixed to the slider: a chain of four bodies.
struct Chain {
  Pose world_T_base = Pose::from_rotation_vector(Eigen::Vector3d(0.1, -0.2, 0.05), Eigen::Vector3d(0.01, 0.0, -0.02));
  Eigen::Vector3d velocity{0.05, -0.02, 0.01};
  Eigen::Vector3d spin{0.0, 0.4, 0.1};
  Joint hinge = Joint::revolute("base", Pose::from_rotation_vector(Eigen::Vector3d(0.0, 0.0, 0.3), Eigen::Vector3d(0.0, 0.04, 0.0)),
                                Eigen::Vector3d(1.0, 0.0, 0.0), 0.0, 2.0);
  Joint slider;
  Joint cap;
  std::vector<JointTrajectory> hinge_trajectory{{0.1, 1.5, 0.4}};
  std::vector<JointTrajectory> slider_trajectory{{-0.01, 0.02, 0.3}, {0.0, -0.5, 0.5}};

  Chain() {
    hinge.joint_T_link = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.0, 0.03));
    slider.parent = "arm";
    slider.parent_T_joint = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.0, 0.03));
    slider.directions.push_back({JointDirection::Kind::kTranslation, Eigen::Vector3d(0.0, 0.0, 1.0), -0.02, 0.03, 5.0});
    slider.directions.push_back({JointDirection::Kind::kRotation, Eigen::Vector3d(0.0, 1.0, 0.0), -1.0, 1.0, 0.0});
    cap.parent = "slider";
    cap.parent_T_joint = Pose::from_rotation_vector(Eigen::Vector3d(0.2, 0.0, 0.0), Eigen::Vector3d(0.0, 0.01, 0.0));
  }

  SequenceWriter writer(int frames) const {
    SequenceWriter writer(tiny_options(frames));
    writer.add_object("base", test::make_box(0.06f, 0.06f, 0.06f), world_T_base, "", spin, velocity);
    writer.add_link("arm", test::make_box(0.02f, 0.02f, 0.06f), hinge, hinge_trajectory);
    writer.add_link("slider", test::make_box(0.01f, 0.01f, 0.01f), slider, slider_trajectory);
    writer.add_link("cap", test::make_box(0.01f, 0.002f, 0.01f), cap, {});
    return writer;
  }
};

/// q(t) as the brief of SequenceWriter states it, computed here on its own.
double trajectory_value(const JointTrajectory& j, double t) {
  return j.from + (j.to - j.from) * 0.5 * (1.0 - std::cos(2.0 * M_PI * t / j.period));
}

void check_same_joint(const Joint& read, const Joint& written) {
  CHECK(read.parent == written.parent);
  CHECK(pose_difference(read.parent_T_joint, written.parent_T_joint) < 1e-12);
  CHECK(pose_difference(read.joint_T_link, written.joint_T_link) < 1e-12);
  REQUIRE(read.size() == written.size());
  for (int k = 0; k < read.size(); ++k) {
    const JointDirection &r = read.directions[k], &w = written.directions[k];
    CHECK(r.kind == w.kind);
    CHECK((r.axis - w.axis).norm() < 1e-15);
    CHECK(r.min == Approx(w.min).margin(1e-15));
    CHECK(r.max == Approx(w.max).margin(1e-15));
    CHECK(r.stiffness == w.stiffness);
  }
}

/// The scene file `text` written into `dir` as scene.yaml; its path.
std::string scene_file(const TempDir& dir, const std::string& text) { return dir.write("scene.yaml", text); }

std::string read_error(const std::string& path) {
  try {
    read_sequence_scene(path, kModels);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("sequence writer: a link's ground truth is its parent's times parent_T_link of its joint truth") {
  TempDir dir("icgp_test_links");
  const Chain chain;
  const SequenceWriter writer = chain.writer(5);
  writer.write(dir.path().string());
  CHECK(fs::is_regular_file(dir.path() / "joints" / "arm.txt"));
  CHECK(!fs::exists(dir.path() / "joints" / "base.txt"));
  CHECK(!fs::exists(dir.path() / "joints" / "cap.txt"));  // a fixed joint has no values

  const Sequence sequence = Sequence::open(dir.path().string());
  REQUIRE(sequence.objects().size() == 4);
  CHECK(!sequence.objects()[0].joint);
  for (int i = 0; i < sequence.size(); ++i) {
    const Frame frame = sequence.load(i);
    const double t = i / sequence.frame_rate();
    // The joint truth is the trajectory at the frame's time.
    const std::vector<double>* hinge = frame.joint_truth("arm");
    const std::vector<double>* slider = frame.joint_truth("slider");
    REQUIRE(hinge);
    REQUIRE(slider);
    REQUIRE(hinge->size() == 1);
    REQUIRE(slider->size() == 2);
    CHECK((*hinge)[0] == Approx(trajectory_value(chain.hinge_trajectory[0], t)).margin(1e-14));
    for (int k = 0; k < 2; ++k)
      CHECK((*slider)[k] == Approx(trajectory_value(chain.slider_trajectory[k], t)).margin(1e-14));
    CHECK(frame.joint_truth("base") == nullptr);
    CHECK(frame.joint_truth("cap") == nullptr);
    // Each link's pose is its parent's composed with the joint at the joint truth.
    const Pose camera_T_arm = *frame.truth("base") * chain.hinge.parent_T_link(*hinge);
    const Pose camera_T_slider = camera_T_arm * chain.slider.parent_T_link(*slider);
    CHECK(pose_difference(*frame.truth("arm"), camera_T_arm) < 1e-12);
    CHECK(pose_difference(*frame.truth("slider"), camera_T_slider) < 1e-12);
    CHECK(pose_difference(*frame.truth("cap"), camera_T_slider * chain.cap.parent_T_link({})) < 1e-12);
  }
}

TEST_CASE("sequence writer: a moving body's truth is its start pose moved by velocity x time") {
  TempDir dir("icgp_test_moving_body");
  const Pose start = Pose::from_rotation_vector(Eigen::Vector3d(0.0, 0.3, 0.0), Eigen::Vector3d(-0.1, 0.0, 0.1));
  const Eigen::Vector3d velocity(0.12, -0.03, 0.02);
  SequenceWriter writer(tiny_options(5));
  writer.add_object("still", test::make_box(0.08f, 0.16f, 0.06f));
  writer.add_object("mover", test::make_box(0.05f, 0.05f, 0.05f), start, "", Eigen::Vector3d::Zero(), velocity);
  writer.write(dir.path().string());

  const Sequence sequence = Sequence::open(dir.path().string());
  for (int i = 0; i < sequence.size(); ++i) {
    const Frame frame = sequence.load(i);
    const Pose world_T_camera = writer.color_T_world(i).inverse();
    const Pose world_T_mover = world_T_camera * *frame.truth("mover");
    const double t = i / sequence.frame_rate();
    CHECK((world_T_mover.translation() - (start.translation() + t * velocity)).norm() < 1e-12);
    CHECK((world_T_mover.rotation() - start.rotation()).norm() < 1e-12);
    CHECK(pose_difference(world_T_camera * *frame.truth("still"), Pose()) < 1e-12);
    CHECK(frame.joint_ground_truth.empty());
  }
}

TEST_CASE("sequence reader: joints round-trip through sequence.yaml") {
  TempDir dir("icgp_test_joint_round_trip");
  const Chain chain;
  chain.writer(2).write(dir.path().string());
  const Sequence sequence = Sequence::open(dir.path().string());
  REQUIRE(sequence.objects()[1].joint);
  REQUIRE(sequence.objects()[2].joint);
  check_same_joint(*sequence.objects()[1].joint, chain.hinge);
  check_same_joint(*sequence.objects()[2].joint, chain.slider);
  REQUIRE(sequence.objects()[3].joint);
  check_same_joint(*sequence.objects()[3].joint, chain.cap);
}

TEST_CASE("sequence reader: a link's parent must be listed before it, its joint file must hold every frame") {
  TempDir dir("icgp_test_joint_reader_errors");
  Chain().writer(2).write(dir.path().string());
  const std::string yaml = test::read_bytes(dir.path() / "sequence.yaml");
  SECTION("unknown parent") {
    std::string edited = yaml;
    edited.replace(edited.find("parent: arm"), 11, "parent: nope");
    dir.write("sequence.yaml", edited);
    REQUIRE_THROWS_WITH(Sequence::open(dir.path().string()),
                        Contains("sequence.yaml: objects[2].parent: 'nope' is not an object listed before 'slider'"));
  }
  SECTION("a line missing") {
    dir.write("joints/arm.txt", "0.1\n");
    REQUIRE_THROWS_WITH(Sequence::open(dir.path().string()),
                        Contains("arm.txt: has 1 lines of joint values, expected one per frame (2)"));
  }
  SECTION("a value missing") {
    dir.write("joints/slider.txt", "0.1 0.2\n0.3\n");
    REQUIRE_THROWS_WITH(Sequence::open(dir.path().string()), Contains("slider.txt: line 2: expected 2 numbers, found 1"));
  }
}

TEST_CASE("sequence writer: a link's joint and trajectory are checked") {
  SequenceWriter writer(tiny_options(2));
  const Mesh box = test::make_box(0.05f, 0.05f, 0.05f);
  writer.add_object("base", box);
  const Joint hinge = Joint::revolute("base", Pose(), Eigen::Vector3d::UnitX(), 0.0, 1.0);
  CHECK_THROWS_WITH(writer.add_link("lid", box, Joint::revolute("nope", Pose(), Eigen::Vector3d::UnitX(), 0.0, 1.0), {{0.0, 1.0, 1.0}}),
                    Contains("link 'lid': parent 'nope' is not an object added before it"));
  CHECK_THROWS_WITH(writer.add_link("lid", box, hinge, {{0.0, 1.5, 1.0}}),
                    Contains("link 'lid': trajectory of direction 0 leaves the joint's limits"));
  CHECK_THROWS_WITH(writer.add_link("lid", box, hinge, {}), Contains("0 trajectories for a joint of 1 directions"));
  CHECK_THROWS_WITH(writer.add_link("base", box, hinge, {{0.0, 1.0, 1.0}}), Contains("'base' is used twice"));
}

TEST_CASE("make-sequence scenes: bodies, links and trajectories as the file gives them, parents first") {
  TempDir dir("icgp_test_scene");
  const std::string path = scene_file(dir, R"(bodies:
  - name: lid
    mesh: textured_box
    parent: box
    joint: revolute
    axis: [-1, 0, 0]
    origin: {t: [0, 0.03, -0.04], r_deg: [0, 0, 0]}
    limits_deg: [0, 110]
    trajectory: {from_deg: 10, to_deg: 90, period: 4}
  - name: box
    mesh: textureless_mug
    scale: 0.5
    pose: {t: [0.1, 0, 0], r_deg: [0, 90, 0]}
    velocity: [0.1, 0, 0]
    spin: [0, 1, 0]
)");
  const std::vector<SceneBody> bodies = read_sequence_scene(path, kModels);
  REQUIRE(bodies.size() == 2);
  CHECK(bodies[0].name == "box");
  CHECK(bodies[0].mesh_path == fs::path(kModels + "/textureless_mug/textureless_mug.obj").lexically_normal().string());
  CHECK(bodies[0].scale == 0.5);
  CHECK((bodies[0].velocity - Eigen::Vector3d(0.1, 0, 0)).norm() == 0.0);
  CHECK((bodies[0].world_T_object.rotation() * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitX()).norm() < 1e-12);
  CHECK(bodies[1].name == "lid");
  REQUIRE(bodies[1].joint);
  CHECK(bodies[1].joint->parent == "box");
  REQUIRE(bodies[1].trajectory.size() == 1);
  CHECK(bodies[1].trajectory[0].from == Approx(10 * M_PI / 180));
  CHECK(bodies[1].trajectory[0].to == Approx(90 * M_PI / 180));
  CHECK(bodies[1].trajectory[0].period == 4.0);
}

TEST_CASE("make-sequence scenes: errors name the file, the body and the field") {
  TempDir dir("icgp_test_scene_errors");
  const std::string box = "    mesh: textured_box\n";
  const std::string lid = "  - name: lid\n" + box + "    parent: box\n    joint: revolute\n";
  const auto error = [&](const std::string& text) { return read_error(scene_file(dir, text)); };
  const std::string file = (dir.path() / "scene.yaml").string();

  CHECK(error("bodies:\n  - name: box\n" + box + "  - name: box\n" + box) ==
        file + ": bodies.box.name: two bodies are named 'box'");
  CHECK(error("bodies:\n" + lid + "    trajectory: {from_deg: 0, to_deg: 10, period: 1}\n") ==
        file + ": bodies.lid.parent: no body is named 'box'");
  CHECK(error("bodies:\n  - name: a\n" + box + "    parent: b\n    joint: fixed\n  - name: b\n" + box +
              "    parent: a\n    joint: fixed\n") == file + ": bodies.a.parent: the parents form a cycle: a -> b -> a");
  CHECK_THAT(error("bodies:\n  - name: box\n" + box + lid +
                   "    limits_deg: [90, 0]\n    trajectory: {from_deg: 0, to_deg: 10, period: 1}\n"),
             Contains(file + ": bodies.lid.limits_deg: expected min <= max"));
  CHECK(error("bodies:\n  - name: box\n" + box + lid +
              "    limits_deg: [0, 45]\n    trajectory: {from_deg: 0, to_deg: 90, period: 1}\n") ==
        file + ": bodies.lid.trajectory: from 0 to 90 deg leaves the joint's limits [0, 45]");
  CHECK_THAT(error("bodies:\n  - name: box\n    mesh: no_such_model\n"),
             Contains(file + ": bodies.box.mesh: expected a model folder of " + kModels));
  CHECK(error("bodies:\n  - name: box\n" + box + lid + "    pose: {t: [0, 0, 0], r_deg: [0, 0, 0]}\n") ==
        file + ": bodies.lid.pose: a link is placed by its parent and joint");
  CHECK(error("bodies:\n  - name: box\n" + box + "    trajectory: {from_deg: 0, to_deg: 10, period: 1}\n") ==
        file + ": bodies.box.trajectory: only a link (a body with a parent) has a trajectory");
  CHECK_THAT(error("bodies:\n  - name: box\n" + box + lid), Contains(file + ": bodies.lid.trajectory: required"));

  // A mesh that cannot be read: named when the bodies are added to a writer.
  dir.write("broken.obj", "this is not a mesh\n");
  const std::vector<SceneBody> bodies = read_sequence_scene(scene_file(dir, "bodies:\n  - name: box\n    mesh: broken.obj\n"), kModels);
  SequenceWriter writer(tiny_options(1));
  CHECK_THROWS_WITH(add_scene_bodies(writer, bodies), Contains(file + ": bodies.box.mesh: cannot read the mesh: "));
}

TEST_CASE("scenes/hinged_box.yaml: the lid opens through 90 degrees on the base") {
  const std::vector<SceneBody> bodies = read_sequence_scene(kScenes + "/hinged_box.yaml", kModels);
  REQUIRE(bodies.size() == 2);
  REQUIRE(bodies[1].joint);
  const JointTrajectory& lid = bodies[1].trajectory.at(0);
  CHECK(std::abs(lid.to - lid.from) == Approx(M_PI / 2));
  // 100 frames at 30 fps, make-sequence's default: the last frame is within a degree of open.
  CHECK(std::abs(lid.at(99 / 30.0) - lid.to) < M_PI / 180);
  // Closed, the lid sits on the base's top face; open, it stands upright above the hinge.
  const Pose closed = bodies[1].joint->parent_T_link({0.0});
  const Pose open = bodies[1].joint->parent_T_link({M_PI / 2});
  CHECK((closed * Eigen::Vector3d(0, 0, 0.08) - Eigen::Vector3d(0, 0.03, 0.04)).norm() < 1e-12);
  CHECK((open * Eigen::Vector3d(0, 0, 0.08) - Eigen::Vector3d(0, 0.11, -0.04)).norm() < 1e-12);
}

TEST_CASE("scenes/crossing.yaml: the near body hides most of the far one for several frames, then leaves it") {
  // The default camera (640 x 480, f = 600 px) at a quarter of the size sees the same.
  TempDir dir("icgp_test_crossing");
  SequenceWriterOptions options = tiny_options(100);
  options.background.enabled = false;
  SequenceWriter writer(options);
  const std::vector<SceneBody> bodies = read_sequence_scene(kScenes + "/crossing.yaml", kModels);
  add_scene_bodies(writer, bodies);
  writer.write(dir.path().string());

  // Visible pixels of the box with and without the mug, rendered from the ground truth.
  Renderer renderer;
  const Renderer::BodyHandle box = renderer.add_body(load_mesh(bodies[0].mesh_path), 1);
  const Renderer::BodyHandle mug = renderer.add_body(load_mesh(bodies[1].mesh_path), 2);
  const Sequence sequence = Sequence::open(dir.path().string());
  int hidden_frames = 0, visible_after = 0, visible_before = 0;
  for (int i = 0; i < sequence.size(); ++i) {
    const Frame frame = sequence.load(i);
    renderer.set_body_pose(box, *frame.truth("box"));
    renderer.set_body_pose(mug, *frame.truth("mug"));
    const auto box_pixels = [&] {
      return cv::countNonZero(renderer.render(options.color_intrinsics, Pose(), kRenderIds).ids == 1);
    };
    renderer.set_body_visible(mug, true);
    const int seen = box_pixels();
    renderer.set_body_visible(mug, false);
    const int whole = box_pixels();
    REQUIRE(whole > 500);  // the box stays in view
    const double visible = double(seen) / whole;
    if (visible < 0.4) ++hidden_frames;
    if (visible > 0.99) (hidden_frames == 0 ? visible_before : visible_after)++;
  }
  CHECK(hidden_frames >= 5);
  CHECK(visible_before >= 10);
  CHECK(visible_after >= 10);
}
