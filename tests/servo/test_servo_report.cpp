// SPDX-License-Identifier: GPL-2.0-or-later
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include <yaml-cpp/yaml.h>

#include "../unit/test_temp_dir.h"
#include "icgp/servo/servo_report.h"

namespace fs = std::filesystem;
using icgp::servo::kDegree;
using icgp::servo::ServoResult;
using icgp::servo::ServoStep;
using icgp::servo::StopSpec;
using icgp::servo::TrialsSummary;
using icgp::test::TempDir;

namespace {

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::size_t count(const std::string& text, char c) { return static_cast<std::size_t>(std::count(text.begin(), text.end(), c)); }

ServoStep step(double time, double servo_t, double track_t, double track_r, double track_ms) {
  ServoStep s;
  s.time = time;
  s.servo_t = servo_t;
  s.servo_r = servo_t * 10.0;  // radians, anything
  s.track_t = track_t;
  s.track_r = track_r;
  s.velocity = vpColVector(6);
  for (unsigned i = 0; i < 6; ++i) s.velocity[i] = 0.01 * (i + 1) * (1.0 - time);
  s.servo_error_norm = servo_t * 2.0;
  s.render_ms = 3.0;
  s.track_ms = track_ms;
  s.control_ms = 0.1;
  return s;
}

/// Run a: 3 steps, converged at 0.1 s, tiny final error (a success).
ServoResult run_a() {
  ServoResult r;
  r.scenario = "pbvs_box";
  r.tracker = "icgp";
  r.seed = 1;
  r.converged = true;
  r.converged_step = 1;
  r.converged_time = 0.1;
  r.final_t = 0.0005;
  r.final_r = 0.05 * kDegree;
  r.steps_per_s = 30.0;
  r.steps = {step(0.0, 0.02, 0.001, 0.01, 10.0), step(0.1, 0.005, 0.002, 0.02, 12.0),
             step(0.2, 0.0005, 0.003, 0.03, 14.0)};
  r.mean_track_t = 0.002;
  r.max_track_t = 0.003;
  r.mean_track_r = 0.02;
  r.max_track_r = 0.03;
  r.max_vouched_track_t = 0.003;
  r.max_vouched_track_r = 0.03;
  r.median_track_ms = 12.0;
  return r;
}

/// Run b: 1 step, never converged, large final error, a safety stop it recovered from.
ServoResult run_b() {
  ServoResult r;
  r.scenario = "pbvs_box";
  r.tracker = "icgp";
  r.seed = 2;
  r.converged = false;
  r.final_t = 0.01;
  r.final_r = 2.0 * kDegree;
  r.steps_per_s = 20.0;
  r.safety_stops = 2;
  r.recovered = true;
  ServoStep s = step(0.0, 0.01, 0.009, 0.05, 20.0);
  s.safety_stop = true;
  s.lost = true;
  r.steps = {s};
  return r;
}

/// Run c: converged at 0.3 s, 0 steps logged, safety stop not recovered.
ServoResult run_c() {
  ServoResult r;
  r.scenario = "pbvs_box";
  r.tracker = "icgp";
  r.seed = 3;
  r.converged = true;
  r.converged_time = 0.3;
  r.final_t = 0.0009;
  r.final_r = 0.08 * kDegree;
  r.steps_per_s = 40.0;
  r.safety_stops = 1;
  r.recovered = false;
  r.steps = {step(0.0, 0.001, 0.004, 0.04, 16.0), step(0.1, 0.0009, 0.001, 0.01, 11.0)};
  r.max_vouched_track_t = 0.004;
  r.max_vouched_track_r = 0.04;
  return r;
}

/// Run d: "converged" by the estimate but the true final error is too large: not a success.
ServoResult run_d() {
  ServoResult r = run_a();
  r.seed = 4;
  r.converged_time = 0.5;
  r.final_t = 0.002;
  r.steps_per_s = 10.0;
  return r;
}

}  // namespace

TEST_CASE("succeeded needs convergence and the true final error within both thresholds", "[servo][report]") {
  StopSpec stop;
  stop.converged_translation = 0.001;
  stop.converged_rotation = 0.1 * kDegree;
  ServoResult r;
  r.converged = true;
  r.final_t = 0.001;  // exactly at the thresholds: success
  r.final_r = 0.1 * kDegree;
  CHECK(icgp::servo::succeeded(r, stop));
  r.final_t = std::nextafter(0.001, 1.0);
  CHECK_FALSE(icgp::servo::succeeded(r, stop));
  r.final_t = 0.0;
  r.final_r = std::nextafter(0.1 * kDegree, 1.0);
  CHECK_FALSE(icgp::servo::succeeded(r, stop));
  r.final_r = 0.0;
  CHECK(icgp::servo::succeeded(r, stop));
  r.converged = false;
  CHECK_FALSE(icgp::servo::succeeded(r, stop));
}

TEST_CASE("summarise computes the batch statistics", "[servo][report]") {
  StopSpec stop;  // 1 mm, 0.1 deg
  const std::vector<ServoResult> runs{run_a(), run_b(), run_c(), run_d()};
  const TrialsSummary s = icgp::servo::summarise(runs, stop);

  CHECK(s.scenario == "pbvs_box");
  CHECK(s.tracker == "icgp");
  CHECK(s.trials == 4);
  CHECK(s.converged == 2);  // a and c; d converged on its estimate but ends 2 mm away
  CHECK(s.success_rate == Approx(0.5));
  // final_t: 0.5, 10, 0.9, 2 mm -> median (0.9 + 2) / 2, max 10.
  CHECK(s.final_t_median == Approx(0.00145));
  CHECK(s.final_t_max == Approx(0.01));
  // final_r: 0.05, 2, 0.08, 0.05 deg -> median (0.05 + 0.08) / 2, max 2.
  CHECK(s.final_r_median == Approx(0.065 * kDegree));
  CHECK(s.final_r_max == Approx(2.0 * kDegree));
  // Over the successful runs a (0.1 s) and c (0.3 s).
  CHECK(s.converged_time_median == Approx(0.2));
  // Tracker error over the 3 + 1 + 2 + 3 = 9 steps.
  const double sum_t = (0.001 + 0.002 + 0.003) * 2 + 0.009 + 0.004 + 0.001;
  const double sum_r = (0.01 + 0.02 + 0.03) * 2 + 0.05 + 0.04 + 0.01;
  CHECK(s.mean_track_t == Approx(sum_t / 9.0));
  CHECK(s.max_track_t == Approx(0.009));
  CHECK(s.mean_track_r == Approx(sum_r / 9.0));
  CHECK(s.max_track_r == Approx(0.05));
  // On frames vouched for: b's one step was lost; c's first step is the largest left.
  CHECK(s.max_vouched_track_t == Approx(0.004));
  CHECK(s.max_vouched_track_r == Approx(0.04));
  // track ms: 10 12 14 20 16 11 10 12 14 -> sorted 10 10 11 12 12 14 14 16 20: median 12.
  CHECK(s.median_track_ms == Approx(12.0));
  // steps/s: 30 20 40 10 -> median 25.
  CHECK(s.steps_per_s == Approx(25.0));
  CHECK(s.safety_stops == 3);
  CHECK(s.recovered == 1);  // b recovered, c did not; a and d had no stop
}

TEST_CASE("summarise: no convergence gives -1, no runs throws", "[servo][report]") {
  StopSpec stop;
  const TrialsSummary s = icgp::servo::summarise({run_b()}, stop);
  CHECK(s.trials == 1);
  CHECK(s.converged == 0);
  CHECK(s.success_rate == 0.0);
  CHECK(s.converged_time_median == -1.0);
  CHECK(s.median_track_ms == Approx(20.0));
  CHECK_THROWS_AS(icgp::servo::summarise({}, stop), std::invalid_argument);
}

TEST_CASE("print_run and print_summaries write the numbers", "[servo][report]") {
  StopSpec stop;
  std::ostringstream run_text;
  icgp::servo::print_run(run_text, run_b(), stop);
  const std::string run = run_text.str();
  CHECK(run.find("pbvs_box") != std::string::npos);
  CHECK(run.find("icgp") != std::string::npos);
  CHECK(run.find("no") != std::string::npos);
  CHECK(run.find("10.000 mm") != std::string::npos);
  CHECK(run.find("2.000 deg") != std::string::npos);
  CHECK(run.find("safety stops       2 (recovered") != std::string::npos);
  CHECK(run.find("safety stops       0") == std::string::npos);  // once, with its count
  CHECK(run.find("joint-limit stops  0") != std::string::npos);

  std::ostringstream converged_text;
  icgp::servo::print_run(converged_text, run_a(), stop);
  CHECK(converged_text.str().find("yes, at step 1 (0.10 s") != std::string::npos);
  CHECK(converged_text.str().find("max on frames it vouched for 3.000 mm") != std::string::npos);
  CHECK(converged_text.str().find("safety stops       0") != std::string::npos);

  TrialsSummary other = icgp::servo::summarise({run_a(), run_b(), run_c(), run_d()}, stop);
  other.tracker = "visp (edge + KLT + dense depth)";
  const std::vector<TrialsSummary> summaries{icgp::servo::summarise({run_a()}, stop), other};
  std::ostringstream table_text;
  icgp::servo::print_summaries(table_text, summaries);
  const std::vector<std::string> table = lines_of(table_text.str());
  REQUIRE(table.size() == 3);
  CHECK(table[0].rfind("tracker", 0) == 0);
  CHECK(table[1].rfind("icgp ", 0) == 0);
  CHECK(table[1].find("100.0%") != std::string::npos);
  CHECK(table[2].find("50.0%") != std::string::npos);
  CHECK(table[2].find("1.450 / 10.000") != std::string::npos);
  // Aligned: every row as long as the header.
  CHECK(table[1].size() == table[0].size());
  CHECK(table[2].size() == table[0].size());
}

TEST_CASE("write_summary_json writes the contract keys in mm and degrees", "[servo][report]") {
  TempDir dir("icgp_test_servo_report_json");
  StopSpec stop;
  const TrialsSummary s = icgp::servo::summarise({run_a(), run_b(), run_c(), run_d()}, stop);

  const fs::path one = dir.path() / "nested" / "folder" / "summary.json";  // parents created
  icgp::servo::write_summary_json({s}, one.string());
  const std::string text = read(one);
  CHECK(text.find("\"success_rate\": 0.5") != std::string::npos);

  const YAML::Node json = YAML::LoadFile(one.string());
  REQUIRE(json.IsMap());
  for (const char* key : {"scenario", "tracker", "trials", "converged", "success_rate", "final_t_mm", "final_r_deg",
                          "median_track_ms", "steps_per_s", "safety_stops", "recovered", "converged_time_s_median",
                          "track_t_mm", "track_r_deg", "interrupted", "seed"})
    CHECK(json[key].IsDefined());
  CHECK(json.size() == 16);
  CHECK(json["seed"].IsNull());  // four runs of four seeds
  CHECK_FALSE(json["interrupted"].as<bool>());
  CHECK(json["scenario"].as<std::string>() == "pbvs_box");
  CHECK(json["tracker"].as<std::string>() == "icgp");
  CHECK(json["trials"].as<int>() == 4);
  CHECK(json["converged"].as<int>() == 2);
  CHECK(json["success_rate"].as<double>() == Approx(0.5));
  CHECK(json["final_t_mm"]["median"].as<double>() == Approx(1.45));
  CHECK(json["final_t_mm"]["max"].as<double>() == Approx(10.0));
  CHECK(json["final_r_deg"]["median"].as<double>() == Approx(0.065));
  CHECK(json["final_r_deg"]["max"].as<double>() == Approx(2.0));
  CHECK(json["median_track_ms"].as<double>() == Approx(12.0));
  CHECK(json["steps_per_s"].as<double>() == Approx(25.0));
  CHECK(json["safety_stops"].as<int>() == 3);
  CHECK(json["recovered"].as<int>() == 1);
  CHECK(json["converged_time_s_median"].as<double>() == Approx(0.2));
  CHECK(json["track_t_mm"]["mean"].as<double>() == Approx(s.mean_track_t * 1000.0));
  CHECK(json["track_t_mm"]["max"].as<double>() == Approx(9.0));
  CHECK(json["track_r_deg"]["mean"].as<double>() == Approx(s.mean_track_r / kDegree));
  CHECK(json["track_r_deg"]["max"].as<double>() == Approx(0.05 / kDegree));
  CHECK(json["track_t_mm"]["max_vouched"].as<double>() == Approx(4.0));
  CHECK(json["track_r_deg"]["max_vouched"].as<double>() == Approx(0.04 / kDegree));

  // Several summaries: an array; no converged run: null time.
  TrialsSummary failed = icgp::servo::summarise({run_b()}, stop);
  failed.tracker = "visp";
  const fs::path many = dir.path() / "compare.json";
  icgp::servo::write_summary_json({s, failed}, many.string());
  const YAML::Node array = YAML::LoadFile(many.string());
  REQUIRE(array.IsSequence());
  REQUIRE(array.size() == 2);
  CHECK(array[0]["tracker"].as<std::string>() == "icgp");
  CHECK(array[1]["tracker"].as<std::string>() == "visp");
  CHECK(array[1]["success_rate"].as<double>() == 0.0);
  CHECK(array[1]["converged_time_s_median"].IsNull());
  CHECK(array[1]["seed"].as<unsigned>() == 2);  // one run: its seed, which a replay of its log takes
}

TEST_CASE("write_step_csv writes a header and one line per step", "[servo][report]") {
  TempDir dir("icgp_test_servo_report_csv");
  ServoResult r = run_a();
  r.steps[1].velocity = vpColVector();  // an empty velocity is written as zeros
  r.steps[2].dropped = true;
  r.steps[2].wMc_true = vpHomogeneousMatrix(0.1, -0.2, 0.3, 0.0, 0.0, 0.0);  // written with every digit
  const fs::path path = dir.path() / "sub" / "steps.csv";
  icgp::servo::write_step_csv(r, path.string());
  const std::vector<std::string> lines = lines_of(read(path));
  REQUIRE(lines.size() == 1 + 3);
  CHECK(lines[0] ==
        "time,servo_t_mm,servo_r_deg,track_t_mm,track_r_deg,error_norm,v0,v1,v2,v3,v4,v5,"
        "lost,safety_stop,dropped,render_ms,track_ms,control_ms,skipped,command_delay_ms,"
        "camera_tx,camera_ty,camera_tz,camera_tux,camera_tuy,camera_tuz");
  for (const std::string& line : lines) CHECK(count(line, ',') == 25);
  CHECK(lines[1].rfind("0,20,", 0) == 0);  // time 0 s, servo error 20 mm
  CHECK(lines[2].find(",0,0,0,0,0,0,0,0,0,") != std::string::npos);  // zero velocity, flags
  CHECK(lines[3].find(",0,0,1,3,14,0.1,0,0,") != std::string::npos);  // dropped, timings, not skipped, no delay
  CHECK(lines[1].substr(lines[1].size() - 12) == ",0,0,0,0,0,0");      // the camera at the world's origin
  CHECK(lines[3].substr(lines[3].size() - 67) ==
        ",0.10000000000000001,-0.20000000000000001,0.29999999999999999,0,0,0");
}

TEST_CASE("plot_run draws error.png and velocity.png with gnuplot", "[servo][report]") {
  TempDir dir("icgp_test_servo_report_plot");
  ServoResult r = run_a();
  r.steps.push_back(run_b().steps.front());  // a safety stop and a lost frame to mark
  r.steps.back().time = 0.3;
  r.steps[0].track_t = 0.0;  // zero on a log scale must not break the plot
  const fs::path out = dir.path() / "plots";
  icgp::servo::plot_run(r, out.string());
  for (const char* name : {"error.png", "velocity.png"}) {
    const std::string png = read(out / name);
    REQUIRE(png.size() > 1000);
    CHECK(png.compare(0, 4, "\x89PNG") == 0);
  }
  CHECK(fs::exists(out / "servo_plot.gp"));
  CHECK_FALSE(fs::exists(out / "servo_plot.log"));

  // No steps at all still gives the two (empty) figures.
  ServoResult empty;
  empty.scenario = "nothing";
  icgp::servo::plot_run(empty, (dir.path() / "empty").string());
  CHECK(read(dir.path() / "empty" / "error.png").compare(0, 4, "\x89PNG") == 0);
  CHECK(read(dir.path() / "empty" / "velocity.png").compare(0, 4, "\x89PNG") == 0);
}

TEST_CASE("an output folder that cannot be created is named in the error", "[servo][report]") {
  TempDir dir("icgp_test_servo_report_errors");
  const fs::path blocker = dir.write("a_file", "not a folder\n");
  const std::string folder = (blocker / "out").string();
  StopSpec stop;
  const TrialsSummary s = icgp::servo::summarise({run_a()}, stop);
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(icgp::servo::write_summary_json({s}, folder + "/summary.json"), Contains(folder));
  CHECK_THROWS_AS(icgp::servo::write_summary_json({s}, folder + "/summary.json"), std::runtime_error);
  CHECK_THROWS_WITH(icgp::servo::write_step_csv(run_a(), folder + "/steps.csv"), Contains(folder));
  CHECK_THROWS_WITH(icgp::servo::plot_run(run_a(), folder), Contains(folder));
  // A path that is a folder cannot be written as a file.
  CHECK_THROWS_WITH(icgp::servo::write_step_csv(run_a(), dir.path().string()), Contains(dir.path().string()));
}

TEST_CASE("plot_run without gnuplot says so", "[servo][report]") {
  TempDir dir("icgp_test_servo_report_no_gnuplot");
  const char* old_path = std::getenv("PATH");
  const std::string saved = old_path ? old_path : "";
  ::setenv("PATH", dir.path().string().c_str(), 1);  // a folder without gnuplot
  std::string message;
  try {
    icgp::servo::plot_run(run_a(), (dir.path() / "plots").string());
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  ::setenv("PATH", saved.c_str(), 1);
  CHECK(message.find("gnuplot") != std::string::npos);
  CHECK(message.find("not installed") != std::string::npos);
}
