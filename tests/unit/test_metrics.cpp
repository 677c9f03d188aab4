// SPDX-License-Identifier: GPL-2.0-or-later
// Pose errors, ADD / ADD-S, AUC scores and the tracking summary against analytic truth.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "icgp/eval/joint_evaluation.h"
#include "icgp/eval/metrics.h"
#include "test_meshes.h"
#include "test_temp_dir.h"

using namespace icgp;
using Catch::Matchers::Contains;

namespace {

Pose rotation_about(const Eigen::Vector3d& axis, double degrees, const Eigen::Vector3d& t = Eigen::Vector3d::Zero()) {
  return Pose::from_rotation_vector(axis.normalized() * degrees * M_PI / 180.0, t);
}

/// A 10 cm square plate in the z = 0 plane (two triangles).
Mesh make_plate() {
  MeshPart part;
  part.vertices = {{-0.05f, -0.05f, 0.f}, {0.05f, -0.05f, 0.f}, {0.05f, 0.05f, 0.f}, {-0.05f, 0.05f, 0.f}};
  part.triangles = {{0, 1, 2}, {0, 2, 3}};
  Mesh mesh;
  mesh.parts.push_back(part);
  return mesh;
}

const Pose kTruth = rotation_about({1, 2, 3}, 40.0, {0.02, -0.01, 0.6});

}  // namespace

TEST_CASE("translation and rotation errors of cMo poses") {
  const Pose moved(kTruth.rotation(), kTruth.translation() + Eigen::Vector3d(0.003, 0.0, -0.004));
  CHECK(translation_error_mm(moved, kTruth) == Approx(5.0));
  CHECK(rotation_error_deg(moved, kTruth) == Approx(0.0).margin(1e-9));

  const Pose turned = kTruth * rotation_about({0, 1, 0}, 12.5);
  CHECK(rotation_error_deg(turned, kTruth) == Approx(12.5));
  CHECK(translation_error_mm(turned, kTruth) == Approx(0.0).margin(1e-9));
}

TEST_CASE("the geodesic rotation error stays accurate near 180 degrees") {
  for (const double degrees : {179.0, 179.99, 180.0}) {
    const Pose turned = kTruth * rotation_about({1, -1, 0.5}, degrees);
    CHECK(rotation_error_deg(turned, kTruth) == Approx(degrees).epsilon(1e-9));
  }
  // Past 180 the shorter way round is reported.
  CHECK(rotation_error_deg(kTruth * rotation_about({0, 0, 1}, 190.0), kTruth) == Approx(170.0));
}

TEST_CASE("a pure translation of 5 mm gives ADD = ADD-S = 5 mm") {
  // Along the plate's normal every other point is farther than the point itself, so
  // ADD-S picks the same point as ADD.
  const ModelPointErrors plate(make_plate());
  const Pose lifted = kTruth * Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 0.005));
  CHECK(plate.add(lifted, kTruth) == Approx(0.005));
  CHECK(plate.adds(lifted, kTruth) == Approx(0.005));

  // On a cube with only its corners (10 cm apart) each corner is still its own nearest.
  const ModelPointErrors corners(test::make_box(0.1f, 0.1f, 0.1f), 0);
  const Pose shifted = kTruth * Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.003, 0.004, 0));
  CHECK(corners.add(shifted, kTruth) == Approx(0.005));
  CHECK(corners.adds(shifted, kTruth) == Approx(0.005));

  // With the surface sampled, points sliding within a face may find a closer neighbour:
  // ADD stays exact and ADD-S can only be smaller.
  const ModelPointErrors cube(test::make_box(0.1f, 0.1f, 0.1f));
  CHECK(cube.add(shifted, kTruth) == Approx(0.005));
  CHECK(cube.adds(shifted, kTruth) <= 0.005 + 1e-12);
  CHECK(cube.adds(shifted, kTruth) > 0.0);
}

TEST_CASE("a cube turned by 90 degrees: large ADD, ADD-S about zero") {
  const Mesh box = test::make_box(0.1f, 0.1f, 0.1f);
  const Pose turned = kTruth * rotation_about({0, 0, 1}, 90.0);

  const ModelPointErrors corners(box, 0);
  CHECK(corners.adds(turned, kTruth) == Approx(0.0).margin(1e-9));
  // Every corner moves by sqrt(2) times its 5 sqrt(2) cm distance to the axis: 10 cm.
  CHECK(corners.add(turned, kTruth) == Approx(0.1));

  const ModelPointErrors cube(box);
  CHECK(cube.add(turned, kTruth) > 0.05);
  // The samples of one face do not land exactly on those of the face it turns onto:
  // ADD-S is a fraction of the sample spacing (0.06 m² over 2000 points: ~5.5 mm).
  CHECK(cube.adds(turned, kTruth) < 0.002);
  CHECK(cube.adds(turned, kTruth) < 0.05 * cube.add(turned, kTruth));
}

TEST_CASE("ADD-S through the k-d tree equals the brute-force nearest neighbour") {
  const ModelPointErrors cube(test::make_box(0.08f, 0.05f, 0.12f), 700);
  const auto& points = cube.points();
  for (const Pose& estimate : {kTruth * rotation_about({1, 1, 0}, 7.0, {0.004, -0.002, 0.01}),
                               kTruth * rotation_about({0, 1, 1}, 150.0), rotation_about({1, 0, 0}, 3.0)}) {
    double sum = 0.0;
    for (const auto& X : points) {
      double best = std::numeric_limits<double>::infinity();
      for (const auto& Y : points) best = std::min(best, (kTruth * X - estimate * Y).norm());
      sum += best;
    }
    CHECK(cube.adds(estimate, kTruth) == Approx(sum / points.size()).epsilon(1e-12));
  }
}

TEST_CASE("surface samples are deterministic, area-weighted, and the diameter is the largest vertex distance") {
  const Mesh box = test::make_box(0.2f, 0.1f, 0.05f);
  const ModelPointErrors a(box, 1000), b(box, 1000);
  REQUIRE(a.points().size() == 1000 + 8);
  CHECK(a.points() == b.points());
  CHECK(a.diameter() == Approx(std::sqrt(0.2 * 0.2 + 0.1 * 0.1 + 0.05 * 0.05)).epsilon(1e-6));

  // Faces of area 0.02, 0.01 and 0.005 m² (two each) get samples in that proportion.
  int on_xy_faces = 0, on_yz_faces = 0;
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d& p = a.points()[i];
    if (std::abs(std::abs(p.z()) - 0.025) < 1e-6) ++on_xy_faces;
    if (std::abs(std::abs(p.x()) - 0.1) < 1e-6) ++on_yz_faces;
  }
  const double total_area = 2 * (0.02 + 0.01 + 0.005);
  CHECK(std::abs(on_xy_faces - 1000 * 0.04 / total_area) <= 4);
  CHECK(std::abs(on_yz_faces - 1000 * 0.01 / total_area) <= 4);
}

TEST_CASE("AUC scores of constant errors") {
  CHECK(auc_score({0.02, 0.02, 0.02}, kYcbAucThreshold) == Approx(80.0));
  CHECK(auc_score({0.0}, kYcbAucThreshold) == Approx(100.0));
  CHECK(auc_score({0.1, 0.5}, kYcbAucThreshold) == Approx(0.0));
  CHECK(auc_score({0.0, 0.2}, kYcbAucThreshold) == Approx(50.0));
  CHECK(std::isnan(auc_score({}, kYcbAucThreshold)));
  // OPT: threshold 0.2 d on a 0..20 scale; an error of 0.1 d is halfway.
  CHECK(opt_auc_score({0.01, 0.01}, 0.5) == Approx(18.0));
  CHECK(opt_auc_score({0.05}, 0.5) == Approx(10.0));
}

TEST_CASE("median of odd and even counts") {
  CHECK(median({3.0, 1.0, 2.0}) == 2.0);
  CHECK(median({4.0, 1.0, 10.0, 2.0}) == 3.0);
  CHECK(std::isnan(median({})));
}

TEST_CASE("percentile: nearest rank of the sorted values") {
  const std::vector<double> ten{10, 9, 8, 7, 6, 5, 4, 3, 2, 1};
  CHECK(percentile(ten, 0.9) == 9.0);  // rank 0.9 * 9 = 8.1 -> the 9th smallest
  CHECK(percentile(ten, 0.0) == 1.0);
  CHECK(percentile(ten, 1.0) == 10.0);
  CHECK(percentile({5.0}, 0.9) == 5.0);
  CHECK(std::isnan(percentile({}, 0.5)));
}

TEST_CASE("tracking evaluation sums up a run and writes its summary and CSV") {
  TrackingEvaluation evaluation(test::make_box(0.1f, 0.1f, 0.1f));
  const Pose off(kTruth.rotation(), kTruth.translation() + Eigen::Vector3d(0.0, 0.002, 0.0));
  evaluation.add(0, kTruth, kTruth, true, 2.0, 0.9);
  evaluation.add(1, off, kTruth, true, 4.0, 0.8);
  evaluation.add(2, kTruth * rotation_about({1, 0, 0}, 3.0), kTruth, false, 1.0);
  evaluation.add(3, kTruth, std::nullopt, true, 10.0);

  const TrackingSummary s = evaluation.summary();
  CHECK(s.frames == 4);
  CHECK(s.tracked == 3);
  CHECK(s.frames_with_truth == 3);
  CHECK(s.mean_t_mm == Approx(2.0 / 3.0));
  CHECK(s.max_t_mm == Approx(2.0));
  CHECK(s.mean_r_deg == Approx(1.0));
  CHECK(s.max_r_deg == Approx(3.0));
  CHECK(s.median_ms == Approx(3.0));
  CHECK(s.hz == Approx(1000.0 / 3.0));
  CHECK(s.mean_ms == Approx(17.0 / 4.0));
  CHECK(s.add_auc > 97.0);
  CHECK(s.add_auc < 100.0);
  CHECK(s.adds_auc >= s.add_auc);
  CHECK(evaluation.frames()[3].has_truth == false);

  const std::string json = s.to_json().dump();
  std::size_t previous = 0;
  for (const char* key : {"\"frames\": 4", "\"tracked\": 3", "\"mean_t_mm\"", "\"max_t_mm\": 2", "\"mean_r_deg\"",
                          "\"max_r_deg\"", "\"add_auc\"", "\"adds_auc\"", "\"median_ms\": 3", "\"hz\""}) {
    const std::size_t at = json.find(key);
    INFO(key << " in " << json);
    REQUIRE(at != std::string::npos);
    CHECK(at >= previous);  // in the documented order
    previous = at;
  }

  const std::filesystem::path csv =
      std::filesystem::temp_directory_path() / ("icgp_test_metrics_" + std::to_string(getpid()) + ".csv");
  evaluation.write_csv(csv.string());
  std::ifstream in(csv);
  std::string header, line;
  std::getline(in, header);
  CHECK(header == "frame,tracked,quality,ms,t_mm,r_deg,add_mm,adds_mm,tx,ty,tz,rx,ry,rz");
  int lines = 0;
  std::string last;
  while (std::getline(in, line)) {
    ++lines;
    last = line;
  }
  CHECK(lines == 4);
  CHECK_THAT(last, Catch::Matchers::StartsWith("3,1,,10,,,,,"));
  std::filesystem::remove(csv);
}

TEST_CASE("joint evaluation: errors per direction in degrees and millimetres, frames without truth left out") {
  Joint joint = Joint::revolute("base", Pose(), Eigen::Vector3d::UnitX(), -3.0, 3.0);
  joint.directions.push_back({JointDirection::Kind::kTranslation, Eigen::Vector3d::UnitZ(), -0.1, 0.1, 0.0});
  JointEvaluation evaluation(joint);
  const std::vector<double> truth{0.5, 0.01};
  evaluation.add(0, {0.5 + M_PI / 180, 0.012}, &truth);  // 1 deg, 2 mm
  evaluation.add(1, {0.5 - 3 * M_PI / 180, 0.01}, &truth);  // 3 deg, 0 mm
  evaluation.add(2, {2.0, 0.05}, nullptr);
  CHECK_THROWS_WITH(evaluation.add(3, {0.5}, &truth), "JointEvaluation: frame 3: expected 2 joint values");

  const std::vector<JointEvaluation::DirectionSummary> s = evaluation.summary();
  REQUIRE(s.size() == 2);
  CHECK(s[0].unit == "deg");
  CHECK(s[0].frames_with_truth == 2);
  CHECK(s[0].mean_error == Approx(2.0));
  CHECK(s[0].max_error == Approx(3.0));
  CHECK(s[1].unit == "mm");
  CHECK(s[1].mean_error == Approx(1.0));
  CHECK(s[1].max_error == Approx(2.0));
  CHECK_THAT(evaluation.to_json().dump(), Catch::Matchers::Contains("\"unit\": \"mm\""));

  const test::TempDir dir("icgp_test_joint_evaluation");
  const std::string csv = dir.file("joints.csv");
  evaluation.write_csv(csv);
  std::ifstream in(csv);
  std::string header, line, last;
  std::getline(in, header);
  CHECK(header == "frame,q0,q0_truth,q0_error,q1,q1_truth,q1_error");
  int lines = 0;
  while (std::getline(in, line)) ++lines, last = line;
  CHECK(lines == 3);
  CHECK_THAT(last, Catch::Matchers::EndsWith(",50,,"));

  JointEvaluation none(joint);
  none.add(0, {0.0, 0.0}, nullptr);
  CHECK(std::isnan(none.summary()[0].mean_error));
}

TEST_CASE("one-direction joint values from the link's pose: the twist about the axis, the slide along it") {
  Joint hinge = Joint::revolute("base", Pose::from_rotation_vector(Eigen::Vector3d(0.1, 0.2, 0.0), Eigen::Vector3d(0.0, 0.03, -0.04)),
                                Eigen::Vector3d(-1.0, 0.0, 0.0), 0.0, 2.0);
  hinge.joint_T_link = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.0, 0.01));
  for (const double q : {0.0, 0.3, 1.5, -2.5})
    CHECK(*one_direction_joint_value(hinge, hinge.parent_T_link({q})) == Approx(q).margin(1e-12));
  const Joint slider = Joint::prismatic("base", Pose(), Eigen::Vector3d(0.0, 2.0, 0.0), -1.0, 1.0);
  CHECK(*one_direction_joint_value(slider, Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.01, 0.25, 0.0))) == Approx(0.25));
  Joint fixed;
  fixed.parent = "base";
  CHECK(!one_direction_joint_value(fixed, Pose()));
}

TEST_CASE("a run without ground truth has null errors in its summary") {
  TrackingEvaluation evaluation(test::make_box(0.1f, 0.1f, 0.1f));
  evaluation.add(0, kTruth, std::nullopt, true, 1.5);
  const TrackingSummary s = evaluation.summary();
  CHECK(s.frames_with_truth == 0);
  CHECK(std::isnan(s.mean_t_mm));
  const std::string json = s.to_json().dump();
  CHECK_THAT(json, Contains("\"mean_t_mm\": null"));
  CHECK_THAT(json, Contains("\"add_auc\": null"));
  CHECK_THAT(json, Contains("\"median_ms\": 1.5"));
}

TEST_CASE("JSON objects nest arrays of objects and escape strings") {
  JsonObject row;
  row.add("config", "edge \"+\" depth").add("n", 3).add("ok", true).add("x", std::nan(""));
  JsonObject root;
  root.add("rows", std::vector<JsonObject>{row});
  CHECK(root.dump() ==
        "{\n  \"rows\": [\n    {\n      \"config\": \"edge \\\"+\\\" depth\",\n      \"n\": 3,\n      \"ok\": true,\n"
        "      \"x\": null\n    }\n  ]\n}");
  CHECK(JsonObject().dump() == "{}");
  CHECK(JsonObject().add("a", 1).add_fields(JsonObject().add("b", 2.5)).dump() == "{\n  \"a\": 1,\n  \"b\": 2.5\n}");
}
