// SPDX-License-Identifier: GPL-2.0-or-later
#include "model_bench.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>

#include "commands.h"
#include "icgp/base/pose.h"
#include "icgp/eval/json_object.h"
#include "icgp/eval/sequence.h"
#include "icgp/eval/sequence_run.h"
#include "icgp/eval/sequence_writer.h"
#include "icgp/model/model_cache.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/cao_writer.h"
#include "icgp/visp/rgbd_tracking_loop.h"
#include "icgp/visp/visp_camera_xml.h"
#include "icgp/visp/vpMbIcgTracker.h"
#include "text_table.h"

namespace icgp::app {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// A torus of `n_around` × `n_tube` quads (2 triangles each): not convex, so its contours
/// change with the view as a real object's do, and as large a mesh as the issue asks of the
/// benchmark (10 000 triangles for 100 × 50).
Mesh torus(int n_around, int n_tube, float major_radius, float minor_radius) {
  MeshPart part;
  for (int i = 0; i < n_around; ++i)
    for (int j = 0; j < n_tube; ++j) {
      const float u = 2.0f * static_cast<float>(kPi) * i / n_around, v = 2.0f * static_cast<float>(kPi) * j / n_tube;
      const float ring = major_radius + minor_radius * std::cos(v);
      part.vertices.emplace_back(ring * std::cos(u), ring * std::sin(u), minor_radius * std::sin(v));
    }
  const auto index = [&](int i, int j) { return (i % n_around) * n_tube + (j % n_tube); };
  for (int i = 0; i < n_around; ++i)
    for (int j = 0; j < n_tube; ++j) {
      // Counter-clockwise seen from outside.
      part.triangles.emplace_back(index(i, j), index(i + 1, j), index(i + 1, j + 1));
      part.triangles.emplace_back(index(i, j), index(i + 1, j + 1), index(i, j + 1));
    }
  part.material.diffuse_rgb = {0.2f, 0.5f, 0.8f};
  Mesh mesh;
  mesh.parts.push_back(std::move(part));
  return mesh;
}

struct BenchMesh {
  std::string name;
  std::string path;
};

/// Each folder of models/ by its main mesh (`<folder>.obj`, else object.obj, else base.obj),
/// then the torus, written as a .cao beside the benchmark's other files.
std::vector<BenchMesh> bench_meshes(const fs::path& out) {
  std::vector<BenchMesh> meshes;
  std::vector<fs::path> folders;
  for (const fs::directory_entry& entry : fs::directory_iterator(models_dir()))
    if (entry.is_directory()) folders.push_back(entry.path());
  std::sort(folders.begin(), folders.end());
  for (const fs::path& folder : folders)
    for (const std::string file : {folder.filename().string() + ".obj", std::string("object.obj"), std::string("base.obj")})
      if (fs::is_regular_file(folder / file)) {
        meshes.push_back({folder.filename().string(), (folder / file).string()});
        break;
      }
  const fs::path torus_path = out / "torus_10k.cao";
  write_cao(torus(100, 50, 0.06f, 0.025f), torus_path.string());
  meshes.push_back({"torus_10k", torus_path.string()});
  return meshes;
}

/// An empty folder at `path`.
std::string empty_folder(const fs::path& path) {
  fs::remove_all(path);
  fs::create_directories(path);
  return path.string();
}

/// The process's largest resident set so far, MB.
double peak_resident_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // kilobytes on Linux
}

double file_mb(const std::string& path) { return fs::file_size(path) / 1e6; }

struct GenerationCost {
  double seconds = 0.0;
  double mb_per_model = 0.0;  ///< the largest cache file
};

GenerationCost generate(const Mesh& mesh, const std::string& name, const std::vector<ViewpointModel::Kind>& kinds,
                        const fs::path& cache) {
  std::vector<ModelRequest> requests;
  for (const ViewpointModel::Kind kind : kinds) requests.push_back({kind, ViewpointModelParams()});
  ModelGenerationOptions options;
  options.print_progress = false;
  options.name = name;
  std::vector<CachedModelInfo> info;
  const auto start = Clock::now();
  load_or_generate(mesh, requests, empty_folder(cache), options, &info);
  GenerationCost cost{seconds_since(start), 0.0};
  for (const CachedModelInfo& i : info) cost.mb_per_model = std::max(cost.mb_per_model, file_mb(i.path));
  return cost;
}

/// One frame of the mesh at 0.5 m, rendered without noise, as a sequence.
Frame rendered_frame(const BenchMesh& bench, const Mesh& mesh, const fs::path& folder) {
  SequenceWriterOptions o;
  o.frame_count = 1;
  o.color_intrinsics = o.depth_intrinsics = Intrinsics::centred(640, 480, 600.0);
  o.depth_T_color = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.025, 0.0, 0.0));
  o.motion.distance = 0.5;
  o.progress = false;
  SequenceWriter writer(o);
  writer.add_object(bench.name, mesh, Pose(), bench.path);
  writer.write(empty_folder(folder));
  return Sequence::open(folder.string(), visp_sequence_options()).load(0);
}

/// loadModel → initFromPose → the first track() of vpMbIcgTracker with the defaults and an
/// empty cache, through the ViSP calls a program makes; seconds.
double first_frame_seconds(const BenchMesh& bench, const Frame& frame, const fs::path& cache) {
  TrackerConfig config;
  config.cache_dir = empty_folder(cache);
  vpMbIcgTracker tracker(kRgbdTrackerTypes);
  tracker.setTrackerConfig(config);
  VispProgram<vpMbIcgTracker> program(tracker, VispModelFiles{bench.path, "", ""}, kRgbdCameraTypes);
  const auto start = Clock::now();
  run_sequence(FrameSource::of(std::vector<Frame>{frame}), program.as_run_tracker(), *frame.truth(bench.name),
               nullptr);
  return seconds_since(start);
}

}  // namespace

void run_model_bench(const ModelBenchOptions& options) {
  const fs::path out(options.out);
  fs::create_directories(out);
  // As `icgp model`: generation renders on one thread per core, and llvmpipe's own raster
  // threads on top would oversubscribe them. Read when the first context is made.
  ::setenv("LP_NUM_THREADS", "0", 0);
  const std::vector<BenchMesh> meshes = bench_meshes(out);
  TextTable table({{"mesh", 18, true}, {"triangles", 9}, {"region s", 9}, {"depth s", 8}, {"both s", 7},
                   {"MB/model", 8}, {"1st frame s", 11}, {"peak MB", 8}});
  std::vector<JsonObject> rows;
  const auto start = Clock::now();
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const BenchMesh& bench = meshes[m];
    const Mesh mesh = load_any_mesh(bench.path);
    const fs::path cache = out / "cache";
    const GenerationCost region = generate(mesh, bench.name, {ViewpointModel::Kind::kRegion}, cache);
    const GenerationCost depth = generate(mesh, bench.name, {ViewpointModel::Kind::kDepth}, cache);
    const GenerationCost both =
        generate(mesh, bench.name, {ViewpointModel::Kind::kRegion, ViewpointModel::Kind::kDepth}, cache);
    const Frame frame = rendered_frame(bench, mesh, out / ("frame-" + bench.name));
    const double first_frame = first_frame_seconds(bench, frame, cache);
    const double peak_mb = peak_resident_mb();
    table.text(bench.name).integer(static_cast<long long>(mesh.triangle_count())).number(region.seconds, 1);
    table.number(depth.seconds, 1).number(both.seconds, 1).number(both.mb_per_model, 1).number(first_frame, 1);
    table.number(peak_mb, 0).end_row();
    rows.push_back(JsonObject()
                       .add("mesh", bench.name)
                       .add("triangles", static_cast<int>(mesh.triangle_count()))
                       .add("region_s", region.seconds)
                       .add("depth_s", depth.seconds)
                       .add("both_s", both.seconds)
                       .add("mb_per_model", both.mb_per_model)
                       .add("first_frame_s", first_frame)
                       .add("peak_resident_mb", peak_mb));
    const double elapsed = seconds_since(start);
    std::fprintf(stderr, "bench --model: %zu/%zu meshes, %.0f s, about %.0f s left\n", m + 1, meshes.size(), elapsed,
                 elapsed / (m + 1) * (meshes.size() - m - 1));
  }
  fs::remove_all(out / "cache");
  std::printf("\n");
  table.print();
  std::printf(
      "\nregion s, depth s: one model kind alone; both s: the two together (one render per view), each into an\n"
      "empty cache, with every core; MB/model: the larger cache file. 1st frame s: vpMbIcgTracker with the\n"
      "defaults (region + depth + texture) on an empty cache, loadModel -> initFromPose -> the first track() on\n"
      "one rendered frame at 0.5 m. peak MB: the process's largest resident set so far.\n");
  if (!options.summary.empty()) {
    JsonObject().add("rows", rows).write(options.summary);
    std::cout << "wrote " << options.summary << "\n";
  }
}

}  // namespace icgp::app
