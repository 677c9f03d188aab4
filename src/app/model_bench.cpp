// SPDX-License-Identifier: GPL-2.0-or-later
#include "model_bench.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <stdexcept>

#include "commands.h"
#include "icgp/base/pose.h"
#include "icgp/eval/json_object.h"
#include "icgp/io/cao_file_check.h"
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

/// A Wavefront OBJ of the mesh's vertices and triangles.
void write_obj(const Mesh& mesh, const fs::path& path) {
  std::ofstream out(path);
  std::size_t first_vertex = 1;
  for (const MeshPart& part : mesh.parts) {
    for (const Eigen::Vector3f& v : part.vertices) out << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
    for (const auto& t : part.triangles)
      out << "f " << first_vertex + t[0] << " " << first_vertex + t[1] << " " << first_vertex + t[2] << "\n";
    first_vertex += part.vertices.size();
  }
  if (!out) throw std::runtime_error("bench --model: cannot write " + path.string());
}

/// Each folder of models/ by its main mesh (`<folder>.obj`, else object.obj, else base.obj),
/// then the torus, written as an .obj and as a ViSP .cao beside the benchmark's other files;
/// only those named in `only` when it is not empty.
std::vector<BenchMesh> bench_meshes(const fs::path& out, const std::vector<std::string>& only) {
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
  const Mesh ring = torus(100, 50, 0.06f, 0.025f);
  write_obj(ring, out / "torus_10k.obj");
  write_cao(ring, (out / "torus_10k.cao").string());
  meshes.push_back({"torus_10k", (out / "torus_10k.obj").string()});
  meshes.push_back({"torus_10k.cao", (out / "torus_10k.cao").string()});
  if (only.empty()) return meshes;
  std::vector<BenchMesh> chosen;
  for (const std::string& name : only) {
    const auto it = std::find_if(meshes.begin(), meshes.end(), [&](const BenchMesh& m) { return m.name == name; });
    if (it == meshes.end()) {
      std::string names;
      for (const BenchMesh& m : meshes) names += (names.empty() ? "" : ", ") + m.name;
      throw std::invalid_argument("bench --model: --object '" + name + "' is none of its meshes (" + names + ")");
    }
    chosen.push_back(*it);
  }
  return chosen;
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
  double cache_mb = 0.0;  ///< the cache files together
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
  for (const CachedModelInfo& i : info) cost.cache_mb += file_mb(i.path);
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

/// vpMbGenericTracker::loadModel of a ViSP model file with the RGB-D programs' tracker
/// types, seconds; NaN for files other than .cao (the benchmark's meshes are .obj otherwise).
double visp_load_seconds(const BenchMesh& bench) {
  if (!is_cao_path(bench.path)) return std::nan("");
  vpMbGenericTracker tracker(kRgbdTrackerTypes);
  const auto start = Clock::now();
  tracker.loadModel(bench.path, bench.path);
  return seconds_since(start);
}

}  // namespace

void run_model_bench(const ModelBenchOptions& options) {
  const fs::path out(options.out);
  fs::create_directories(out);
  const std::vector<BenchMesh> meshes = bench_meshes(out, options.meshes);
  TextTable table({{"mesh", 18, true}, {"triangles", 9}, {"region s", 9}, {"depth s", 8}, {"both s", 7},
                   {"cache MB", 8}, {"1st frame s", 11}, {"ViSP load s", 11}, {"peak MB", 8}});
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
    const double visp_load = visp_load_seconds(bench);
    const double peak_mb = peak_resident_mb();
    table.text(bench.name).integer(static_cast<long long>(mesh.triangle_count())).number(region.seconds, 1);
    table.number(depth.seconds, 1).number(both.seconds, 1).number(both.cache_mb, 1).number(first_frame, 1);
    if (std::isnan(visp_load))
      table.text("-");
    else
      table.number(visp_load, 1);
    table.number(peak_mb, 0).end_row();
    rows.push_back(JsonObject()
                       .add("mesh", bench.name)
                       .add("triangles", static_cast<int>(mesh.triangle_count()))
                       .add("region_s", region.seconds)
                       .add("depth_s", depth.seconds)
                       .add("both_s", both.seconds)
                       .add("cache_mb", both.cache_mb)
                       .add("first_frame_s", first_frame)
                       .add("visp_load_s", visp_load)
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
      "empty cache, with every core, before returning; cache MB: the object's two cache files. 1st frame s:\n"
      "vpMbIcgTracker with the defaults (region + depth + texture) on an empty cache, loadModel -> initFromPose\n"
      "-> the first track() on one rendered frame at 0.5 m; its models are made in the background, the views\n"
      "the tracker needs first. ViSP load s: vpMbGenericTracker::loadModel (edge + KLT, dense depth) of the same\n"
      "file, for the .cao that ViSP reads (vpMbIcgTracker parses a .cao with ViSP's parser too). peak MB: the\n"
      "process's largest resident set so far.\n");
  if (!options.summary.empty()) {
    JsonObject().add("rows", rows).write(options.summary);
    std::cout << "wrote " << options.summary << "\n";
  }
}

}  // namespace icgp::app
