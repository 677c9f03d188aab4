// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp detect`: detection alone on every frame of a sequence (no tracking, no pose
// carried from frame to frame), each result against the frame's ground truth.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>

#include "commands.h"
#include "icgp/base/stop_request.h"
#include "icgp/detection/body_detector.h"
#include "icgp/eval/metrics.h"
#include "icgp/eval/sequence.h"
#include "icgp/tracker/tracker_builder.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/visp_camera_xml.h"
#include "sequence_model.h"
#include "single_thread_scope.h"

namespace icgp::app {
namespace {

/// How far a lost object has moved from its last trusted pose when `icgp detect` times the
/// local search: 2 cm and 10 degrees.
const Pose kLostDrift = Pose::from_rotation_vector(Eigen::Vector3d(0.0, 10.0 * kPi / 180.0, 0.0),
                                                   Eigen::Vector3d(0.02, 0.0, 0.0));

struct DetectOptions {
  std::string sequence;
  std::string model;
  std::string config;
  int frames = 0;
  double max_translation_mm = 5.0;
  double max_rotation_deg = 5.0;
  SequenceOptions sequence_options = visp_sequence_options();
  bool quiet = false;
};

void run_detect(const DetectOptions& o) {
  install_stop_on_sigint();  // as in `icgp track`: stops between frames and between views
  const Sequence sequence = Sequence::open(o.sequence, o.sequence_options);
  const std::string model = sequence_model_path(o.model, sequence, o.sequence);
  const std::string body = sequence_body_name(sequence, model);
  TrackerConfig config = sequence_tracker_config(o.config, o.sequence);
  if (o.sequence_options.grey_without_depth)
    config.modalities.erase(std::remove(config.modalities.begin(), config.modalities.end(), cue::kDepth),
                            config.modalities.end());
  const Mesh mesh = load_any_mesh(model);
  BodyDetector detector(config, mesh, body, configured_cameras(config));
  const ModelPointErrors surface(mesh);
  const int n = o.frames > 0 ? std::min(o.frames, sequence.size()) : sequence.size();
  std::cout << "sequence   " << o.sequence << " (" << sequence.layout() << ", " << n << " frames)\n"
            << "model      " << model << " as body '" << body << "'\n"
            << "detector   " << detector.templates().templates().size() << " templates over "
            << detector.templates().n_views() << " views (made as the searches reach them)\n";
  if (!o.quiet) std::printf("\nframe  found     t mm    r deg  ADD-S mm  quality  candidates       ms\n");

  const SingleThreadScope single_thread;
  int correct = 0, equivalent = 0, wrong = 0, missed = 0, without_object = 0, false_positives = 0;
  std::vector<double> ms, near_ms;
  int near_right = 0;
  for (int i = 0; i < n; ++i) {
    if (stop_requested()) throw StopRequested("stopped on request before frame " + std::to_string(i));
    const Frame frame = sequence.load(i);
    const auto begin = std::chrono::steady_clock::now();
    const Detection d = detector.detect(frame);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count());
    const Pose* truth = frame.truth(body);
    double t = -1.0, r = -1.0, adds_mm = -1.0;
    if (!truth) {
      ++without_object;
      false_positives += d.found;
    } else if (!d.found) {
      ++missed;
    } else {
      t = translation_error_mm(d.reference_T_body, *truth);
      r = rotation_error_deg(d.reference_T_body, *truth);
      adds_mm = 1e3 * surface.adds(d.reference_T_body, *truth);
      if (t <= o.max_translation_mm && r <= o.max_rotation_deg)
        ++correct;
      else if (adds_mm <= o.max_translation_mm)
        ++equivalent;  // the model's own symmetry: its surface is where the truth's is
      else
        ++wrong;
    }
    if (truth) {
      // The search recovery runs every frame after a loss, from a last trusted pose that
      // the object has since moved away from.
      const Pose last_trusted = *truth * kLostDrift;
      const auto near_begin = std::chrono::steady_clock::now();
      const Detection near = detector.search_near(frame, last_trusted);
      near_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - near_begin).count());
      near_right += near.found && translation_error_mm(near.reference_T_body, *truth) <= o.max_translation_mm &&
                    (rotation_error_deg(near.reference_T_body, *truth) <= o.max_rotation_deg ||
                     1e3 * surface.adds(near.reference_T_body, *truth) <= o.max_translation_mm);
    }
    if (o.quiet) continue;
    std::printf("%5d  %-5s %8.2f %8.2f  %8.2f  %7.3f  %10d %8.1f%s%s\n", frame.index, d.found ? "yes" : "no", t, r,
                adds_mm, d.quality, d.candidates, ms.back(), d.found ? "" : "  ", d.found ? "" : d.why_not.c_str());
  }
  const int with_object = n - without_object;
  std::printf("\nfound      %d of %d frames with the object within %.1f mm and %.1f deg (%.1f %%); %d at a pose the "
              "model's symmetry makes equivalent (ADD-S within %.1f mm); %d wrong, %d not found\n",
              correct, with_object, o.max_translation_mm, o.max_rotation_deg,
              with_object > 0 ? 100.0 * correct / with_object : 0.0, equivalent, o.max_translation_mm, wrong, missed);
  if (without_object > 0)
    std::printf("empty      %d of %d frames without the object returned a pose\n", false_positives, without_object);
  std::printf("time       median %.1f ms, p90 %.1f ms\n", median(ms), percentile(ms, 0.9));
  if (!near_ms.empty())
    std::printf("near       the local search after a loss, from the true pose moved 2 cm and turned 10 deg: %d of %zu "
                "frames right or equivalent, median %.1f ms, p90 %.1f ms\n",
                near_right, near_ms.size(), median(near_ms), percentile(near_ms, 0.9));
}

}  // namespace

void register_detect_command(CLI::App& app) {
  auto o = std::make_shared<DetectOptions>();
  CLI::App* cmd = app.add_subcommand("detect", "Detect the object in every frame of a sequence, without tracking, "
                                               "against the ground truth");
  cmd->add_option("--sequence", o->sequence, "Sequence folder (any layout `icgp track` reads)")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--model", o->model, "Mesh or ViSP .cao (default: the sequence's own model)")->check(CLI::ExistingFile);
  cmd->add_option("--config", o->config, "Tracker configuration (YAML; its detection section applies)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--frames", o->frames, "Detect in the first N frames only (default: all)")->check(CLI::Range(1, 100000));
  cmd->add_option("--max-translation-mm", o->max_translation_mm, "A detection within this translation error is right")
      ->check(CLI::Range(0.0, 1e4));
  cmd->add_option("--max-rotation-deg", o->max_rotation_deg, "... and within this rotation error")
      ->check(CLI::Range(0.0, 180.0));
  cmd->add_option("--color-intrinsics", o->sequence_options.color_intrinsics_file,
                  "ViSP XML with the colour camera (for ViSP layouts whose files are ambiguous)")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--grey-without-depth", o->sequence_options.grey_without_depth,
                "Detect in grey images without depth (colour converted to grey, depth left out)");
  cmd->add_flag("--quiet", o->quiet, "Print only the summary");
  cmd->callback([o] { run_detect(*o); });
}

}  // namespace icgp::app
