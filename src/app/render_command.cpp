// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp render`: renders a model headlessly at a chosen view and writes colour, depth,
// normals and ids side by side into one PNG.
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <opencv2/imgcodecs.hpp>

#include "commands.h"
#include "option_ranges.h"
#include "icgp/render/renderer.h"
#include "icgp/render/visualization.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "view_options.h"

namespace icgp::app {
namespace {

struct RenderOptions {
  std::string model;
  double scale = 1.0;
  ViewOptions view;
  std::string out = "out/render.png";
};

void run_render(const RenderOptions& o) {
  check_image_pixels(o.view.width, o.view.height, "--width", "--height");
  const Mesh mesh = load_any_mesh(o.model, o.scale);
  Renderer renderer;
  renderer.add_body(mesh, 1);
  const Intrinsics k = o.view.intrinsics();
  const Pose camera_T_body = o.view.camera_T_body(mesh.radius_about_origin());

  const auto start = std::chrono::steady_clock::now();
  const RenderOutput out = renderer.render(k, camera_T_body, kRenderColor | kRenderDepth | kRenderNormals | kRenderIds);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

  const std::filesystem::path path(o.out);
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  const cv::Mat mosaic = tile({out.color, depth_to_bgr(out.depth), normals_to_bgr(out.normals), ids_to_bgr(out.ids)}, 2);
  if (!cv::imwrite(o.out, mosaic)) throw std::runtime_error("cannot write image '" + o.out + "'");
  std::cout << "model      " << o.model << " (" << mesh.triangle_count() << " triangles, radius "
            << mesh.radius_about_origin() << " m)\n"
            << "renderer   " << renderer.description() << "\n"
            << "view       " << k.width << "x" << k.height << ", object " << o.view.distance_for(mesh.radius_about_origin())
            << " m away\n"
            << "object px  " << cv::countNonZero(out.ids) << " pixels, rendered in " << ms
            << " ms (all four targets, first render: includes shader compilation)\n"
            << "wrote      " << o.out << " (colour | depth / normals | ids)\n";
}

}  // namespace

void register_render_command(CLI::App& app) {
  auto options = std::make_shared<RenderOptions>();
  options->model = default_model_path();
  CLI::App* cmd = app.add_subcommand("render", "Render a model headlessly (colour, depth, normals, ids) to a PNG");
  cmd->add_option("model", options->model, "Mesh (.obj/.ply/.stl/.gltf/.dae) or ViSP .cao")
      ->check(CLI::ExistingFile)
      ->capture_default_str();
  cmd->add_option("--scale", options->scale, "Metres per mesh unit")->check(number_in(kMeshScale))->capture_default_str();
  add_view_options(*cmd, options->view);
  cmd->add_option("--out", options->out, "Output PNG")->capture_default_str();
  cmd->callback([options] { run_render(*options); });
}

}  // namespace icgp::app
