// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp track`: runs the tracker over an RGB-D sequence from a known first pose, prints
// per-frame errors, quality and time, and writes the summary, a per-frame CSV and an
// overlay video on request.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <opencv2/core.hpp>
#include <optional>

#include "commands.h"
#include "icgp/eval/metrics.h"
#include "icgp/eval/sequence.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/visp_camera_xml.h"
#include "overlay_video.h"
#include "single_thread_scope.h"
#include "timed_icg_tracker.h"

namespace icgp::app {
namespace {

struct TrackOptions {
  std::string sequence;
  std::string model;
  std::string config;
  std::vector<std::string> modalities;
  std::string init_pose;
  std::string summary;
  std::string csv;
  std::string video;
  SequenceOptions sequence_options = visp_sequence_options();
  bool quiet = false;
};

/// The model: --model, else the one the sequence names for its only object.
std::string model_path(const TrackOptions& o, const Sequence& sequence) {
  if (!o.model.empty()) return o.model;
  if (sequence.objects().size() == 1 && !sequence.objects().front().mesh_path.empty())
    return sequence.objects().front().mesh_path;
  throw std::runtime_error("the sequence in " + o.sequence + " names no single model: give --model");
}

/// The body takes the name the sequence stores its ground truth under, so frames' truths
/// are found; a sequence without objects falls back to the model's file name.
std::string body_name(const Sequence& sequence, const std::string& model) {
  if (sequence.objects().size() == 1) return sequence.objects().front().name;
  return std::filesystem::path(model).stem().string();
}

std::optional<Pose> truth_of(const Frame& frame, const std::string& body) {
  const Pose* truth = frame.truth(body);
  return truth ? std::optional<Pose>(*truth) : std::nullopt;
}

std::string frame_line(const FrameEvaluation& e) {
  char line[160];
  if (e.has_truth)
    std::snprintf(line, sizeof line, "%5d %9.2f %8.2f %8.3f %8s %8.2f", e.frame, e.t_mm, e.r_deg, e.quality,
                  e.tracked ? "yes" : "LOST", e.ms);
  else
    std::snprintf(line, sizeof line, "%5d %9s %8s %8.3f %8s %8.2f", e.frame, "-", "-", e.quality,
                  e.tracked ? "yes" : "LOST", e.ms);
  return line;
}

/// Each cue's score and the standard deviation it was weighed with in the frame's last
/// iteration, "score/sigma", or "no-data" for a cue that abstained.
std::string cue_columns(const BodyResult& result) {
  std::string text;
  char value[48];
  for (const ModalityQuality& q : result.modalities) {
    if (q.abstained)
      std::snprintf(value, sizeof value, "%sno-data", text.empty() ? "" : " ");
    else
      std::snprintf(value, sizeof value, "%s%.2f/%.3g", text.empty() ? "" : " ", q.score, q.sigma);
    text += value;
  }
  return text;
}

std::string caption(const FrameEvaluation& e) {
  char text[160];
  if (e.has_truth)
    std::snprintf(text, sizeof text, "frame %d  %.2f mm  %.2f deg  quality %.2f%s", e.frame, e.t_mm, e.r_deg,
                  e.quality, e.tracked ? "" : "  LOST");
  else
    std::snprintf(text, sizeof text, "frame %d  quality %.2f%s", e.frame, e.quality, e.tracked ? "" : "  LOST");
  return text;
}

void print_summary(const TrackingSummary& s) {
  std::printf("\nframes     %d, tracked %d\n", s.frames, s.tracked);
  if (s.frames_with_truth > 0) {
    std::printf("translation mean %.2f mm, max %.2f mm\n", s.mean_t_mm, s.max_t_mm);
    std::printf("rotation   mean %.2f deg, max %.2f deg\n", s.mean_r_deg, s.max_r_deg);
    std::printf("ADD AUC    %.2f %%, ADD-S AUC %.2f %% (threshold 10 cm)\n", s.add_auc, s.adds_auc);
  } else {
    std::printf("no ground truth: errors not available\n");
  }
  std::printf("time       median %.2f ms (%.0f Hz), mean %.2f ms, single thread\n", s.median_ms, s.hz, s.mean_ms);
}

void run_track(const TrackOptions& o) {
  const Sequence sequence = Sequence::open(o.sequence, o.sequence_options);
  if (sequence.size() == 0) throw std::runtime_error("the sequence in " + o.sequence + " has no frames");
  const std::string model = model_path(o, sequence);
  const std::string body = body_name(sequence, model);
  const Mesh mesh = load_any_mesh(model);

  TrackerConfig config = sequence_tracker_config(o.config, o.sequence);
  if (!o.modalities.empty()) config.modalities = parse_cue_list(o.modalities);
  if (o.sequence_options.grey_without_depth) {
    // Without a depth camera the depth cue has nothing to read: the other cues track.
    config.modalities.erase(std::remove(config.modalities.begin(), config.modalities.end(), CueKind::kDepth),
                            config.modalities.end());
    if (config.modalities.empty())
      throw std::runtime_error("--grey-without-depth leaves no modality: the configuration has only depth");
  }

  const Frame first = sequence.load(0);
  Pose initial_pose;
  if (!o.init_pose.empty()) {
    initial_pose = read_pose_matrix_file(o.init_pose);
  } else if (const Pose* truth = first.truth(body)) {
    initial_pose = *truth;
  } else {
    throw std::runtime_error("the sequence in " + o.sequence + " has no ground truth for '" + body +
                             "' to start from: give --init-pose");
  }

  std::cout << "sequence   " << o.sequence << " (" << sequence.layout() << ", " << sequence.size() << " frames)\n"
            << "model      " << model << " as body '" << body << "'\n"
            << "modalities ";
  for (std::size_t i = 0; i < config.modalities.size(); ++i) std::cout << (i ? "," : "") << to_string(config.modalities[i]);
  std::cout << "\nstart      " << (o.init_pose.empty() ? "first ground-truth pose" : o.init_pose) << "\n" << std::flush;

  TimedIcgTracker tracker(config, mesh, body);
  TrackingEvaluation evaluation(mesh);
  std::optional<OverlayVideo> video;
  if (!o.video.empty()) video.emplace(o.video, mesh, sequence.frame_rate());

  if (!o.quiet)
    std::printf("\nframe      t mm    r deg  quality  tracked       ms  cue score/sigma (px; depth: m at 1 m)\n");
  const SingleThreadScope single_thread;
  tracker.start(first, initial_pose);
  int frames_without_depth = 0;
  for (int i = 0; i < sequence.size(); ++i) {
    const Frame frame = i == 0 ? first : sequence.load(i);
    if (!frame.depths.empty() && cv::countNonZero(frame.depths.front().depth) == 0) ++frames_without_depth;
    double ms = 0.0;
    const BodyResult result = tracker.track(frame, &ms);
    const std::optional<Pose> truth = truth_of(frame, body);
    const FrameEvaluation& e =
        evaluation.add(frame.index, result.reference_T_body, truth, result.tracked, ms, result.quality);
    if (!o.quiet) std::cout << frame_line(e) << "  " << cue_columns(result) << "\n";
    if (video) video->write(frame.colors.at(0), result.reference_T_body, truth ? &*truth : nullptr, caption(e));
  }

  const TrackingSummary summary = evaluation.summary();
  print_summary(summary);
  if (frames_without_depth > 0)
    std::cerr << "icgp: warning: " << frames_without_depth << " of " << sequence.size()
              << " frames have no valid depth measurement (every pixel 0, NaN, inf, negative or beyond "
              << o.sequence_options.max_depth << " m), so the depth cue measured nothing there; check the depth files\n";
  if (!o.summary.empty()) {
    summary.to_json().write(o.summary);
    std::cout << "wrote      " << o.summary << "\n";
  }
  if (!o.csv.empty()) {
    evaluation.write_csv(o.csv);
    std::cout << "wrote      " << o.csv << "\n";
  }
  if (video) std::cout << "wrote      " << o.video << " (red: estimate, green: ground truth)\n";
}

}  // namespace

void register_track_command(CLI::App& app) {
  auto o = std::make_shared<TrackOptions>();
  CLI::App* cmd = app.add_subcommand("track", "Track an object through an RGB-D sequence and report errors and timing");
  cmd->add_option("--sequence", o->sequence, "Sequence folder (ViSP teabox-blender / realsense layout or icgp's)")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--model", o->model, "Mesh or ViSP .cao (default: the sequence's own model)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--config", o->config, "Tracker configuration (YAML); default: the sequence folder's icgp.yaml, else icgp's defaults")
      ->check(CLI::ExistingFile);
  cmd->add_option("--modalities", o->modalities, "Modalities to use, e.g. region,depth (overrides the configuration)")
      ->delimiter(',');
  cmd->add_option("--init-pose", o->init_pose, "Initial cMo, 4x4 matrix file (default: the first ground-truth pose)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--summary", o->summary, "Write the summary as JSON");
  cmd->add_option("--csv", o->csv, "Write per-frame errors, quality, time and pose as CSV");
  cmd->add_option("--video", o->video, "Write an overlay video (.avi, MJPEG): estimate in red, ground truth in green");
  cmd->add_option("--color-intrinsics", o->sequence_options.color_intrinsics_file,
                  "ViSP XML with the colour camera (for ViSP layouts whose files are ambiguous)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--depth-intrinsics", o->sequence_options.depth_intrinsics_file,
                  "ViSP XML with the depth camera (default: <colour>_depth.xml)")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--blender-principal-point", o->sequence_options.blender_principal_point, kBlenderPrincipalPointHelp);
  cmd->add_flag("--grey-without-depth", o->sequence_options.grey_without_depth,
                "Track as a monocular grey camera: colour frames converted to grey, no depth (the depth modality is "
                "left out)");
  cmd->add_flag("--quiet", o->quiet, "Print only the summary");
  cmd->callback([o] { run_track(*o); });
}

}  // namespace icgp::app
