// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp model`: builds the region and depth viewpoint model caches of a mesh ahead of time,
// so the first tracking run does not wait for them, and reports what they cost.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "commands.h"
#include "option_ranges.h"
#include "icgp/base/stop_request.h"
#include "icgp/model/model_cache.h"
#include "icgp/visp/cao_mesh_loader.h"

namespace icgp::app {
namespace {

struct ModelOptions {
  std::string mesh;
  std::string kind = "both";
  std::string cache_dir;
  ViewpointModelParams params;
  double scale = 1.0;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void run_model(const ModelOptions& o) {
  install_stop_on_sigint();  // generation stops between views; nothing is left half written
  const Mesh mesh = load_any_mesh(o.mesh, o.scale);
  std::vector<ModelRequest> requests;
  if (o.kind != "depth") requests.push_back({ViewpointModel::Kind::kRegion, o.params});
  if (o.kind != "region") requests.push_back({ViewpointModel::Kind::kDepth, o.params});
  const std::string cache_dir = o.cache_dir.empty() ? default_model_cache_dir() : o.cache_dir;
  std::cout << "mesh       " << o.mesh << " (" << mesh.triangle_count() << " triangles, radius "
            << mesh.radius_about_origin() << " m about its origin)\ncache      " << cache_dir << std::endl;

  const auto start = std::chrono::steady_clock::now();
  std::vector<CachedModelInfo> info;
  std::vector<std::string> summaries;
  {
    const std::vector<ViewpointModel> models = load_or_generate(mesh, requests, cache_dir, {}, &info);
    for (const ViewpointModel& model : models) {
      int fewest = model.n_points();
      for (int v = 0; v < model.n_views(); ++v) fewest = std::min(fewest, model.view_point_count(v));
      summaries.push_back(std::to_string(model.n_views()) + " views x " + std::to_string(model.n_points()) +
                          " points (fewest in a view: " + std::to_string(fewest) + "), ");
    }
  }  // released before the reloads, which map the files anew
  const double total = seconds_since(start);
  const auto generated = std::count_if(info.begin(), info.end(), [](const CachedModelInfo& i) { return i.generated; });

  std::cout << std::fixed << std::setprecision(1);
  for (std::size_t m = 0; m < requests.size(); ++m) {
    std::cout << std::left << std::setw(11) << to_string(requests[m].kind) << std::right << summaries[m];
    if (info[m].generated)
      std::cout << "generated in " << total << " s" << (generated > 1 ? " (together, one render per view)" : "")
                << "\n";
    else
      std::cout << "already cached\n";
    std::cout << "           " << info[m].path;
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(info[m].path, ec);
    if (ec) {
      std::cout << ": not written (see the warning above)\n";
      continue;
    }
    const auto reload_start = std::chrono::steady_clock::now();
    load_viewpoint_model(info[m].path);
    std::cout << ", " << bytes / 1e6 << " MB, reloaded in " << 1e3 * seconds_since(reload_start) << " ms\n";
  }
}

}  // namespace

void register_model_command(CLI::App& app) {
  auto o = std::make_shared<ModelOptions>();
  CLI::App* cmd = app.add_subcommand("model", "Build the region and depth viewpoint model caches of a mesh");
  cmd->add_option("mesh", o->mesh, "Mesh (.obj/.ply/.stl/.gltf/.dae) or ViSP .cao")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--kind", o->kind, "Which models")
      ->check(CLI::IsMember({"region", "depth", "both"}))
      ->capture_default_str();
  cmd->add_option("--cache-dir", o->cache_dir,
                  "Cache folder (default: $ICGP_CACHE_DIR, $XDG_CACHE_HOME/icgp or ~/.cache/icgp)");
  cmd->add_option("--views-divides", o->params.n_divides, "Icosphere subdivisions: 10*4^N+2 views")
      ->check(integer_in(0, 6))
      ->capture_default_str();
  cmd->add_option("--image-size", o->params.image_size, "Render size in pixels")
      ->check(integer_in(16, kMaxImageSide))
      ->capture_default_str();
  cmd->add_option("--points", o->params.n_points, "Points per view")->check(integer_in(1, 100000))->capture_default_str();
  cmd->add_option("--scale", o->scale, "Metres per mesh unit")->check(number_in(kMeshScale))->capture_default_str();
  cmd->callback([o] { run_model(*o); });
}

}  // namespace icgp::app
