// SPDX-License-Identifier: GPL-2.0-or-later
#include "visp_types_bench.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <visp3/mbt/vpMbGenericTracker.h>

#include "commands.h"
#include "text_table.h"
#include "timing_rounds.h"
#include "single_thread_scope.h"
#include "icgp/eval/json_object.h"
#include "icgp/eval/metrics.h"
#include "icgp/eval/sequence_run.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/rgbd_tracking_loop.h"
#include "icgp/visp/visp_baseline.h"
#include "icgp/visp/vpMbIcgTracker.h"

namespace icgp::app {
namespace {

namespace fs = std::filesystem;

constexpr int kEdge = vpMbGenericTracker::EDGE_TRACKER, kKlt = vpMbGenericTracker::KLT_TRACKER;
constexpr int kDense = vpMbGenericTracker::DEPTH_DENSE_TRACKER, kNormal = vpMbGenericTracker::DEPTH_NORMAL_TRACKER;

/// Every single type and every combination the issue of ViSP parity names.
struct TypeRow {
  std::string name;
  VispCameraTypes types;
};
const std::vector<TypeRow> kTypeRows = {
    {"EDGE", {kEdge, 0}},
    {"KLT", {kKlt, 0}},
    {"EDGE+KLT", {kEdge | kKlt, 0}},
    {"DEPTH_DENSE", {0, kDense}},
    {"DEPTH_NORMAL", {0, kNormal}},
    {"EDGE+DEPTH_DENSE", {kEdge, kDense}},
    {"KLT+DEPTH_DENSE", {kKlt, kDense}},
    {"EDGE+KLT+DEPTH_DENSE", {kEdge | kKlt, kDense}},
};

/// The sequence's ViSP files, or files written for its mesh when it has none.
VispModelFiles visp_files_for(const SequenceObject& object, const std::string& sequence_dir) {
  const fs::path cao = fs::path(object.mesh_path).replace_extension(".cao");
  if (fs::is_regular_file(cao)) return VispModelFiles::beside_model(cao.string());
  const fs::path dir = fs::path("out") / "visp-types" / fs::path(sequence_dir).filename();
  std::cerr << "no ViSP model beside " << object.mesh_path << ": writing one and ViSP's tutorial settings to " << dir
            << "\n";
  return VispModelFiles::written_for_mesh(object.mesh_path, dir.string());
}

/// The ViSP XML of each camera of `types`, as a program loads them.
std::map<std::string, std::string> xml_settings(const VispCameraTypes& types, const VispModelFiles& files) {
  std::map<std::string, std::string> settings;
  if (types.color) settings[kColorCamera] = files.color_config;
  if (types.depth) settings[kDepthCamera] = files.depth_config;
  return settings;
}

template <class TrackerT>
TrackingSummary run_class(const std::vector<Frame>& frames, const SequenceObject& object, const Mesh& mesh,
                          const VispModelFiles& files, const VispCameraTypes& types, bool colour) {
  TrackerT tracker(types.names(), types.types());
  tracker.loadConfigFile(xml_settings(types, files), false);
  // ViSP's RGB-D XML files ask for PCL's plane estimation of depth normals, which ViSP built
  // without PCL (Debian's) refuses at the first frame: both classes get ViSP's own method.
  if (types.depth & kNormal)
    tracker.setDepthNormalFeatureEstimationMethod(vpMbtFaceDepthNormal::ROBUST_FEATURE_ESTIMATION);
  VispProgram<TrackerT> program(tracker, files, types, colour);
  return evaluate_sequence(FrameSource::of(frames), object.name, mesh, program.as_run_tracker(),
                           *frames.front().truth(object.name))
      .summary();
}

struct ResultRow {
  std::string sequence, types, image;
  const TimedRow* visp = nullptr;
  const TimedRow* icgp = nullptr;
};

/// Whether vpMbIcgTracker's row is at least as accurate in every error and twice as fast.
std::string verdict(const ResultRow& r) {
  if (!r.visp || !r.icgp) return "failed";
  const TrackingSummary &v = r.visp->summary, &i = r.icgp->summary;
  const bool accurate = i.mean_t_mm <= v.mean_t_mm && i.max_t_mm <= v.max_t_mm && i.mean_r_deg <= v.mean_r_deg &&
                        i.max_r_deg <= v.max_r_deg;
  const double speed = speed_ratio(r.visp, *r.icgp);
  return std::string(accurate ? "accurate" : "LESS ACCURATE") + (speed >= 2.0 ? ", >=2x" : ", <2x SPEED");
}

void print_rows(const std::vector<ResultRow>& rows) {
  const std::vector<TableColumn> errors = {{"mean", 6}, {"max", 6}, {"mean", 6}, {"max", 6}, {"ms", 6}};
  TextTable table(columns({{"sequence", 16, true}, {"tracker types", 21, true}, {"image", 6, true}, {"|", 1}},
                          {errors, {{"|", 1}}, errors, {{"|", 1}, {"speed", 6}, {"verdict", 0, true}}}),
                  {{"", 3}, {"|", 1}, {"vpMbGenericTracker mm / deg", 5}, {"|", 1}, {"vpMbIcgTracker mm / deg", 5},
                   {"|", 1}});
  const auto error_cells = [&table](const TimedRow* row) {
    if (!row) {
      table.text("").text("").text("failed").text("").text("");
      return;
    }
    const TrackingSummary& s = row->summary;
    table.accuracy(s).number(s.median_ms, 2);
  };
  for (const ResultRow& r : rows) {
    table.text(r.sequence).text(r.types).text(r.image).text("|");
    error_cells(r.visp);
    table.text("|");
    error_cells(r.icgp);
    table.text("|").ratio(r.visp && r.icgp ? speed_ratio(r.visp, *r.icgp) : NAN).text(verdict(r)).end_row();
  }
  std::printf("\n");
  table.print();
  std::printf(
      "\nBoth classes: constructed with the row's types (colour camera Camera1, depth camera Camera2), the\n"
      "sequence's ViSP XML per camera (loadConfigFile), the .cao, the frames' cameras, initFromPose at the first\n"
      "frame's truth, then track() every frame: vpMbGenericTracker always on the grey image (ViSP's edges and\n"
      "KLT read grey), vpMbIcgTracker on the grey or colour image. mm / deg: translation / rotation error; ms:\n"
      "median of track() alone, single thread; speed: ViSP's median / icgp's in the same round.\n");
}

}  // namespace

void run_visp_types_bench(const VispTypesBenchOptions& o) {
  std::vector<std::string> sequences = o.sequences;
  if (sequences.empty()) sequences.push_back(std::string(ICGP_SOURCE_TEST_DATA_DIR) + "/teabox-blender");
  std::vector<TimedJob> jobs;
  std::vector<ResultRow> rows;
  std::vector<std::string> visp_names, icgp_names;
  // Frames, meshes and files outlive the jobs that read them.
  std::vector<std::unique_ptr<std::vector<Frame>>> all_frames;
  std::vector<std::unique_ptr<Mesh>> meshes;
  std::vector<std::unique_ptr<VispModelFiles>> files;
  std::vector<SequenceObject> objects;
  objects.reserve(sequences.size());
  int n_frames_total = 0;
  for (const std::string& dir : sequences) {
    const Sequence sequence = Sequence::open(dir, o.sequence_options);
    if (!sequence.has_ground_truth() || sequence.objects().size() != 1 || sequence.objects().front().mesh_path.empty())
      throw std::runtime_error("--visp-types needs sequences with ground truth for one object with a mesh: " + dir);
    if (sequence.size() == 0) throw std::runtime_error("the sequence in " + dir + " has no frames");
    objects.push_back(sequence.objects().front());
    const SequenceObject& object = objects.back();
    files.push_back(std::make_unique<VispModelFiles>(visp_files_for(object, dir)));
    meshes.push_back(std::make_unique<Mesh>(load_any_mesh(object.mesh_path)));
    const int n = o.frames > 0 ? std::min(o.frames, sequence.size()) : sequence.size();
    std::cerr << "loading " << n << " frames of " << dir << "\n";
    auto frames = std::make_unique<std::vector<Frame>>();
    for (int i = 0; i < n; ++i) frames->push_back(sequence.load(i));
    const bool has_depth = !frames->front().depths.empty();
    n_frames_total = std::max(n_frames_total, n);
    const std::string name = fs::path(dir).filename().string();
    for (const TypeRow& type_row : kTypeRows) {
      if (type_row.types.depth && !has_depth) continue;
      const std::string visp_name = name + " " + type_row.name + " ViSP";
      const std::vector<Frame>& f = *frames;
      const Mesh& mesh = *meshes.back();
      const VispModelFiles& visp_files = *files.back();
      jobs.push_back({visp_name, [&f, &object, &mesh, &visp_files, type_row] {
                        return run_class<vpMbGenericTracker>(f, object, mesh, visp_files, type_row.types, false);
                      }});
      // A depth camera alone reads no image: one row. Colour rows also run on grey.
      for (const bool colour : type_row.types.color ? std::vector<bool>{false, true} : std::vector<bool>{false}) {
        const std::string icgp_name = name + " " + type_row.name + (colour ? " colour" : " grey") + " icgp";
        jobs.push_back({icgp_name, [&f, &object, &mesh, &visp_files, type_row, colour] {
                          return run_class<vpMbIcgTracker>(f, object, mesh, visp_files, type_row.types, colour);
                        }});
        rows.push_back({name, type_row.name, colour ? "colour" : "grey"});
        visp_names.push_back(visp_name);
        icgp_names.push_back(icgp_name);
      }
    }
    all_frames.push_back(std::move(frames));
  }

  std::cerr << kModelsOnFirstUse;
  std::vector<std::string> failures;
  const SingleThreadScope single_thread;
  const std::vector<TimedRow> timed = run_rounds(jobs, o.rounds, n_frames_total, failures);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    rows[i].visp = find_row(timed, visp_names[i]);
    rows[i].icgp = find_row(timed, icgp_names[i]);
  }
  print_rows(rows);
  if (!o.summary.empty()) {
    std::vector<JsonObject> json_rows;
    for (const ResultRow& r : rows) {
      JsonObject row = JsonObject().add("sequence", r.sequence).add("types", r.types).add("image", r.image);
      if (r.visp) row.add("visp", JsonObject().add_fields(r.visp->summary.to_json()));
      if (r.icgp) row.add("icgp", JsonObject().add_fields(r.icgp->summary.to_json()));
      json_rows.push_back(row.add("verdict", verdict(r)));
    }
    JsonObject().add("rows", json_rows).write(o.summary);
    std::cout << "wrote " << o.summary << "\n";
  }
  throw_if_failed(failures);
}

}  // namespace icgp::app
