// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp make-sequence`: renders an RGB-D sequence of a model, or of the bodies of a scene
// file (eval/sequence_scene.h), with exact ground truth, in the layout `icgp track` and the
// tests read.
#include <iostream>
#include <limits>

#include "commands.h"
#include "option_ranges.h"
#include "icgp/eval/make_sequence.h"
#include "icgp/visp/cao_mesh_loader.h"

namespace icgp::app {
namespace {

void run_make_sequence(const MakeSequenceRequest& request) {
  check_image_pixels(request.width, request.height, "--width", "--height");
  const std::string written = make_sequence(request, models_dir(), [](const std::string& path, double scale) {
    return load_any_mesh(path, scale);
  });
  std::cout << "wrote " << written << " to " << request.out << "\n";
}

}  // namespace

void register_make_sequence_command(CLI::App& app) {
  auto o = std::make_shared<MakeSequenceRequest>();
  o->model = default_model_path();
  CLI::App* cmd = app.add_subcommand("make-sequence", "Render an RGB-D sequence of a model with exact ground truth");
  CLI::Option* model = cmd->add_option("model", o->model, "Mesh or ViSP .cao")->check(CLI::ExistingFile)->capture_default_str();
  CLI::Option* scene =
      cmd->add_option("--scene", o->scene,
                      "Scene file: several bodies with their own motions and joints (scenes/*.yaml) instead of a model")
          ->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "Output folder (created; an earlier sequence there is replaced)")->required();
  namespace range = make_sequence_range;
  CLI::Option* scale =
      cmd->add_option("--scale", o->scale, "Metres per mesh unit")->check(number_in(kMeshScale))->capture_default_str();
  cmd->add_option("--frames", o->writer.frame_count, "Number of frames")
      ->check(integer_in(1, kMaxFramesWritten))
      ->capture_default_str();
  cmd->add_option("--rate", o->writer.frame_rate, "Frames per second")
      ->check(number_in(range::kRate))
      ->capture_default_str();
  cmd->add_option("--seed", o->writer.seed, "Seed of the motion, background and noise")
      ->check(integer_in(0, std::numeric_limits<unsigned>::max()))
      ->capture_default_str();
  cmd->add_option("--speed", o->writer.motion.speed, "Motion speed factor (1 calm, 3-5 fast)")
      ->check(number_in(range::kSpeed))
      ->capture_default_str();
  cmd->add_option("--distance", o->writer.motion.distance, "Mean camera distance to the object, metres")
      ->check(number_in(range::kDistance))
      ->capture_default_str();
  cmd->add_option("--width", o->width, "Image width")->check(image_side())->capture_default_str();
  cmd->add_option("--height", o->height, "Image height")->check(image_side())->capture_default_str();
  cmd->add_option("--focal", o->focal, "Focal length in pixels (colour and depth)")
      ->check(number_in(kFocalPx))
      ->capture_default_str();
  cmd->add_option("--baseline", o->baseline, "Depth camera offset along the colour camera's x axis, metres")
      ->check(number_in(range::kBaseline))
      ->capture_default_str();
  cmd->add_option("--stereo-baseline", o->stereo_baseline,
                  "Second colour camera (color2/, same intrinsics) this far along the colour camera's x axis, "
                  "metres (0: none)")
      ->check(number_in(range::kBaseline))
      ->capture_default_str();
  CLI::Option* spin = cmd->add_option("--spin", o->spin, "Object rotation about its y axis (the models' up axis), rad/s")
                          ->check(number_in(range::kSpin))
                          ->capture_default_str();
  // A scene gives each body its mesh, scale and motion.
  scene->excludes(model)->excludes(scale)->excludes(spin);
  cmd->add_option("--color-noise", o->writer.noise.color_sigma, "Gaussian colour noise, 8-bit levels")
      ->check(number_in(range::kColorNoise))
      ->capture_default_str();
  cmd->add_option("--depth-noise", o->writer.noise.depth_sigma_at_1m, "Depth noise sigma at 1 m (grows with Z^2)")
      ->check(number_in(range::kDepthNoise))
      ->capture_default_str();
  cmd->add_option("--depth-dropout", o->writer.noise.depth_dropout, "Fraction of depth pixels missing")
      ->check(number_in(range::kDepthDropout))
      ->capture_default_str();
  cmd->add_option("--grazing-angle", o->writer.noise.grazing_angle_deg,
                  "Depth missing where the surface is seen more obliquely than this, degrees (90: never)")
      ->check(number_in(range::kGrazingAngle))
      ->capture_default_str();
  cmd->add_option("--depth-edge-holes", o->writer.noise.depth_edge_holes_px,
                  "Depth missing within this many pixels of a depth discontinuity (0: never)")
      ->check(integer_in(0, range::kMaxDepthEdgeHoles))
      ->capture_default_str();
  cmd->add_option("--antialias", o->writer.antialias_samples, "Multisample antialiasing of colour, samples per pixel (0: off)")
      ->check(integer_in(0, range::kMaxAntialiasSamples))
      ->capture_default_str();
  cmd->add_option("--motion-blur", o->writer.motion_blur.samples,
                  "Colour renders averaged over the exposure of each frame (1: sharp)")
      ->check(integer_in(1, range::kMaxMotionBlurSamples))
      ->capture_default_str();
  cmd->add_option("--exposure", o->writer.motion_blur.exposure, "Exposure as a fraction of the frame interval (motion blur)")
      ->check(number_in(range::kExposure))
      ->capture_default_str();
  cmd->add_option("--gain-variation", o->writer.gain_variation,
                  "Auto-exposure hunting: colour scaled by 1 + this * sin(2 pi 0.4 Hz t + phase) (0: steady)")
      ->check(number_in(range::kGainVariation))
      ->capture_default_str();
  cmd->callback([o] { run_make_sequence(*o); });
}

}  // namespace icgp::app
