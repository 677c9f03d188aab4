// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp make-sequence`: renders an RGB-D sequence of a model, or of the bodies of a scene
// file (eval/sequence_scene.h), with exact ground truth, in the layout `icgp track` and the
// tests read.
#include <filesystem>
#include <iostream>
#include <limits>

#include "commands.h"
#include "option_ranges.h"
#include "icgp/eval/sequence_scene.h"
#include "icgp/eval/sequence_writer.h"
#include "icgp/visp/cao_mesh_loader.h"

namespace icgp::app {
namespace {

struct MakeSequenceOptions {
  std::string model;
  std::string scene;
  std::string out;
  double scale = 1.0;
  int width = 640, height = 480;
  double focal = 600.0;
  double baseline = 0.0;
  double stereo_baseline = 0.0;
  double spin = 0.0;
  SequenceWriterOptions writer;
};

void run_make_sequence(MakeSequenceOptions o) {
  check_image_pixels(o.width, o.height, "--width", "--height");
  o.writer.color_intrinsics = o.writer.depth_intrinsics = Intrinsics::centred(o.width, o.height, o.focal);
  o.writer.depth_T_color = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0 - o.baseline, 0.0, 0.0));
  if (o.stereo_baseline != 0.0) {
    // A rectified pair: the same camera, moved along the colour camera's x axis.
    o.writer.stereo = true;
    o.writer.stereo_intrinsics = o.writer.color_intrinsics;
    o.writer.stereo_T_color = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0 - o.stereo_baseline, 0.0, 0.0));
  }

  if (!o.scene.empty()) {
    const std::vector<SceneBody> bodies = read_sequence_scene(o.scene, models_dir());
    SequenceWriter writer(o.writer);
    add_scene_bodies(writer, bodies);
    writer.write(o.out);
    std::cout << "wrote " << o.writer.frame_count << " frames of " << bodies.size() << " bodies of " << o.scene
              << (o.writer.stereo ? " (stereo)" : "") << " to " << o.out << "\n";
    return;
  }
  const Mesh mesh = load_any_mesh(o.model, o.scale);
  SequenceWriter writer(o.writer);
  const std::string stem = std::filesystem::path(o.model).stem().string();
  writer.add_object(stem, mesh, Pose(), std::filesystem::absolute(o.model).string(), Eigen::Vector3d(0.0, o.spin, 0.0));
  writer.write(o.out);
  std::cout << "wrote " << o.writer.frame_count << " frames of '" << stem << "'"
            << (o.writer.stereo ? " (stereo)" : "") << " to " << o.out << "\n";
}

}  // namespace

void register_make_sequence_command(CLI::App& app) {
  auto o = std::make_shared<MakeSequenceOptions>();
  o->model = default_model_path();
  CLI::App* cmd = app.add_subcommand("make-sequence", "Render an RGB-D sequence of a model with exact ground truth");
  CLI::Option* model = cmd->add_option("model", o->model, "Mesh or ViSP .cao")->check(CLI::ExistingFile)->capture_default_str();
  CLI::Option* scene =
      cmd->add_option("--scene", o->scene,
                      "Scene file: several bodies with their own motions and joints (scenes/*.yaml) instead of a model")
          ->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "Output folder (created; an earlier sequence there is replaced)")->required();
  const yaml::Interval baseline_m{-10.0, 10.0};
  CLI::Option* scale =
      cmd->add_option("--scale", o->scale, "Metres per mesh unit")->check(number_in(kMeshScale))->capture_default_str();
  cmd->add_option("--frames", o->writer.frame_count, "Number of frames")
      ->check(integer_in(1, kMaxFramesWritten))
      ->capture_default_str();
  cmd->add_option("--rate", o->writer.frame_rate, "Frames per second")
      ->check(number_in({0.0, 1000.0, true}))
      ->capture_default_str();
  cmd->add_option("--seed", o->writer.seed, "Seed of the motion, background and noise")
      ->check(integer_in(0, std::numeric_limits<unsigned>::max()))
      ->capture_default_str();
  cmd->add_option("--speed", o->writer.motion.speed, "Motion speed factor (1 calm, 3-5 fast)")
      ->check(number_in({0.0, 100.0, true}))
      ->capture_default_str();
  cmd->add_option("--distance", o->writer.motion.distance, "Mean camera distance to the object, metres")
      ->check(number_in({0.0, 1000.0, true}))
      ->capture_default_str();
  cmd->add_option("--width", o->width, "Image width")->check(image_side())->capture_default_str();
  cmd->add_option("--height", o->height, "Image height")->check(image_side())->capture_default_str();
  cmd->add_option("--focal", o->focal, "Focal length in pixels (colour and depth)")
      ->check(number_in(kFocalPx))
      ->capture_default_str();
  cmd->add_option("--baseline", o->baseline, "Depth camera offset along the colour camera's x axis, metres")
      ->check(number_in(baseline_m))
      ->capture_default_str();
  cmd->add_option("--stereo-baseline", o->stereo_baseline,
                  "Second colour camera (color2/, same intrinsics) this far along the colour camera's x axis, "
                  "metres (0: none)")
      ->check(number_in(baseline_m))
      ->capture_default_str();
  CLI::Option* spin = cmd->add_option("--spin", o->spin, "Object rotation about its y axis (the models' up axis), rad/s")
                          ->check(number_in({-100.0, 100.0}))
                          ->capture_default_str();
  // A scene gives each body its mesh, scale and motion.
  scene->excludes(model)->excludes(scale)->excludes(spin);
  cmd->add_option("--color-noise", o->writer.noise.color_sigma, "Gaussian colour noise, 8-bit levels")
      ->check(number_in({0.0, 255.0}))
      ->capture_default_str();
  cmd->add_option("--depth-noise", o->writer.noise.depth_sigma_at_1m, "Depth noise sigma at 1 m (grows with Z^2)")
      ->check(number_in({0.0, 1.0}))
      ->capture_default_str();
  cmd->add_option("--depth-dropout", o->writer.noise.depth_dropout, "Fraction of depth pixels missing")
      ->check(number_in({0.0, 1.0}))
      ->capture_default_str();
  cmd->add_option("--grazing-angle", o->writer.noise.grazing_angle_deg,
                  "Depth missing where the surface is seen more obliquely than this, degrees (90: never)")
      ->check(number_in({0.0, 90.0, true}))
      ->capture_default_str();
  cmd->add_option("--depth-edge-holes", o->writer.noise.depth_edge_holes_px,
                  "Depth missing within this many pixels of a depth discontinuity (0: never)")
      ->check(integer_in(0, 100))
      ->capture_default_str();
  cmd->add_option("--antialias", o->writer.antialias_samples, "Multisample antialiasing of colour, samples per pixel (0: off)")
      ->check(integer_in(0, 64))
      ->capture_default_str();
  cmd->add_option("--motion-blur", o->writer.motion_blur.samples,
                  "Colour renders averaged over the exposure of each frame (1: sharp)")
      ->check(integer_in(1, 256))
      ->capture_default_str();
  cmd->add_option("--exposure", o->writer.motion_blur.exposure, "Exposure as a fraction of the frame interval (motion blur)")
      ->check(number_in({0.0, 1.0}))
      ->capture_default_str();
  cmd->callback([o] { run_make_sequence(*o); });
}

}  // namespace icgp::app
