// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp bench`: icgp's tracker and ViSP's vpMbGenericTracker on the same frames, in one
// process and one thread, so accuracy and speed compare directly.
#include <algorithm>
#include <cstdio>
#include <iostream>

#include "commands.h"
#include "option_ranges.h"
#include "icgp/tracker/cue_registry.h"
#include "icgp/eval/metrics.h"
#include "icgp/eval/sequence.h"
#include "icgp/eval/single_body_tracker.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/visp_baseline.h"
#include "icgp/visp/visp_camera_xml.h"
#include "single_thread_scope.h"
#include "timing_rounds.h"
#include "detect_bench.h"
#include "model_bench.h"
#include "sweep.h"
#include "visp_types_bench.h"

namespace icgp::app {
namespace {

/// The ViSP row every speed is compared with: ViSP's most complete RGB-D configuration.
const std::string kReferenceRow = "ViSP edge + KLT + dense depth";

struct BenchOptions {
  std::string sequence = std::string(ICGP_SOURCE_TEST_DATA_DIR) + "/teabox-blender";
  std::string config;
  std::string summary;
  std::string plot;  ///< --plot for --sweep or --detect; empty: each one's default
  std::string out;   ///< --out for --sweep, --detect or --model; empty: each one's default
  int frames = 0;
  int rounds = 3;
  bool ablation = false;
  bool sweep = false;
  SweepOptions sweep_options;
  bool detect = false;
  std::vector<std::string> objects;  ///< --detect, --model: only these
  bool visp_types = false;
  std::vector<std::string> more_sequences;  ///< --visp-types: sequences after --sequence
  bool model = false;
  SequenceOptions sequence_options = visp_sequence_options();
};

void print_table(const std::vector<TimedRow>& rows, int rounds) {
  const TimedRow* reference = find_row(rows, kReferenceRow);
  TextTable table(columns({{"configuration", 34, true}}, {accuracy_columns(), timing_columns()}));
  for (const TimedRow& row : rows) timing_cells(table.text(row.name).accuracy(row.summary), row, reference);
  std::printf("\n");
  table.print();
  std::printf("\nTimes are of the tracking call alone, single thread (OpenMP and OpenCV limited to one). Every\n"
              "configuration ran %d rounds, in alternating order; median ms is the median over rounds of each\n"
              "round's median, and speed vs ViSP the median over rounds of '%s''s median / the row's\n"
              "median in the same round (> 1: faster). Absolute times vary with the machine's load.\n",
              rounds, kReferenceRow.c_str());
}

/// Where icgp's time goes with `config`: one more run over `frames` with the tracker's cost
/// timing, each cue's and the render step's median ms per frame, and the rest of the frame
/// (the solve and the tracker's bookkeeping).
void print_cue_costs(const std::vector<Frame>& frames, const std::string& body, const Mesh& mesh,
                     const TrackerConfig& config, const std::string& name) {
  SingleBodyTracker tracker(config, mesh, body);
  tracker.tracker().set_cost_timing(true);
  std::vector<std::string> parts;
  std::vector<std::vector<double>> part_ms;
  std::vector<double> frame_ms, rest_ms;
  const auto add = [&](const std::string& part, double ms) {
    const std::size_t i = static_cast<std::size_t>(std::find(parts.begin(), parts.end(), part) - parts.begin());
    if (i == parts.size()) {
      parts.push_back(part);
      part_ms.emplace_back();
    }
    part_ms[i].push_back(ms);
  };
  run_sequence(FrameSource::of(frames), tracker.as_run_tracker(), *frames.front().truth(body),
               [&](const Frame&, const TrackedFrame& outcome) {
                 const FrameCosts& costs = tracker.tracker().last_costs();
                 double counted = costs.render_ms;
                 for (const FrameCosts::Cue& cue : costs.cues) {
                   add(cue.cue + (cue.camera.empty() ? "" : " (" + cue.camera + ")"), cue.ms);
                   counted += cue.ms;
                 }
                 add("render step", costs.render_ms);
                 frame_ms.push_back(outcome.ms);
                 rest_ms.push_back(outcome.ms - counted);
               });
  TextTable table({{"part of " + name, 34, true}, {"median ms", 10}, {"share", 7}});
  const double frame = median(frame_ms);
  for (std::size_t i = 0; i < parts.size(); ++i)
    table.text(parts[i]).number(median(part_ms[i]), 3).percent(100.0 * median(part_ms[i]) / frame).end_row();
  table.text("rest (solve, bookkeeping)").number(median(rest_ms), 3).percent(100.0 * median(rest_ms) / frame).end_row();
  table.text("whole frame").number(frame, 3).percent(100.0).end_row();
  std::printf("\n");
  table.print();
  std::printf("\nOne more run of %s with the tracker's cost timing (Tracker::set_cost_timing), single thread:\n"
              "a cue's time is its correspondences, gradients and finish; medians over frames, so the parts\n"
              "need not add up to the whole.\n",
              name.c_str());
}

void run_bench(const BenchOptions& o) {
  const Sequence sequence = Sequence::open(o.sequence, o.sequence_options);
  if (!sequence.has_ground_truth() || sequence.objects().size() != 1 || sequence.objects().front().mesh_path.empty())
    throw std::runtime_error("bench needs a sequence with ground truth for one object with a ViSP model: " +
                             o.sequence);
  if (sequence.size() == 0) throw std::runtime_error("the sequence in " + o.sequence + " has no frames");
  const SequenceObject& object = sequence.objects().front();
  const VispModelFiles visp_files = VispModelFiles::beside_model(object.mesh_path);
  const Mesh mesh = load_any_mesh(object.mesh_path);
  const TrackerConfig base_config = benchmark_tracker_config(o.config);

  const int n_frames = o.frames > 0 ? std::min(o.frames, sequence.size()) : sequence.size();
  std::cerr << "loading " << n_frames << " frames of " << o.sequence << "\n";
  std::vector<Frame> frames;
  for (int i = 0; i < n_frames; ++i) frames.push_back(sequence.load(i));
  const Pose start = *frames.front().truth(object.name);

  std::vector<TimedJob> jobs;
  for (const std::vector<std::string>& modalities :
       std::vector<std::vector<std::string>>{{"region", "depth", "texture"}, {"region", "depth"}, {"region"}, {"depth"}}) {
    // With texture it is ICG+ (with the configured descriptor, oriented_brief by default).
    std::string name = modalities.size() == 3 ? "ICG+" : "ICG";
    for (std::size_t i = 0; i < modalities.size(); ++i) name += (i ? " + " : " ") + modalities[i];
    jobs.push_back({name, [&, modalities] {
                      TrackerConfig config = base_config;
                      config.modalities = parse_cue_list(modalities);
                      return evaluate_tracker(FrameSource::of(frames), object.name, mesh, config, start).summary();
                    }});
  }
  for (const VispTrackerConfiguration& configuration : visp_reference_configurations()) {
    jobs.push_back({"ViSP " + configuration.name, [&, configuration] {
                      VispRgbdTracker tracker(configuration, visp_files);
                      return evaluate_sequence(FrameSource::of(frames), object.name, mesh, tracker.as_run_tracker(),
                                               start)
                          .summary();
                    }});
  }

  std::cerr << "ICG rows generate their viewpoint models on first use (10-30 s on 2 cores); later runs read them from the cache\n";
  std::vector<std::string> failures;
  const SingleThreadScope single_thread;
  const std::vector<TimedRow> rows = run_rounds(jobs, o.rounds, n_frames, failures);
  print_table(rows, o.rounds);
  std::string cues;
  for (const std::string& cue : base_config.modalities) cues += (cues.empty() ? "" : " + ") + cue;
  print_cue_costs(frames, object.name, mesh, base_config, "icgp " + cues);
  const TimedRow* reference = find_row(rows, kReferenceRow);

  if (!o.summary.empty()) {
    std::vector<JsonObject> json_rows;
    for (const TimedRow& row : rows)
      json_rows.push_back(JsonObject()
                              .add("config", row.name)
                              .add_fields(row.summary.to_json())
                              .add("speed_ratio", speed_ratio(reference, row)));
    JsonObject().add("rows", json_rows).write(o.summary);
    std::cout << "wrote " << o.summary << "\n";
  }
  throw_if_failed(failures);
}

}  // namespace

void register_bench_command(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand(
      "bench", "Compare icgp's tracker with ViSP's vpMbGenericTracker on one sequence: accuracy and speed");
  cmd->add_option("--sequence", o->sequence, "Sequence with ground truth and a ViSP model (.cao + .xml files)")
      ->check(CLI::ExistingDirectory)
      ->capture_default_str();
  cmd->add_option("--config", o->config,
                  "icgp tracker configuration (YAML) for the ICG rows; default: icgp's defaults (a sequence "
                  "folder's icgp.yaml is not read)")->check(CLI::ExistingFile);
  cmd->add_flag("--blender-principal-point", o->sequence_options.blender_principal_point, kBlenderPrincipalPointHelp);
  cmd->add_option("--summary", o->summary, "Write the table as JSON: {\"rows\": [...]}");
  cmd->add_option("--frames", o->frames, "Use only the first N frames (default: all; --sweep: frames per cell, default 60; --detect: frames per cell, default 12)")->check(integer_in(1, kMaxFramesWritten));
  cmd->add_flag("--ablation", o->ablation,
                 "Instead: ICG+ with each descriptor and without each cue (the paper's Tables III/IV) on "
                 "teabox-blender and rendered ambiguous-geometry sequences");
  CLI::Option* rounds =
      cmd->add_option("--rounds", o->rounds,
                      "Run every configuration this many times, alternating the order, and take speed ratios within "
                      "a round")
          ->check(integer_in(1, kMaxRounds))
          ->capture_default_str();
  CLI::Option* sweep =
      cmd->add_flag("--sweep", o->sweep,
                    "Instead: icgp's defaults, the reference parameters (icg_reference) and ViSP over 4 models x "
                    "3 depth sensors x 3 image conditions plus grey cells without depth, rendered with ground truth");
  sweep->excludes("--ablation");
  CLI::Option* detect =
      cmd->add_flag("--detect", o->detect,
                    "Instead: detection alone (no pose given) on rendered frames of 5 models at 0.3-1.0 m, with exact, "
                    "RealSense- and Kinect-class depth and grey without depth, beside distractors, partly occluded, "
                    "without the object and on a white table under a hunting auto-exposure, against vpKeyPoint "
                    "(docs/detection.md)");
  detect->excludes("--ablation")->excludes(sweep);
  rounds->excludes(sweep)->excludes("--ablation");
  cmd->add_option("--out", o->out,
                  "--sweep: folder of the cached sequences, ViSP models and plot script (default " +
                      SweepOptions().out + "); --detect: of its cached sequences and plot script (default " +
                      DetectBenchOptions().out + "); --model: of its caches and frames (default " +
                      ModelBenchOptions().out + ")");
  cmd->add_option("--plot", o->plot,
                  "--sweep: PNG of the mean error against depth noise (default " + SweepOptions().plot +
                      "); --detect: PNG of success against occlusion (default " + DetectBenchOptions().plot + ")");
  cmd->add_option("--object", o->objects,
                  "--detect: only this one of its objects (textured_box, two_region, labelled_can, "
                  "textureless_mug, figurine); --model: only this mesh (a folder of models/, or torus_10k); repeatable");
  CLI::Option* visp_types = cmd->add_flag(
      "--visp-types", o->visp_types,
      "Instead: every ViSP tracker type alone and combined (EDGE, KLT, EDGE+KLT, DEPTH_DENSE, DEPTH_NORMAL, each "
      "colour type + DEPTH_DENSE) with vpMbGenericTracker and vpMbIcgTracker on the same frames (docs/visp.md)");
  visp_types->excludes("--ablation")->excludes(sweep)->excludes(detect);
  CLI::Option* model = cmd->add_flag(
      "--model", o->model,
      "Instead: what a new object costs before its first tracked frame: viewpoint-model generation per kind for "
      "models/ and a 10k-triangle torus, the first frame through vpMbIcgTracker on an empty cache, cache size, "
      "memory");
  model->excludes("--ablation")->excludes(sweep)->excludes(detect)->excludes(visp_types)->excludes(rounds);
  cmd->add_option("--and-sequence", o->more_sequences,
                  "--visp-types: a further sequence with ground truth (repeatable); its ViSP files are written for "
                  "its mesh when it has no .cao")
      ->check(CLI::ExistingDirectory)
      ->needs(visp_types);
  cmd->add_flag("--quick", o->sweep_options.quick,
                "--sweep: one model, two conditions and its grey cell, 320x240, at most 8 frames (a test)")
      ->needs(sweep);
  cmd->add_option("--viewpoint-models", o->sweep_options.viewpoint_models,
                  "--sweep: YAML whose region_model/depth_model replace both presets' (e.g. coarse models for a test)")
      ->check(CLI::ExistingFile)
      ->needs(sweep);
  cmd->callback([o] {
    if (!o->objects.empty() && !o->detect && !o->model)
      throw CLI::ValidationError("--object", "needs --detect or --model");
    if (o->model) {
      ModelBenchOptions model_options;
      model_options.summary = o->summary;
      model_options.meshes = o->objects;
      if (!o->out.empty()) model_options.out = o->out;
      run_model_bench(model_options);
    } else if (o->visp_types) {
      VispTypesBenchOptions types_options;
      types_options.sequences.push_back(o->sequence);
      for (const std::string& dir : o->more_sequences) types_options.sequences.push_back(dir);
      types_options.frames = o->frames;
      types_options.rounds = o->rounds;
      types_options.summary = o->summary;
      types_options.sequence_options = o->sequence_options;
      run_visp_types_bench(types_options);
    } else if (o->detect) {
      DetectBenchOptions detect_options;
      detect_options.summary = o->summary;
      if (!o->plot.empty()) detect_options.plot = o->plot;
      if (!o->out.empty()) detect_options.out = o->out;
      detect_options.objects = o->objects;
      if (o->frames > 0) detect_options.frames = o->frames;
      run_detect_bench(detect_options);
    } else if (o->sweep) {
      SweepOptions sweep_options = o->sweep_options;
      sweep_options.summary = o->summary;
      if (!o->plot.empty()) sweep_options.plot = o->plot;
      if (!o->out.empty()) sweep_options.out = o->out;
      if (o->frames > 0) sweep_options.frames = o->frames;
      run_sweep(sweep_options);
    } else if (o->ablation) {
      run_ablation(o->summary, o->frames);
    } else {
      run_bench(*o);
    }
  });
}

}  // namespace icgp::app
