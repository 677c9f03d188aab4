// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp compare`: ViSP's vpMbGenericTracker and icgp's vpMbIcgTracker run through the same
// ViSP-API code (icgp::track_rgbd_sequence) on the same frames, single-threaded, side by
// side; plus what the ViSP layer costs vpMbIcgTracker over icgp's core tracker.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <visp3/mbt/vpMbGenericTracker.h>

#include "bench_runner.h"
#include "commands.h"
#include "icgp/eval/json_object.h"
#include "icgp/eval/metrics.h"
#include "icgp/eval/sequence.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/rgbd_tracking_loop.h"
#include "icgp/visp/visp_baseline.h"
#include "icgp/visp/vpMbIcgTracker.h"
#include "single_thread_scope.h"

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
  SequenceOptions sequence_options;
};

struct CompareRow {
  std::string tracker;
  std::string config;
  TrackingSummary summary;       ///< errors of the first round; times over all rounds
  std::vector<double> round_ms;  ///< each round's median time
};

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : " + ") + name;
  return text;
}

/// Errors against the ground truth and timing of the track() calls of a run.
TrackingSummary summarise(const std::vector<Frame>& frames, const std::string& body, const Mesh& mesh,
                          const RgbdRun& run) {
  TrackingEvaluation evaluation(mesh);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const Pose* truth = frames[i].truth(body);
    evaluation.add(frames[i].index, run.poses[i], truth ? std::optional<Pose>(*truth) : std::nullopt, true,
                   run.track_ms[i]);
  }
  return evaluation.summary();
}

/// How many times faster a row is than the reference row, as the median over rounds of the
/// ratio of their medians in the same round: a round's trackers run within seconds of each
/// other, so they meet the same load from elsewhere on the machine.
double speed_vs(const CompareRow& reference, const CompareRow& row) {
  std::vector<double> ratios;
  for (std::size_t r = 0; r < std::min(reference.round_ms.size(), row.round_ms.size()); ++r)
    ratios.push_back(reference.round_ms[r] / row.round_ms[r]);
  return ratios.empty() ? std::numeric_limits<double>::quiet_NaN() : median(ratios);
}

void print_table(const std::vector<CompareRow>& rows, const CompareRow* reference, int rounds) {
  std::printf("\n%-20s %-26s %8s %8s %9s %9s %10s %8s %14s\n", "tracker", "configuration", "mean mm", "max mm",
              "mean deg", "max deg", "median ms", "Hz", "speed vs ViSP");
  for (const CompareRow& row : rows) {
    const TrackingSummary& s = row.summary;
    const double speed = reference ? speed_vs(*reference, row) : std::numeric_limits<double>::quiet_NaN();
    std::printf("%-20s %-26s %8.2f %8.2f %9.2f %9.2f %10.2f %8.0f %13.2fx\n", row.tracker.c_str(), row.config.c_str(),
                s.mean_t_mm, s.max_t_mm, s.mean_r_deg, s.max_r_deg, s.median_ms, s.hz, speed);
  }
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
  TrackerConfig icgp_config = sequence_tracker_config(o.config, o.sequence);
  if (!o.modalities.empty()) icgp_config.modalities = o.modalities;
  const std::string icgp_name = joined(icgp_config.modalities);

  const int n_frames = o.frames > 0 ? std::min(o.frames, sequence.size()) : sequence.size();
  std::cerr << "loading " << n_frames << " frames of " << o.sequence << "\n";
  std::vector<Frame> frames;
  for (int i = 0; i < n_frames; ++i) frames.push_back(sequence.load(i));
  const vpHomogeneousMatrix cMo0 = to_homogeneous_matrix(*frames.front().truth(object.name));

  // Each job gives its row; the vpMbIcgTracker job also keeps its run for the overhead line.
  RgbdRun icg_run;
  struct Job {
    std::string tracker, config;
    std::function<TrackingSummary()> run;
  };
  std::vector<Job> jobs;
  for (const std::string& name : kVispConfigs) {
    jobs.push_back({kVispTracker, name, [&, name] {
                      const std::unique_ptr<vpMbGenericTracker> tracker =
                          make_visp_tracker(visp_reference_configuration(name), visp_files);
                      return summarise(frames, object.name, mesh,
                                       track_rgbd_sequence(*tracker, frames, visp_files, cMo0));
                    }});
  }
  jobs.push_back({kIcgTracker, icgp_name, [&] {
                    vpMbIcgTracker tracker;
                    tracker.setTrackerConfig(icgp_config);
                    icg_run = track_rgbd_sequence(tracker, frames, visp_files, cMo0);
                    return summarise(frames, object.name, mesh, icg_run);
                  }});
  // icgp's own Tracker, timed as `icgp bench` does: on the grey image the ViSP-API code
  // gives vpMbIcgTracker (the baseline of the layer's overhead), and on the colour image.
  std::vector<Frame> grey_frames = frames;
  for (Frame& frame : grey_frames) {
    cv::Mat& image = frame.colors.front().image;
    if (image.channels() == 3) cv::cvtColor(image, image, cv::COLOR_BGR2GRAY);
  }
  jobs.push_back({kCoreTracker, icgp_name + kGreySuffix,
                  [&] { return run_icgp(grey_frames, object.name, mesh, icgp_config); }});
  jobs.push_back({kCoreTracker, icgp_name + kColourSuffix,
                  [&] { return run_icgp(frames, object.name, mesh, icgp_config); }});

  std::cerr << "vpMbIcgTracker generates its viewpoint models on first use (10-30 s on 2 cores); later runs read them "
               "from the cache\n";
  // Every tracker runs once per round, in reverse order every other round: load from
  // elsewhere on the machine comes and goes over seconds, and is shared out between the
  // trackers of a round. The poses are the same every round (the trackers are deterministic).
  std::vector<std::optional<CompareRow>> results(jobs.size());
  std::vector<std::vector<double>> icg_overheads;  // per round: vpMbIcgTracker's and the core's median
  std::vector<bool> failed(jobs.size(), false);
  std::vector<std::string> failures;
  const SingleThreadScope single_thread;
  for (int round = 0; round < o.rounds; ++round) {
    double icg_ms = std::numeric_limits<double>::quiet_NaN(), core_ms = icg_ms;
    for (std::size_t k = 0; k < jobs.size(); ++k) {
      const std::size_t j = round % 2 == 0 ? k : jobs.size() - 1 - k;
      if (failed[j]) continue;
      const std::string name = jobs[j].tracker + " " + jobs[j].config;
      std::cerr << "[round " << round + 1 << "/" << o.rounds << ", " << k + 1 << "/" << jobs.size() << "] " << name
                << " ..." << std::flush;
      const auto begin = std::chrono::steady_clock::now();
      // A tracker that cannot run (no EGL for model generation, say) must not cost the
      // others' results: it is reported and the command fails at the end.
      TrackingSummary summary;
      try {
        summary = jobs[j].run();
      } catch (const std::exception& e) {
        std::cerr << " failed: " << e.what() << "\n";
        failures.push_back(name);
        failed[j] = true;
        continue;
      }
      if (!results[j]) results[j] = CompareRow{jobs[j].tracker, jobs[j].config, summary, {}};
      results[j]->round_ms.push_back(summary.median_ms);
      if (jobs[j].tracker == kIcgTracker) icg_ms = summary.median_ms;
      if (jobs[j].tracker == kCoreTracker && jobs[j].config == icgp_name + kGreySuffix) core_ms = summary.median_ms;
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
      std::fprintf(stderr, " %d frames in %.1f s (including set-up), median %.2f ms\n", n_frames, seconds,
                   summary.median_ms);
    }
    if (std::isfinite(icg_ms) && std::isfinite(core_ms)) icg_overheads.push_back({icg_ms, core_ms});
  }
  std::vector<CompareRow> rows;
  const CompareRow* reference = nullptr;
  for (std::optional<CompareRow>& row : results) {
    if (!row) continue;
    row->summary.median_ms = median(row->round_ms);
    row->summary.hz = 1000.0 / row->summary.median_ms;
    rows.push_back(std::move(*row));
  }
  for (const CompareRow& row : rows)
    if (row.tracker == kVispTracker && row.config == kReferenceConfig) reference = &row;
  print_table(rows, reference, o.rounds);

  // The ViSP layer's cost: what vpMbIcgTracker::track() takes (reading ViSP's grey image and
  // point cloud included) beyond icgp's Tracker::track on the same grey and depth images, in
  // the same round. Building the cloud is the caller's, the same for vpMbGenericTracker,
  // and not counted. NaN (null in the summary) when either run failed.
  std::vector<double> overheads, icg_ms, core_ms;
  for (const std::vector<double>& round : icg_overheads) {
    overheads.push_back((round[0] - round[1]) / round[0] * 100.0);
    icg_ms.push_back(round[0]);
    core_ms.push_back(round[1]);
  }
  const double overhead_percent = overheads.empty() ? std::numeric_limits<double>::quiet_NaN() : median(overheads);
  if (std::isfinite(overhead_percent))
    std::printf(
        "\nViSP-layer overhead of vpMbIcgTracker: track() %.3f ms (point cloud read included) vs\n"
        "icgp::Tracker::track %.3f ms on the same grey and depth images: %.1f%% of the frame time\n"
        "(median over rounds). Building the grey image and point cloud, the caller's work for either\n"
        "tracker: %.2f ms.\n",
        median(icg_ms), median(core_ms), overhead_percent, median(icg_run.convert_ms));

  if (!o.summary.empty()) {
    std::vector<JsonObject> json_rows;
    for (const CompareRow& row : rows)
      json_rows.push_back(
          JsonObject().add("tracker", row.tracker).add("config", row.config).add_fields(row.summary.to_json()));
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
                  "icgp tracker configuration (YAML) for vpMbIcgTracker; default: the sequence folder's icgp.yaml, "
                  "else icgp's defaults")
      ->check(CLI::ExistingFile);
  cmd->add_option("--modalities", o->modalities,
                  "vpMbIcgTracker's modalities, e.g. region,depth (overrides the configuration)")
      ->delimiter(',');
  cmd->add_option("--summary", o->summary,
                  "Write the table as JSON: {\"rows\": [...], \"visp_layer_overhead_percent\": x}");
  cmd->add_option("--frames", o->frames, "Use only the first N frames (default: all)")->check(CLI::PositiveNumber);
  cmd->add_option("--rounds", o->rounds,
                  "Run every tracker this many times, alternating the order, and time each by its fastest round")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  cmd->add_flag("--blender-principal-point", o->sequence_options.blender_principal_point, kBlenderPrincipalPointHelp);
  cmd->callback([o] { run_compare(*o); });
}

}  // namespace icgp::app
