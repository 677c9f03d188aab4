// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp stereo`: vpMbIcgTracker with one colour camera against the same tracker with two
// (a stereo pair whose cues are fused in one Newton step), on a rendered stereo sequence
// with exact ground truth, through ViSP's API alone: what a second colour camera adds.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/core/vpTrackingException.h>

#include "commands.h"
#include "option_ranges.h"
#include "icgp/base/camera_names.h"
#include "icgp/eval/json_object.h"
#include "icgp/eval/metrics.h"
#include "icgp/eval/sequence.h"
#include "icgp/eval/sequence_run.h"
#include "icgp/eval/sequence_writer.h"
#include "icgp/model/model_cache.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/conversions.h"
#include "icgp/visp/rgbd_tracking_loop.h"
#include "icgp/visp/visp_camera_xml.h"
#include "icgp/visp/vpMbIcgTracker.h"
#include "single_thread_scope.h"
#include "text_table.h"
#include "timing_rounds.h"

namespace icgp::app {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// The colour cues of ViSP's colour cameras: edges and KLT points (icgp: region and texture).
constexpr int kColorTypes = vpMbIcgTracker::EDGE_TRACKER | vpMbIcgTracker::KLT_TRACKER;

struct StereoOptions {
  std::string sequence;  ///< empty: the default stereo sequence, rendered once into the cache
  std::string config;
  std::string summary;
  std::string csv;  ///< folder for the per-frame errors of each configuration; empty: none
  int frames = 0;
  bool stereo_camera_alone = false;  ///< also a row of the stereo camera on its own
};

/// The cameras a configuration tracks with: the sequence's colour camera "Camera1", its
/// stereo camera "Camera3", or both (ViSP's "Camera1" and "Camera2" of a two-camera tracker).
enum class Cameras { kFirst, kStereoAlone, kPair };

/// The sequence rendered when none is given: the textured box seen by a rectified pair 8 cm
/// apart, VGA, mild colour noise, antialiased edges, calm hand-held motion.
std::string default_stereo_sequence() {
  // The version in the folder name changes whenever these settings do.
  const fs::path dir = fs::path(default_model_cache_dir()) / "stereo-sequences" / "textured_box-b80-v1";
  if (fs::exists(dir / "sequence.yaml")) {
    std::cerr << "stereo sequence: " << dir.string() << " (rendered earlier)\n";
    return dir.string();
  }
  SequenceWriterOptions o;
  o.frame_count = 150;
  o.seed = 1;
  o.color_intrinsics = o.depth_intrinsics = o.stereo_intrinsics = Intrinsics::centred(640, 480, 600.0);
  o.depth_T_color = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.025, 0.0, 0.0));
  o.stereo = true;
  o.stereo_T_color = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.08, 0.0, 0.0));
  o.noise.color_sigma = 2.0;
  o.antialias_samples = 4;
  const std::string model = default_model_path();
  std::cerr << "stereo sequence: rendering " << o.frame_count << " frames of " << model << " into " << dir.string()
            << " (once; later runs reuse it)\n";
  SequenceWriter writer(o);
  writer.add_object(fs::path(model).stem().string(), load_any_mesh(model), Pose(), model);
  // Written beside and renamed, so that an interrupted render is not taken for a sequence.
  const fs::path partial = dir.string() + ".partial";
  fs::remove_all(partial);
  writer.write(partial.string());
  fs::rename(partial, dir);
  return dir.string();
}

/// Progress of a run on stderr: about every tenth of the frames, with the time left.
class Progress {
 public:
  Progress(std::string label, int total) : label_(std::move(label)), total_(total), begin_(Clock::now()) {}
  void done(int frames) {
    if (frames * 10 / total_ == (frames - 1) * 10 / total_ && frames != total_) return;
    const double elapsed = std::chrono::duration<double>(Clock::now() - begin_).count();
    const double left = elapsed / frames * (total_ - frames);
    std::fprintf(stderr, "  %s: frame %d/%d, %.1f s, about %.0f s left\n", label_.c_str(), frames, total_, elapsed,
                 left);
  }

 private:
  std::string label_;
  int total_;
  Clock::time_point begin_;
};

/// One configuration's results.
struct StereoRow {
  std::string name;
  int cameras = 1;
  TrackingSummary summary;
  int lost = 0;
  /// Mean absolute translation error along the colour camera's x, y and z (optical) axes, mm.
  Eigen::Vector3d mean_abs_axis_mm = Eigen::Vector3d::Zero();
};

/// Tracks the first `n_frames` frames with vpMbIcgTracker on the colour images of
/// `cameras`, started at frame 0's ground truth. A frame whose testTracking() throws counts
/// as lost; tracking goes on from the tracker's estimate, and the frame's errors count like
/// any other's. Errors are of Camera1's cMo (the stereo camera's alone moved into Camera1).
StereoRow run_configuration(const Sequence& sequence, int n_frames, const SequenceObject& object, const Mesh& mesh,
                            const TrackerConfig& config, Cameras cameras, const std::string& name,
                            const std::string& csv_path) {
  const bool stereo = cameras == Cameras::kPair;
  std::unique_ptr<vpMbIcgTracker> tracker =
      stereo ? std::make_unique<vpMbIcgTracker>(std::vector<int>{kColorTypes, kColorTypes})
             : std::make_unique<vpMbIcgTracker>(1, kColorTypes);
  tracker->setTrackerConfig(config);
  {
    const detail::StdoutSilencer quiet_parser;
    tracker->loadModel(object.mesh_path);
  }
  const vpCameraParameters cam1 = to_camera_parameters(sequence.color_intrinsics());
  const vpCameraParameters cam3 = to_camera_parameters(sequence.stereo_intrinsics());
  const vpHomogeneousMatrix c3Mc1 = to_homogeneous_matrix(sequence.stereo_T_color());
  // I1: the first (or only) camera of the tracker, I2: the second.
  vpImage<vpRGBa> I1, I2;
  const auto convert = [&](const Frame& frame) {
    const cv::Mat& first = frame.colors.at(0).image;
    const cv::Mat& second = frame.find_color(kStereoCamera)->image;
    to_vp_image(cameras == Cameras::kStereoAlone ? second : first, I1);
    if (stereo) to_vp_image(second, I2);
  };

  const auto start = [&](const Frame& first, const Pose& pose) {
    convert(first);
    const vpHomogeneousMatrix c1Mo0 = to_homogeneous_matrix(pose);
    if (stereo) {
      // The tracker's "Camera2" is the sequence's stereo camera "Camera3".
      tracker->setCameraParameters(cam1, cam3);
      tracker->setCameraTransformationMatrix("Camera2", c3Mc1);
      tracker->initFromPose(I1, I2, c1Mo0, c3Mc1 * c1Mo0);
    } else if (cameras == Cameras::kStereoAlone) {
      tracker->setCameraParameters(cam3);
      tracker->initFromPose(I1, c3Mc1 * c1Mo0);
    } else {
      tracker->setCameraParameters(cam1);
      tracker->initFromPose(I1, c1Mo0);
    }
  };
  const auto track = [&](const Frame& frame) {
    convert(frame);
    TrackedFrame outcome;
    const auto begin = Clock::now();
    if (stereo)
      tracker->track(I1, I2);
    else
      tracker->track(I1);
    outcome.ms = std::chrono::duration<double, std::milli>(Clock::now() - begin).count();
    vpHomogeneousMatrix cMo;
    tracker->getPose(cMo);
    if (cameras == Cameras::kStereoAlone) cMo = c3Mc1.inverse() * cMo;
    outcome.reference_T_body = to_pose(cMo);
    try {
      tracker->testTracking();
    } catch (const vpTrackingException&) {
      outcome.tracked = false;
    }
    outcome.quality = tracker->getTrackingQuality();
    return outcome;
  };

  // Times are of track() alone, single thread, as every icgp benchmark reports them; the
  // viewpoint models were generated (or read) above, with every core.
  const SingleThreadScope single_thread;
  StereoRow row{name, stereo ? 2 : 1};
  Progress progress(name, n_frames);
  const FrameSource frames = FrameSource::of(sequence, n_frames);
  const Pose first_truth = *frames.load(0).truth(object.name);
  const TrackingEvaluation evaluation = evaluate_sequence(
      frames, object.name, mesh, {start, track}, first_truth,
      [&](const Frame& frame, const TrackedFrame& outcome, const FrameEvaluation&) {
        row.lost += !outcome.tracked;
        if (const Pose* truth = frame.truth(object.name))
          row.mean_abs_axis_mm += (outcome.reference_T_body.translation() - truth->translation()).cwiseAbs() * 1000.0;
        progress.done(frame.index + 1);
      });
  row.summary = evaluation.summary();
  if (!csv_path.empty()) evaluation.write_csv(csv_path);
  if (row.summary.frames_with_truth > 0) row.mean_abs_axis_mm /= row.summary.frames_with_truth;
  return row;
}

void print_table(const std::vector<StereoRow>& rows) {
  TextTable table(columns({{"configuration", 34, true}}, {accuracy_columns(),
                                                           {{"|x| mm", 7}, {"|y| mm", 7}, {"|z| mm", 7}},
                                                           {{"median ms", 10}, {"Hz", 7}, {"lost", 6}}}));
  for (const StereoRow& row : rows) {
    const TrackingSummary& s = row.summary;
    table.text(row.name).accuracy(s, 3);
    for (int axis = 0; axis < 3; ++axis) table.number(row.mean_abs_axis_mm[axis], 2);
    char lost[32];
    std::snprintf(lost, sizeof lost, "%3d/%-3d", row.lost, s.frames);
    table.number(s.median_ms, 2).number(s.hz, 1).text(lost).end_row();
  }
  std::printf("\n");
  table.print();
}

void run_stereo(const StereoOptions& o) {
  const std::string dir = o.sequence.empty() ? default_stereo_sequence() : o.sequence;
  const Sequence sequence = Sequence::open(dir, visp_sequence_options());
  if (!sequence.has_stereo())
    throw std::runtime_error(dir + ": not a stereo sequence (no color2/; render one with `icgp make-sequence "
                                   "--stereo-baseline B`)");
  if (!sequence.has_ground_truth() || sequence.objects().size() != 1 || sequence.objects().front().mesh_path.empty())
    throw std::runtime_error(dir + ": stereo needs ground truth for one object with its mesh");
  const SequenceObject& object = sequence.objects().front();
  const Mesh mesh = load_any_mesh(object.mesh_path);
  const TrackerConfig config = benchmark_tracker_config(o.config);
  const int n_frames = o.frames > 0 ? std::min(o.frames, sequence.size()) : sequence.size();
  const double baseline_mm = sequence.stereo_T_color().inverse().translation().norm() * 1000.0;
  std::cerr << "stereo: " << n_frames << " frames of " << dir << ", object '" << object.name << "', baseline "
            << baseline_mm << " mm\n"
            << kModelsOnFirstUse;

  char two_name[64];
  std::snprintf(two_name, sizeof two_name, "two cameras (stereo, %.0f mm)", baseline_mm);
  struct Configuration {
    Cameras cameras;
    std::string name, csv_file;
  };
  std::vector<Configuration> configurations = {{Cameras::kFirst, "one camera (Camera1)", "one_camera.csv"}};
  if (o.stereo_camera_alone)
    configurations.push_back({Cameras::kStereoAlone, "one camera (Camera3 alone)", "stereo_camera_alone.csv"});
  configurations.push_back({Cameras::kPair, two_name, "two_cameras.csv"});
  std::vector<StereoRow> rows;
  std::vector<std::string> failures;
  const StereoRow* one = nullptr;
  const StereoRow* two = nullptr;
  rows.reserve(configurations.size());
  for (const Configuration& c : configurations) {
    const std::string csv = o.csv.empty() ? "" : (fs::path(o.csv) / c.csv_file).string();
    std::cerr << c.name << ":\n";
    try {
      if (!csv.empty()) fs::create_directories(o.csv);
      rows.push_back(run_configuration(sequence, n_frames, object, mesh, config, c.cameras, c.name, csv));
      if (c.cameras == Cameras::kFirst) one = &rows.back();
      if (c.cameras == Cameras::kPair) two = &rows.back();
    } catch (const std::exception& e) {
      std::cerr << c.name << " failed: " << e.what() << "\n";
      failures.push_back(c.name);
    }
  }
  print_table(rows);
  const double t_ratio = one && two ? one->summary.mean_t_mm / two->summary.mean_t_mm : NAN;
  const double r_ratio = one && two ? one->summary.mean_r_deg / two->summary.mean_r_deg : NAN;
  if (one && two)
    std::printf(
        "\nmean error one camera / two cameras: translation %.2fx, rotation %.2fx (> 1: the pair is more accurate)\n",
        t_ratio, r_ratio);
  std::printf(
      "\nvpMbIcgTracker through ViSP's API, colour images only (EDGE_TRACKER | KLT_TRACKER: region and\n"
      "texture cues, no depth), started at frame 0's ground truth, %s configuration.\n"
      "Errors of Camera1's cMo (Camera3 alone: its estimate moved into Camera1) against the ground truth,\n"
      "over every frame; |x| |y| |z|: mean absolute translation error along Camera1's axes (z: the optical\n"
      "axis). lost: frames whose testTracking() threw (tracking went on). Times: the track() call alone,\n"
      "single thread.\n",
      o.config.empty() ? "icgp's default" : ("the " + o.config).c_str());

  if (!o.summary.empty()) {
    std::vector<JsonObject> json_rows;
    for (const StereoRow& row : rows)
      json_rows.push_back(JsonObject()
                              .add("config", row.name)
                              .add("cameras", row.cameras)
                              .add("lost", row.lost)
                              .add("mean_abs_x_mm", row.mean_abs_axis_mm.x())
                              .add("mean_abs_y_mm", row.mean_abs_axis_mm.y())
                              .add("mean_abs_z_mm", row.mean_abs_axis_mm.z())
                              .add_fields(row.summary.to_json()));
    JsonObject()
        .add("sequence", dir)
        .add("baseline_mm", baseline_mm)
        .add("rows", json_rows)
        .add("mean_t_ratio_one_over_two", t_ratio)
        .add("mean_r_ratio_one_over_two", r_ratio)
        .write(o.summary);
    std::cout << "wrote " << o.summary << "\n";
  }
  throw_if_failed(failures);
}

}  // namespace

void register_stereo_command(CLI::App& app) {
  auto o = std::make_shared<StereoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "stereo", "vpMbIcgTracker with one colour camera vs a stereo pair fused in one step, on a rendered stereo sequence");
  cmd->add_option("--sequence", o->sequence,
                  "Stereo sequence with ground truth (icgp make-sequence --stereo-baseline B); default: the textured "
                  "box seen by a pair 80 mm apart, 150 frames, rendered once into the model cache")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--config", o->config,
                  "icgp tracker configuration (YAML); default: icgp's defaults (a sequence folder's icgp.yaml is not "
                  "read)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--frames", o->frames, "Use only the first N frames (default: all)")->check(integer_in(1, kMaxFramesRead));
  cmd->add_option("--summary", o->summary, "Write the table as JSON: {\"rows\": [...], ...}");
  cmd->add_flag("--stereo-camera-alone", o->stereo_camera_alone,
               "Also track with the stereo camera (Camera3) alone, its pose moved into Camera1 for the errors");
  cmd->add_option("--csv", o->csv, "Folder for each configuration's per-frame errors (one_camera.csv, two_cameras.csv)");
  cmd->callback([o] { run_stereo(*o); });
}

}  // namespace icgp::app
