// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp bench-render`: how long the renders that tracking and model generation need take
// on this machine. Prints medians and rates; asserts nothing.
#include <algorithm>
#include <chrono>
#include <functional>
#include <iomanip>
#include <iostream>

#include "commands.h"
#include "option_ranges.h"
#include "icgp/render/renderer.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "view_options.h"

namespace icgp::app {
namespace {

struct BenchRenderOptions {
  std::string model;
  int runs = 200;
};

struct Timing {
  double median_ms, p90_ms;
};

Timing time_runs(int runs, const std::function<void()>& work) {
  for (int i = 0; i < 5; ++i) work();  // warm-up: shader compilation, buffer allocation
  std::vector<double> ms;
  for (int i = 0; i < runs; ++i) {
    const auto start = std::chrono::steady_clock::now();
    work();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(ms.begin(), ms.end());
  return {ms[ms.size() / 2], ms[ms.size() * 9 / 10]};
}

void print_row(const std::string& what, const Timing& t) {
  std::cout << std::left << std::setw(44) << what << std::right << std::fixed << std::setprecision(3)
            << std::setw(10) << t.median_ms << std::setw(10) << t.p90_ms << std::setprecision(1) << std::setw(10)
            << 1000.0 / t.median_ms << "\n";
}

void run_bench_render(const BenchRenderOptions& o) {
  const Mesh mesh = load_any_mesh(o.model);
  Renderer renderer;
  renderer.add_body(mesh, 1);
  ViewOptions view;
  const Intrinsics k = view.intrinsics();
  const double radius = mesh.radius_about_origin();
  const Pose camera_T_body = view.camera_T_body(radius);
  const ImageSquare focus = square_around_sphere(k, camera_T_body.translation(), radius);

  std::cout << "renderer: " << renderer.description() << "\nmodel: " << o.model << " (" << mesh.triangle_count()
            << " triangles), " << o.runs << " runs each (model-generation size: " << std::max(1, o.runs / 10)
            << ")\n\n"
            << std::left << std::setw(44) << "render" << std::right << std::setw(10) << "median ms" << std::setw(10)
            << "p90 ms" << std::setw(10) << "Hz" << "\n";
  print_row("depth 640x480", time_runs(o.runs, [&] { renderer.render(k, camera_T_body, kRenderDepth); }));
  print_row("silhouette 200x200 focused (" + std::to_string(static_cast<int>(focus.size)) + " px crop)",
            time_runs(o.runs, [&] {
              renderer.render_focused(k, camera_T_body, focus.u_min, focus.v_min, focus.size, 200, kRenderIds);
            }));
  print_row("depth + silhouette 200x200 focused", time_runs(o.runs, [&] {
              renderer.render_focused(k, camera_T_body, focus.u_min, focus.v_min, focus.size, 200,
                                      kRenderIds | kRenderDepth);
            }));
  print_row("colour 640x480", time_runs(o.runs, [&] { renderer.render(k, camera_T_body, kRenderColor); }));
  Intrinsics big = k.scaled(2000, 2000);
  big.pu = big.pv = 999.5;
  print_row("model view 2000x2000 ids + depth + normals", time_runs(std::max(1, o.runs / 10), [&] {
              renderer.render(big, camera_T_body, kRenderIds | kRenderDepth | kRenderNormals);
            }));
}

}  // namespace

void register_bench_render_command(CLI::App& app) {
  auto options = std::make_shared<BenchRenderOptions>();
  options->model = default_model_path();
  CLI::App* cmd = app.add_subcommand("bench-render", "Time the headless renders tracking and model generation use");
  cmd->add_option("model", options->model, "Mesh or ViSP .cao")->check(CLI::ExistingFile)->capture_default_str();
  cmd->add_option("--runs", options->runs, "Timed runs per render")->check(integer_in(1, 100000))->capture_default_str();
  cmd->callback([options] { run_bench_render(*options); });
}

}  // namespace icgp::app
