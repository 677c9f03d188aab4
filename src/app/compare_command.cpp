// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp compare`: ViSP's vpMbGenericTracker and icgp's vpMbIcgTracker run through the same
// ViSP-API code (icgp::track_rgbd_sequence) on the same frames, single-threaded, side by
// side; plus what the ViSP layer costs vpMbIcgTracker over icgp's core tracker.
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <visp3/mbt/vpMbGenericTracker.h>

#include "commands.h"
#include "option_ranges.h"
#include "icgp/tracker/cue_registry.h"
#include "icgp/eval/json_object.h"
#include "icgp/eval/metrics.h"
#include "icgp/eval/sequence.h"
#include "icgp/eval/single_body_tracker.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/rgbd_tracking_loop.h"
#include "icgp/visp/visp_baseline.h"
#include "icgp/visp/visp_camera_xml.h"
#include "icgp/visp/vpMbIcgTracker.h"
#include "single_thread_scope.h"
#include "timing_rounds.h"

namespace icgp::app {
namespace {

const std::string kVispTracker = "vpMbGenericTracker";
const std::string kIcgTracker = "vpMbIcgTracker";
/// icgp's own tracker without the ViSP layer, the baseline of that layer's overhead.
const std::string kCoreTracker = "icgp::Tracker (core)";
const std::string kGreySuffix = ", grey";
const std::string kColourSuffix = ", colour";
/// The row every speed is compared with: ViSP's most complete RGB-D configuration.
const std::string kReferenceConfig = "edge + KLT + dense depth";
/// ViSP's configurations compared: the two most accurate RGB-D ones of visp_reference_configurations().
const std::vector<std::string> kVispConfigs = {kReferenceConfig, "edge + dense depth"};

struct CompareOptions {
  std::string sequence = std::string(ICGP_SOURCE_TEST_DATA_DIR) + "/teabox-blender";
  std::string config;
  std::vector<std::string> modalities;
  std::string summary;
  int frames = 0;
  int rounds = 3;
  SequenceOptions sequence_options = visp_sequence_options();
};

/// A row's tracker and configuration, the two columns of the table: its TimedJob name is
/// "tracker configuration".
struct RowName {
  std::string tracker, config;
  std::string name() const { return tracker + " " + config; }
};

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : " + ") + name;
  return text;
}

void print_table(const std::vector<TimedRow>& rows, const std::vector<RowName>& names, int rounds) {
  const TimedRow* reference = find_row(rows, RowName{kVispTracker, kReferenceConfig}.name());
  TextTable table(columns({{"tracker", 20, true}, {"configuration", 38, true}}, {accuracy_columns(), timing_columns()}));
  for (const RowName& name : names)
    if (const TimedRow* row = find_row(rows, name.name()))
      timing_cells(table.text(name.tracker).text(name.config).accuracy(row->summary), *row, reference);
  std::printf("\n");
  table.print();
  std::printf(
      "\n%s and %s run through the same ViSP-API code (grey image + organised point cloud);\n"
      "%s is icgp's tracker on the grey or colour image and the depth image, without the ViSP layer.\n"
      "Times are of the track() call alone, single thread (OpenMP and OpenCV limited to one). Every tracker\n"
      "ran %d rounds, in alternating order; median ms is the median over rounds of each round's median, and\n"
      "speed vs ViSP the median over rounds of %s '%s''s median / the row's median in the same\n"
      "round (> 1: faster). Absolute times vary with the machine's load; compare ratios.\n",
      kVispTracker.c_str(), kIcgTracker.c_str(), kCoreTracker.c_str(), rounds, kVispTracker.c_str(),
      kReferenceConfig.c_str());
}

void run_compare(const CompareOptions& o) {
  const Sequence sequence = Sequence::open(o.sequence, o.sequence_options);
  if (!sequence.has_ground_truth() || sequence.objects().size() != 1 || sequence.objects().front().mesh_path.empty())
    throw std::runtime_error("compare needs a sequence with ground truth for one object with a ViSP model: " +
                             o.sequence);
  if (sequence.size() == 0) throw std::runtime_error("the sequence in " + o.sequence + " has no frames");
  const SequenceObject& object = sequence.objects().front();
  const VispModelFiles visp_files = VispModelFiles::beside_model(object.mesh_path);
  const Mesh mesh = load_any_mesh(object.mesh_path);
  TrackerConfig icgp_config = benchmark_tracker_config(o.config);
  if (!o.modalities.empty()) icgp_config.modalities = parse_cue_list(o.modalities);
  const std::string icgp_name = joined(icgp_config.modalities);

  const int n_frames = o.frames > 0 ? std::min(o.frames, sequence.size()) : sequence.size();
  std::cerr << "loading " << n_frames << " frames of " << o.sequence << "\n";
  std::vector<Frame> frames;
  for (int i = 0; i < n_frames; ++i) frames.push_back(sequence.load(i));
  const Pose start = *frames.front().truth(object.name);
  const FrameSource colour_frames = FrameSource::of(frames);

  // Each job gives its row; the vpMbIcgTracker job also keeps its conversion times for the
  // overhead line.
  std::vector<double> icg_convert_ms;
  std::vector<RowName> names;
  std::vector<TimedJob> jobs;
  auto add_job = [&](RowName name, std::function<TrackingSummary()> run) {
    jobs.push_back({name.name(), std::move(run)});
    names.push_back(std::move(name));
  };
  for (const std::string& name : kVispConfigs) {
    add_job({kVispTracker, name}, [&, name] {
      const std::unique_ptr<vpMbGenericTracker> tracker =
          make_visp_tracker(visp_reference_configuration(name), visp_files);
      VispProgram<vpMbGenericTracker> program(*tracker, visp_files, kRgbdCameraTypes);
      return evaluate_sequence(colour_frames, object.name, mesh, program.as_run_tracker(), start).summary();
    });
  }
  // Without a file or a cue list vpMbIcgTracker keeps the defaults a ViSP program gets:
  // icgp's, with flow and edge standing in for depth (they sit out frames with depth).
  const bool class_defaults = o.config.empty() && o.modalities.empty();
  const std::string icg_row_config = class_defaults ? icgp_name + " (defaults)" : icgp_name;
  add_job({kIcgTracker, icg_row_config}, [&] {
    vpMbIcgTracker tracker(kRgbdTrackerTypes);
    if (!class_defaults) tracker.setTrackerConfig(icgp_config);
    VispProgram<vpMbIcgTracker> program(tracker, visp_files, kRgbdCameraTypes);
    const TrackingSummary summary =
        evaluate_sequence(colour_frames, object.name, mesh, program.as_run_tracker(), start).summary();
    icg_convert_ms = program.convert_ms();
    return summary;
  });
  // icgp's own Tracker, timed as `icgp bench` does: on the grey image the ViSP-API code
  // gives vpMbIcgTracker (the baseline of the layer's overhead), and on the colour image.
  std::vector<Frame> grey_frames = frames;
  for (Frame& frame : grey_frames) {
    cv::Mat& image = frame.colors.front().image;
    if (image.channels() == 3) cv::cvtColor(image, image, cv::COLOR_BGR2GRAY);
  }
  add_job({kCoreTracker, icgp_name + kGreySuffix}, [&] {
    return evaluate_tracker(FrameSource::of(grey_frames), object.name, mesh, icgp_config, start).summary();
  });
  add_job({kCoreTracker, icgp_name + kColourSuffix},
          [&] { return evaluate_tracker(colour_frames, object.name, mesh, icgp_config, start).summary(); });

  std::cerr << kModelsOnFirstUse;
  std::vector<std::string> failures;
  const SingleThreadScope single_thread;
  const std::vector<TimedRow> rows = run_rounds(jobs, o.rounds, n_frames, failures);
  print_table(rows, names, o.rounds);
  if (class_defaults) {
    const TrackerConfig defaults = vpMbIcgTracker(kRgbdTrackerTypes).getTrackerConfig();
    std::printf("\n%s (defaults): the class's own configuration, as a ViSP program gets it:\n%s, with %s standing in\n"
                "for depth (they work only in frames in which no camera delivers depth).\n",
                kIcgTracker.c_str(), joined(defaults.modalities).c_str(), joined(defaults.depth_stand_ins).c_str());
  }

  // The ViSP layer's cost: what vpMbIcgTracker::track() takes (reading ViSP's grey image and
  // point cloud included) beyond icgp's Tracker::track on the same grey and depth images,
  // in the same round. Building the cloud is the caller's, the same for vpMbGenericTracker,
  // and not counted. NaN (null in the summary) when either run failed.
  const TimedRow* icg = find_row(rows, RowName{kIcgTracker, icg_row_config}.name());
  const TimedRow* core = find_row(rows, RowName{kCoreTracker, icgp_name + kGreySuffix}.name());
  const double overhead_percent =
      median_over_rounds(icg, core, [](double icg_ms, double core_ms) { return (icg_ms - core_ms) / icg_ms * 100.0; });
  if (std::isfinite(overhead_percent))
    std::printf(
        "\nViSP-layer overhead of vpMbIcgTracker: track() %.3f ms (point cloud read included) vs\n"
        "icgp::Tracker::track %.3f ms on the same grey and depth images: %.1f%% of the frame time\n"
        "(median over rounds). Building the grey image and point cloud, the caller's work for either\n"
        "tracker: %.2f ms.\n",
        icg->summary.median_ms, core->summary.median_ms, overhead_percent, median(icg_convert_ms));

  if (!o.summary.empty()) {
    std::vector<JsonObject> json_rows;
    for (const RowName& name : names)
      if (const TimedRow* row = find_row(rows, name.name()))
        json_rows.push_back(
            JsonObject().add("tracker", name.tracker).add("config", name.config).add_fields(row->summary.to_json()));
    JsonObject().add("rows", json_rows).add("visp_layer_overhead_percent", overhead_percent).write(o.summary);
    std::cout << "wrote " << o.summary << "\n";
  }
  if (!failures.empty()) {
    std::string names;
    for (const std::string& name : failures) names += (names.empty() ? "" : ", ") + name;
    throw std::runtime_error(std::to_string(failures.size()) + " tracker(s) failed: " + names);
  }
}

}  // namespace

void register_compare_command(CLI::App& app) {
  auto o = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Run ViSP's vpMbGenericTracker and icgp's vpMbIcgTracker through the same ViSP-API code on one sequence");
  cmd->add_option("--sequence", o->sequence, "Sequence with ground truth and a ViSP model (.cao + .xml files)")
      ->check(CLI::ExistingDirectory)
      ->capture_default_str();
  cmd->add_option("--config", o->config,
                  "icgp tracker configuration (YAML) for vpMbIcgTracker; default: icgp's defaults (a sequence "
                  "folder's icgp.yaml is not read)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--modalities", o->modalities,
                  "vpMbIcgTracker's modalities, e.g. region,depth (overrides the configuration)")
      ->delimiter(',');
  cmd->add_option("--summary", o->summary,
                  "Write the table as JSON: {\"rows\": [...], \"visp_layer_overhead_percent\": x}");
  cmd->add_option("--frames", o->frames, "Use only the first N frames (default: all)")->check(integer_in(1, kMaxFramesRead));
  cmd->add_option("--rounds", o->rounds,
                  "Run every tracker this many times, alternating the order, and take speed ratios within a round")
      ->check(integer_in(1, kMaxRounds))
      ->capture_default_str();
  cmd->add_flag("--blender-principal-point", o->sequence_options.blender_principal_point, kBlenderPrincipalPointHelp);
  cmd->callback([o] { run_compare(*o); });
}

}  // namespace icgp::app
