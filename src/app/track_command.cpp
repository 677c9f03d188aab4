// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp track`: runs the tracker over an RGB-D sequence from a known first pose, prints
// per-frame errors, quality and time, and writes the summary, a per-frame CSV and an
// overlay video on request. A sequence of several bodies (make-sequence --scene) is
// tracked whole: every body, links with their joints, each body's and joint's errors.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <opencv2/core.hpp>
#include <optional>

#include "commands.h"
#include "icgp/base/stop_request.h"
#include "icgp/tracker/cue_registry.h"
#include "icgp/detection/body_detector.h"
#include "icgp/eval/joint_evaluation.h"
#include "icgp/eval/metrics.h"
#include "icgp/eval/sequence.h"
#include "icgp/eval/single_body_tracker.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/tracker/tracker_builder.h"
#include "icgp/visp/visp_camera_xml.h"
#include "overlay_video.h"
#include "sequence_model.h"
#include "single_thread_scope.h"

namespace icgp::app {
namespace {

struct TrackOptions {
  std::string sequence;
  std::string model;
  std::string config;
  std::vector<std::string> modalities;
  std::string init_pose;
  std::string init = "truth";  ///< truth | detect (--init-pose given: that file)
  std::string summary;
  std::string csv;
  std::string video;
  SequenceOptions sequence_options = visp_sequence_options();
  bool quiet = false;
  bool independent = false;
};

std::string model_path(const TrackOptions& o, const Sequence& sequence) {
  return sequence_model_path(o.model, sequence, o.sequence);
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

/// The frames tracked and, with ground truth, the pose errors and AUCs of one body.
void print_errors(const TrackingSummary& s) {
  std::printf("frames     %d, tracked %d\n", s.frames, s.tracked);
  if (s.frames_with_truth > 0) {
    std::printf("translation mean %.2f mm, max %.2f mm\n", s.mean_t_mm, s.max_t_mm);
    std::printf("rotation   mean %.2f deg, max %.2f deg\n", s.mean_r_deg, s.max_r_deg);
    std::printf("ADD AUC    %.2f %%, ADD-S AUC %.2f %% (threshold 10 cm)\n", s.add_auc, s.adds_auc);
  }
}

void print_summary(const TrackingSummary& s) {
  std::printf("\n");
  print_errors(s);
  if (s.frames_with_truth == 0) std::printf("no ground truth: errors not available\n");
  std::printf("time       median %.2f ms (%.0f Hz), mean %.2f ms, single thread\n", s.median_ms, s.hz, s.mean_ms);
}

/// The configuration file's (or the sequence's icgp.yaml, or the defaults) with the
/// command line's modalities.
TrackerConfig tracking_config(const TrackOptions& o) {
  TrackerConfig config = sequence_tracker_config(o.config, o.sequence);
  if (!o.modalities.empty()) config.modalities = parse_cue_list(o.modalities);
  if (o.sequence_options.grey_without_depth) {
    // Without a depth camera the depth cue has nothing to read: the other cues track.
    config.modalities.erase(std::remove(config.modalities.begin(), config.modalities.end(), cue::kDepth),
                            config.modalities.end());
    if (config.modalities.empty())
      throw std::runtime_error("--grey-without-depth leaves no modality: the configuration has only depth");
  }
  return config;
}

void print_modalities(const TrackerConfig& config) {
  std::cout << "modalities ";
  for (std::size_t i = 0; i < config.modalities.size(); ++i) std::cout << (i ? "," : "") << config.modalities[i];
  std::cout << "\n";
}

void warn_frames_without_depth(int frames_without_depth, const Sequence& sequence, const TrackOptions& o) {
  if (frames_without_depth > 0)
    std::cerr << "icgp: warning: " << frames_without_depth << " of " << sequence.size()
              << " frames have no valid depth measurement (every pixel 0, NaN, inf, negative or beyond "
              << o.sequence_options.max_depth << " m), so the depth cue measured nothing there; check the depth files\n";
}

bool has_no_depth(const Frame& frame) {
  return !frame.depths.empty() && cv::countNonZero(frame.depths.front().depth) == 0;
}

void run_single_body_track(const TrackOptions& o, const Sequence& sequence) {
  const std::string model = model_path(o, sequence);
  const std::string body = sequence_body_name(sequence, model);
  const Mesh mesh = load_any_mesh(model);
  const TrackerConfig config = tracking_config(o);

  const Frame first = sequence.load(0);
  const bool detect = o.init == "detect";
  Pose initial_pose;
  if (!o.init_pose.empty()) {
    initial_pose = read_pose_matrix_file(o.init_pose);
  } else if (const Pose* truth = first.truth(body)) {
    initial_pose = *truth;
  } else if (!detect) {
    throw std::runtime_error("the sequence in " + o.sequence + " has no ground truth for '" + body +
                             "' to start from: give --init-pose or --init detect");
  }

  std::cout << "sequence   " << o.sequence << " (" << sequence.layout() << ", " << sequence.size() << " frames)\n"
            << "model      " << model << " as body '" << body << "'\n";
  print_modalities(config);
  std::cout << "start      "
            << (detect ? "detection (no pose given)" : o.init_pose.empty() ? "first ground-truth pose" : o.init_pose)
            << "\n" << std::flush;

  SingleBodyTracker tracker(config, mesh, body);
  std::optional<OverlayVideo> video;
  if (!o.video.empty()) video.emplace(o.video, mesh, sequence.frame_rate());

  if (!o.quiet)
    std::printf("\nframe      t mm    r deg  quality  tracked       ms  cue score/sigma (px; depth: m at 1 m)\n");
  const SingleThreadScope single_thread;
  // Detection: frames until the body is found are reported lost at the identity pose.
  bool started = !detect;
  BodyResult result;  // the last frame's, for its cue columns
  bool found_again = false;
  int frames_without_depth = 0, frames_found_again = 0;
  const auto start = [&](const Frame& frame, const Pose& pose) { tracker.start(frame, pose); };
  const auto track = [&](const Frame& frame) {
    double ms = 0.0;
    found_again = false;
    if (!started) {
      const auto begin = std::chrono::steady_clock::now();
      const Detection detection = tracker.start_by_detection(frame);
      started = detection.found;
      if (started) {
        result = tracker.track(frame);
      } else {
        result = BodyResult{body};
        if (!o.quiet) std::cout << "frame " << frame.index << ": not found: " << detection.why_not << "\n";
      }
      ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
    } else {
      result = tracker.track(frame, &ms, &found_again);
      frames_found_again += found_again;
    }
    return TrackedFrame::of(result, ms);
  };
  const TrackingEvaluation evaluation = evaluate_sequence(
      FrameSource::of(sequence, first), body, mesh, {start, track}, detect ? std::nullopt : std::optional<Pose>(initial_pose),
      [&](const Frame& frame, const TrackedFrame& outcome, const FrameEvaluation& e) {
        if (has_no_depth(frame)) ++frames_without_depth;
        if (!o.quiet)
          std::cout << frame_line(e) << "  " << cue_columns(result) << (found_again ? "  found again" : "") << "\n";
        const std::optional<Pose> truth = truth_of(frame, body);
        if (video) video->write(frame.colors.at(0), outcome.reference_T_body, truth ? &*truth : nullptr, caption(e));
      });

  const TrackingSummary summary = evaluation.summary();
  print_summary(summary);
  if (frames_found_again > 0) std::cout << "recovery   found again after a loss in " << frames_found_again << " frames\n";
  warn_frames_without_depth(frames_without_depth, sequence, o);
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


// ---- Several bodies ----------------------------------------------------------------------

/// A body of a multi-body sequence, how it is tracked and its errors.
struct TrackedBody {
  const SequenceObject* object = nullptr;
  bool link = false;  ///< tracked as a link of its parent (else free, --independent included)
  TrackingEvaluation evaluation;
  /// A link's joint errors: its tracked joint values or, tracked free, the one-direction
  /// joint value its pose relative to its parent's implies.
  std::optional<JointEvaluation> joint;
};

/// `path` with the body's name before the extension: run.csv -> run.lid.csv.
std::string per_body_path(const std::string& path, const std::string& body, const std::string& suffix = "") {
  const std::filesystem::path file(path);
  return (file.parent_path() / (file.stem().string() + "." + body + suffix + file.extension().string())).string();
}

void print_body_summary(const TrackedBody& body) {
  const TrackingSummary s = body.evaluation.summary();
  const SequenceObject& object = *body.object;
  const std::string role = !object.joint ? "free"
                           : body.link   ? "link of " + object.joint->parent
                                         : "free; a link of " + object.joint->parent + " in the sequence";
  std::printf("\nbody       %s (%s)\n", object.name.c_str(), role.c_str());
  print_errors(s);
  if (!body.joint) return;
  const std::vector<JointEvaluation::DirectionSummary> directions = body.joint->summary();
  for (std::size_t k = 0; k < directions.size(); ++k) {
    const JointEvaluation::DirectionSummary& d = directions[k];
    std::printf("joint %zu    mean %.3f %s, max %.3f %s over %d frames%s\n", k, d.mean_error, d.unit.c_str(), d.max_error,
                d.unit.c_str(), d.frames_with_truth, body.link ? "" : " (from the free poses)");
  }
}

/// "q 12.34/12.30 deg" for a link's joint values (estimate/truth), "" for other bodies.
std::string joint_columns(const TrackedBody& body, const std::vector<double>& values, const std::vector<double>* truth) {
  if (!body.joint || values.empty()) return "";
  std::string text = " q";
  char value[64];
  for (std::size_t k = 0; k < values.size(); ++k) {
    const bool rotation = body.object->joint->directions[k].kind == JointDirection::Kind::kRotation;
    const double unit = rotation ? 180.0 / kPi : 1000.0;
    if (truth)
      std::snprintf(value, sizeof value, " %.2f/%.2f %s", values[k] * unit, (*truth)[k] * unit, rotation ? "deg" : "mm");
    else
      std::snprintf(value, sizeof value, " %.2f %s", values[k] * unit, rotation ? "deg" : "mm");
    text += value;
  }
  return text;
}

const BodyResult& result_of(const std::vector<BodyResult>& results, const std::string& body) {
  for (const BodyResult& result : results)
    if (result.body == body) return result;
  throw std::logic_error("the tracker reported no result for body '" + body + "'");
}

/// Tracks every object of the sequence: the first free one is the tracker's main body, the
/// others come through TrackerConfig::bodies with their joints (none with --independent).
/// Every body and joint starts from the first frame's ground truth.
void run_multi_body_track(const TrackOptions& o, const Sequence& sequence) {
  if (!o.video.empty()) throw std::runtime_error("--video draws one body: a sequence of several bodies has no video");
  const std::vector<SequenceObject>& objects = sequence.objects();
  for (const SequenceObject& object : objects)
    if (object.mesh_path.empty())
      throw std::runtime_error("the sequence in " + o.sequence + " names no mesh for its object '" + object.name + "'");
  // The sequence lists parents before their links, so the first object is free.
  const SequenceObject& main = objects.front();

  TrackerConfig config = tracking_config(o);
  for (const SequenceObject& object : objects) {
    if (&object == &main) continue;
    BodyConfig body;
    body.name = object.name;
    body.mesh = object.mesh_path;
    if (!o.independent) body.joint = object.joint;
    config.bodies.push_back(body);
  }
  // Each mesh is read once: the evaluation and the tracker see the same one.
  std::map<std::string, Mesh> meshes;
  std::vector<TrackedBody> bodies;
  for (const SequenceObject& object : objects) {
    const Mesh& mesh = meshes.try_emplace(object.mesh_path, load_any_mesh(object.mesh_path)).first->second;
    TrackedBody body{&object, object.joint && !o.independent, TrackingEvaluation(mesh), std::nullopt};
    if (object.joint && (body.link || object.joint->size() == 1)) body.joint.emplace(*object.joint);
    bodies.push_back(std::move(body));
  }
  std::unique_ptr<Tracker> tracker = build_tracker(config, meshes.at(main.mesh_path), main.name,
                                                   [&](const std::string& path, double) { return meshes.at(path); });

  std::cout << "sequence   " << o.sequence << " (" << sequence.layout() << ", " << sequence.size() << " frames)\n"
            << "bodies     ";
  for (const TrackedBody& body : bodies)
    std::cout << (&body == &bodies.front() ? "" : ", ") << body.object->name
              << (body.link ? " (link of " + body.object->joint->parent + ")" : "");
  std::cout << (o.independent ? ", every link tracked as a free body (--independent)" : "") << "\n";
  print_modalities(config);
  std::cout << "start      every body and joint at the first frame's ground truth\n" << std::flush;

  // Free bodies first, then the joints, parents before links (the sequence's order).
  const Frame first = sequence.load(0);
  for (const TrackedBody& body : bodies) {
    const std::string& name = body.object->name;
    if (body.link) continue;
    const Pose* truth = first.truth(name);
    if (!truth) throw std::runtime_error("the sequence in " + o.sequence + " has no ground truth for '" + name + "'");
    tracker->body(name).reference_T_body = *truth;
  }
  for (const TrackedBody& body : bodies) {
    if (!body.link || body.object->joint->size() == 0) continue;
    const std::vector<double>* truth = first.joint_truth(body.object->name);
    if (!truth)
      throw std::runtime_error("the sequence in " + o.sequence + " has no joint ground truth for '" + body.object->name + "'");
    tracker->set_joint_values(body.object->name, *truth);
  }

  if (!o.quiet)
    std::printf("\nframe      t mm    r deg  quality  tracked       ms  body  joint estimate/truth  cue score/sigma\n");
  const SingleThreadScope single_thread;
  int frames_without_depth = 0;
  std::vector<double> frame_ms;
  std::vector<BodyResult> results;  // every body's, of the frame being reported
  // Every body's pose and joint values are set above: starting reads them all.
  const auto start = [&](const Frame& frame, const Pose&) { tracker->start(frame); };
  const auto track = [&](const Frame& frame) {
    const auto begin = std::chrono::steady_clock::now();
    results = tracker->track(frame);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
    return TrackedFrame::of(result_of(results, main.name), ms);
  };
  run_sequence(FrameSource::of(sequence, first), {start, track}, *first.truth(main.name), [&](const Frame& frame, const TrackedFrame& outcome) {
    if (has_no_depth(frame)) ++frames_without_depth;
    const double ms = outcome.ms;
    frame_ms.push_back(ms);
    for (TrackedBody& body : bodies) {
      const std::string& name = body.object->name;
      const BodyResult& result = result_of(results, name);
      const FrameEvaluation& e =
          body.evaluation.add(frame.index, result.reference_T_body, truth_of(frame, name), result.tracked, ms, result.quality);
      std::vector<double> joint_values = result.joint_values;
      if (body.joint && !body.link) {
        const Pose parent_T_link = result_of(results, body.object->joint->parent).reference_T_body.inverse() *
                                   result.reference_T_body;
        joint_values = {*one_direction_joint_value(*body.object->joint, parent_T_link)};
      }
      const std::vector<double>* joint_truth = frame.joint_truth(name);
      if (body.joint) body.joint->add(frame.index, joint_values, joint_truth);
      if (!o.quiet)
        std::cout << frame_line(e) << "  " << name << joint_columns(body, joint_values, joint_truth) << "  "
                  << cue_columns(result) << "\n";
    }
  });

  for (const TrackedBody& body : bodies) print_body_summary(body);
  const double median_ms = median(frame_ms);
  std::printf("\ntime       median %.2f ms (%.0f Hz) for all %zu bodies, single thread\n", median_ms, 1000.0 / median_ms,
              bodies.size());
  warn_frames_without_depth(frames_without_depth, sequence, o);
  if (!o.summary.empty()) {
    std::vector<JsonObject> entries;
    for (const TrackedBody& body : bodies) {
      JsonObject entry;
      entry.add("body", body.object->name).add("tracked_as", body.link ? "link" : "free");
      if (body.object->joint) entry.add("parent", body.object->joint->parent);
      entry.add_fields(body.evaluation.summary().to_json());
      if (body.joint) entry.add("joint", body.joint->to_json());
      entries.push_back(std::move(entry));
    }
    JsonObject().add("sequence", o.sequence).add("independent", o.independent).add("bodies", std::move(entries)).write(o.summary);
    std::cout << "wrote      " << o.summary << "\n";
  }
  if (!o.csv.empty()) {
    for (const TrackedBody& body : bodies) {
      const std::string path = per_body_path(o.csv, body.object->name);
      body.evaluation.write_csv(path);
      std::cout << "wrote      " << path << "\n";
      if (!body.joint) continue;
      const std::string joint_path = per_body_path(o.csv, body.object->name, ".joint");
      body.joint->write_csv(joint_path);
      std::cout << "wrote      " << joint_path << "\n";
    }
  }
}

void run_track(const TrackOptions& o) {
  // Ctrl-C stops between frames, and a model being generated between views: no cache file
  // is left half written.
  install_stop_on_sigint();
  const Sequence sequence = Sequence::open(o.sequence, o.sequence_options);
  if (sequence.size() == 0) throw std::runtime_error("the sequence in " + o.sequence + " has no frames");
  if (o.model.empty() && sequence.objects().size() > 1) {
    run_multi_body_track(o, sequence);
    return;
  }
  if (o.independent) throw std::runtime_error("--independent: the sequence in " + o.sequence + " is tracked as one body");
  run_single_body_track(o, sequence);
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
  cmd->add_option("--init", o->init,
                  "How the tracker starts: truth (the first ground-truth pose, or --init-pose) or detect (found in "
                  "the images alone; no truth or pose file is used, at the start or after a loss)")
      ->check(CLI::IsMember({"truth", "detect"}))
      ->excludes(cmd->get_option("--init-pose"));
  cmd->add_option("--summary", o->summary, "Write the summary as JSON (several bodies: one entry per body)");
  cmd->add_option("--csv", o->csv,
                  "Write per-frame errors, quality, time and pose as CSV (several bodies: one file per body, "
                  "<stem>.<body>.csv, and <stem>.<link>.joint.csv)");
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
  cmd->add_flag("--independent", o->independent,
                "On a sequence of several bodies: track every link as a free body, without its joint (a link's joint "
                "error is then measured from its pose relative to its parent's)");
  cmd->callback([o] { run_track(*o); });
}

}  // namespace icgp::app
