// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp bench --sweep`: icgp's defaults against the ICG papers' reference parameters and
// ViSP's vpMbGenericTracker, over models x depth sensors x image conditions rendered here
// with exact ground truth, with no tuning per condition. Every tracker of a cell sees the
// same frames.
#include "sweep.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <optional>
#include <sstream>
#include <visp3/core/vpException.h>

#include "commands.h"
#include "icgp/tracker/cue_registry.h"
#include "icgp/eval/gnuplot.h"
#include "icgp/eval/json_object.h"
#include "icgp/eval/sequence.h"
#include "icgp/eval/single_body_tracker.h"
#include "icgp/eval/sequence_writer.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/visp_baseline.h"
#include "single_thread_scope.h"
#include "text_table.h"

namespace icgp::app {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// A frame counts as lost when the tracker says so or when its error exceeds these.
constexpr double kLostTranslationMm = 50.0;
constexpr double kLostRotationDeg = 30.0;
/// Bumped whenever the rendering of the sweep's sequences changes, so old caches are unused.
constexpr int kSequenceVersion = 1;

const std::string kIcgpDefaults = "icgp defaults";
const std::string kIcgpRegionDepth = "icgp defaults, region + depth";
const std::string kIcgReference = "icg_reference";
const std::string kVispRgbd = "ViSP edge + KLT + dense depth";

struct DepthCondition {
  std::string name;
  SensorNoise noise;
};

struct ImageCondition {
  std::string name;
  int antialias_samples = 0;
  MotionBlur blur;
};

/// One sequence and the trackers run on it. A grey cell tracks the colour of its
/// sequence as grey images, with no depth given to any tracker.
struct SweepCell {
  const SweepModel* model = nullptr;
  DepthCondition depth;
  ImageCondition image;
  bool grey = false;

  std::string depth_label() const { return grey ? "none" : depth.name; }
  std::string image_label() const { return grey ? "grey " + image.name : image.name; }
};

struct SweepRow {
  std::string model, depth, image, tracker;
  TrackingSummary summary;
  int lost = 0;
};

/// Camera, motion and frame count shared by every sequence of a run.
struct SceneSettings {
  int width = 640, height = 480;
  double focal = 600.0;
  int frames = 60;
  std::uint64_t seed = 7;
  double speed = 2.5;  ///< brisk hand-held motion, so that motion blur is visible
};

std::vector<DepthCondition> depth_conditions() {
  return {{"exact", SensorNoise{}}, {"realsense", SensorNoise::realsense_class()}, {"kinect", SensorNoise::kinect_class()}};
}

std::vector<ImageCondition> image_conditions() {
  // 4 samples: what llvmpipe offers (GL_MAX_SAMPLES), and what GPUs all have.
  return {{"sharp", 0, MotionBlur{}}, {"antialiased", 4, MotionBlur{}}, {"motion-blurred", 4, MotionBlur{8, 0.5}}};
}

/// The full design: every model x depth x image as RGB-D cells, then one grey cell per
/// model (antialiased). Quick: the first model, exact/sharp and Kinect/motion-blurred, and
/// its grey cell.
std::vector<SweepCell> sweep_cells(const std::vector<SweepModel>& models, bool quick) {
  const std::vector<DepthCondition> depths = depth_conditions();
  const std::vector<ImageCondition> images = image_conditions();
  const ImageCondition& antialiased = images[1];
  std::vector<SweepCell> cells;
  if (quick) {
    cells.push_back({&models.front(), depths.front(), images.front(), false});
    cells.push_back({&models.front(), depths.back(), images.back(), false});
    cells.push_back({&models.front(), depths.front(), antialiased, true});
    return cells;
  }
  for (const SweepModel& model : models)
    for (const DepthCondition& depth : depths)
      for (const ImageCondition& image : images) cells.push_back({&model, depth, image, false});
  // Grey cells read the colour of the exact-depth antialiased sequence: no extra renders.
  for (const SweepModel& model : models) cells.push_back({&model, depths.front(), antialiased, true});
  return cells;
}

SequenceWriterOptions writer_options(const SceneSettings& scene, const SweepCell& cell) {
  SequenceWriterOptions o;
  o.frame_count = scene.frames;
  o.seed = scene.seed;
  o.color_intrinsics = o.depth_intrinsics = Intrinsics::centred(scene.width, scene.height, scene.focal);
  o.depth_T_color = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.025, 0.0, 0.0));
  o.motion.speed = scene.speed;
  o.noise = cell.depth.noise;
  o.antialias_samples = cell.image.antialias_samples;
  o.motion_blur = cell.image.blur;
  o.progress = false;
  return o;
}

/// Every option that changes the images, as text: the key of a cached sequence.
std::string sequence_key(const SweepModel& model, const SequenceWriterOptions& o) {
  std::ostringstream key;
  key.precision(17);
  const SensorNoise& n = o.noise;
  key << "v" << kSequenceVersion << " " << model.mesh_path << " " << o.frame_count << " " << o.frame_rate << " "
      << o.seed << " " << o.color_intrinsics.width << "x" << o.color_intrinsics.height << " f" << o.color_intrinsics.fu
      << " baseline " << o.depth_T_color.translation().transpose() << " speed " << o.motion.speed << " noise "
      << n.color_sigma << " " << n.depth_sigma_at_1m << " " << n.depth_dropout << " " << n.grazing_angle_deg << " "
      << n.depth_edge_holes_px << " aa " << o.antialias_samples << " blur " << o.motion_blur.samples << " "
      << o.motion_blur.exposure;
  return key.str();
}

/// 64-bit FNV-1a, to name a folder after a key.
std::string short_hash(const std::string& text) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (const unsigned char c : text) h = (h ^ c) * 0x100000001b3ull;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return std::string(hex, 10);
}

/// Sequences rendered once per set of options under `root`, reused by later runs.
class SequenceCache {
 public:
  SequenceCache(fs::path root, SceneSettings scene) : root_(std::move(root)), scene_(scene) {}

  /// The folder of the cell's sequence, rendered first when absent or incomplete.
  std::string folder(const SweepCell& cell) const {
    const SequenceWriterOptions o = writer_options(scene_, cell);
    const fs::path dir = root_ / (cell.model->name + "-" + cell.depth.name + "-" + cell.image.name + "-" +
                                  short_hash(sequence_key(*cell.model, o)));
    if (fs::is_regular_file(dir / "sequence.yaml")) return dir.string();
    // Rendered beside and renamed when complete: an interrupted run leaves no half sequence.
    const fs::path partial = dir.string() + ".partial";
    fs::remove_all(partial);
    std::cerr << "sweep: rendering " << dir.filename().string() << " (" << o.frame_count << " frames)\n";
    SequenceWriter writer(o);
    writer.add_object(cell.model->name, load_any_mesh(cell.model->mesh_path), Pose(), cell.model->mesh_path);
    writer.write(partial.string());
    fs::rename(partial, dir);
    return dir.string();
  }

 private:
  fs::path root_;
  SceneSettings scene_;
};

std::vector<Frame> load_frames(const std::string& dir, bool grey_without_depth) {
  SequenceOptions options;
  options.grey_without_depth = grey_without_depth;
  const Sequence sequence = Sequence::open(dir, options);
  std::vector<Frame> frames;
  for (int i = 0; i < sequence.size(); ++i) frames.push_back(sequence.load(i));
  return frames;
}

int lost_frames(const TrackingEvaluation& evaluation) {
  int lost = 0;
  for (const FrameEvaluation& f : evaluation.frames())
    if (!f.tracked || (f.has_truth && (f.t_mm > kLostTranslationMm || f.r_deg > kLostRotationDeg))) ++lost;
  return lost;
}

/// Builds each tracker of a cell and runs it over the cell's frames.
class CellTrackers {
 public:
  CellTrackers(fs::path visp_dir, std::optional<TrackerConfig> viewpoint_models)
      : visp_dir_(std::move(visp_dir)), viewpoint_models_(std::move(viewpoint_models)) {}

  struct Job {
    std::string name;
    std::function<TrackingEvaluation(const std::vector<Frame>&, const std::string& body, const Mesh&)> run;
  };

  std::vector<Job> jobs(const SweepCell& cell) const {
    const SweepModel& m = *cell.model;
    std::vector<Job> jobs;
    if (cell.grey) {
      // Without a depth camera, the presets' colour cues.
      jobs.push_back(icgp_job(kIcgpDefaults + " (region + texture)", icgp_config("default", m, {"region", "texture"})));
      jobs.push_back(
          icgp_job(kIcgReference + " (region + texture)", icgp_config("icg_reference", m, {"region", "texture"})));
      jobs.push_back(visp_job("ViSP edge", {"edge (no depth)", true, false, false}, m));
      jobs.push_back(visp_job("ViSP edge + KLT", visp_reference_configuration("edge + KLT (no depth)"), m));
      return jobs;
    }
    jobs.push_back(icgp_job(kIcgpDefaults, icgp_config("default", m, {})));
    jobs.push_back(icgp_job(kIcgpRegionDepth, icgp_config("default", m, {"region", "depth"})));
    jobs.push_back(icgp_job(kIcgReference, icgp_config("icg_reference", m, {})));
    jobs.push_back(visp_job(kVispRgbd, visp_reference_configuration("edge + KLT + dense depth"), m));
    return jobs;
  }

 private:
  /// A preset with the model's colour regions, optionally other modalities and the
  /// viewpoint-model resolution of --viewpoint-models.
  TrackerConfig icgp_config(const std::string& preset, const SweepModel& model,
                            const std::vector<std::string>& modalities) const {
    TrackerConfig config = tracker_config_preset(preset);
    config.regions = model.regions;
    if (!modalities.empty()) config.modalities = parse_cue_list(modalities);
    if (viewpoint_models_) {
      config.region_model = viewpoint_models_->region_model;
      config.depth_model = viewpoint_models_->depth_model;
    }
    return config;
  }

  static Job icgp_job(const std::string& name, const TrackerConfig& config) {
    return {name, [config](const std::vector<Frame>& frames, const std::string& body, const Mesh& mesh) {
              return evaluate_tracker(FrameSource::of(frames), body, mesh, config, *frames.front().truth(body));
            }};
  }

  /// vpMbGenericTracker on a .cao written from the model's mesh. ViSP throws when it
  /// cannot track (too few features): that frame is lost and keeps the previous pose.
  Job visp_job(const std::string& name, const VispTrackerConfiguration& configuration, const SweepModel& model) const {
    const std::string files_dir = (visp_dir_ / model.name).string();
    const std::string mesh_path = model.mesh_path;
    return {name, [=](const std::vector<Frame>& frames, const std::string& body, const Mesh& mesh) {
              VispRgbdTracker tracker(configuration, VispModelFiles::written_for_mesh(mesh_path, files_dir));
              return evaluate_sequence(FrameSource::of(frames), body, mesh, tracker.as_run_tracker(),
                                       *frames.front().truth(body));
            }};
  }

  fs::path visp_dir_;
  std::optional<TrackerConfig> viewpoint_models_;
};

std::string clock_text(double seconds) {
  const long s = std::lround(seconds);
  char text[32];
  if (s >= 3600)
    std::snprintf(text, sizeof text, "%ldh%02ldm%02lds", s / 3600, s / 60 % 60, s % 60);
  else
    std::snprintf(text, sizeof text, "%ldm%02lds", s / 60, s % 60);
  return text;
}

/// Cells done of the total, time elapsed and an estimate of the time left, on stderr.
class SweepProgress {
 public:
  explicit SweepProgress(std::size_t total) : total_(total), begin_(Clock::now()) {}
  double elapsed() const { return std::chrono::duration<double>(Clock::now() - begin_).count(); }
  void cell_done(const SweepCell& cell) {
    ++done_;
    const double seconds = elapsed();
    const double left = seconds / double(done_) * double(total_ - done_);
    std::fprintf(stderr, "sweep: %zu/%zu cells (%s / %s / %s), elapsed %s, ETA %s\n", done_, total_,
                 cell.model->name.c_str(), cell.depth_label().c_str(), cell.image_label().c_str(),
                 clock_text(seconds).c_str(), clock_text(left).c_str());
  }

 private:
  std::size_t total_, done_ = 0;
  Clock::time_point begin_;
};

void print_table(const std::vector<SweepRow>& rows, int frames) {
  std::printf("\nicgp bench --sweep: %d frames per cell, each tracker started at the first ground-truth pose, one thread\n"
              "lost = frames the tracker reported lost (icgp: quality below its threshold; ViSP: track() threw)\n"
              "       or whose error exceeded %.0f mm or %.0f deg\n\n",
              frames, kLostTranslationMm, kLostRotationDeg);
  TextTable table(columns({{"model", 16, true}, {"depth", 9, true}, {"image", 20, true}, {"tracker", 32, true}},
                          {accuracy_columns(8), {{"ADD", 7}, {"ADD-S", 7}, {"lost", 5}, {"median ms", 9}}}));
  for (const SweepRow& r : rows) {
    const TrackingSummary& s = r.summary;
    table.text(r.model).text(r.depth).text(r.image).text(r.tracker).accuracy(s);
    table.number(s.add_auc, 1).number(s.adds_auc, 1).integer(r.lost).number(s.median_ms, 2).end_row();
  }
  table.print();
  std::printf("\nADD / ADD-S: area under the accuracy curve up to 10 cm, percent (YCB-Video).\n");
}

void write_summary(const std::vector<SweepRow>& rows, int frames, const std::string& path) {
  std::vector<JsonObject> json_rows;
  for (const SweepRow& r : rows)
    json_rows.push_back(JsonObject()
                            .add("model", r.model)
                            .add("depth", r.depth)
                            .add("image", r.image)
                            .add("tracker", r.tracker)
                            .add("lost", r.lost)
                            .add_fields(r.summary.to_json()));
  JsonObject()
      .add("frames_per_cell", frames)
      .add("lost_translation_mm", kLostTranslationMm)
      .add("lost_rotation_deg", kLostRotationDeg)
      .add("rows", json_rows)
      .write(path);
}

/// Mean translation error over all frames of the models, against the depth condition: one
/// panel per image condition, one line per RGB-D tracker.
void plot_sweep(const std::vector<SweepRow>& rows, const fs::path& script, const std::string& png) {
  const std::vector<std::string> trackers = {kIcgpDefaults, kIcgpRegionDepth, kIcgReference, kVispRgbd};
  const std::vector<DepthCondition> depths = depth_conditions();
  std::vector<std::string> images;
  for (const ImageCondition& image : image_conditions())
    for (const SweepRow& r : rows)
      if (r.image == image.name) {
        images.push_back(image.name);
        break;
      }

  std::ostringstream s;
  s << gnuplot_png_preamble("icgp bench --sweep", "gnuplot " + script.filename().string(), 1500, 520);
  s << "set output '" << png << "'\n";
  s << "set logscale y\nset format y '%g'\n";
  s << "set xtics ('exact' 0, 'RealSense-class' 1, 'Kinect-class' 2)\nset xrange [-0.3:2.3]\n";
  s << "set key below\nset ylabel 'mean translation error (mm, all models)'\n";
  s << "set multiplot layout 1," << images.size() << " title 'icgp bench --sweep: defaults vs reference vs ViSP'\n";
  // One datablock per panel, $d0, $d1, ...: depth level, then each tracker's mean error.
  for (std::size_t i = 0; i < images.size(); ++i) {
    s << "$d" << i << " << EOD\n";
    for (std::size_t d = 0; d < depths.size(); ++d) {
      s << d;
      for (const std::string& tracker : trackers) {
        double sum = 0.0;
        int count = 0;
        for (const SweepRow& r : rows)
          if (r.image == images[i] && r.depth == depths[d].name && r.tracker == tracker) sum += r.summary.mean_t_mm, ++count;
        s << " " << (count ? std::to_string(sum / count) : std::string("NaN"));
      }
      s << "\n";
    }
    s << "EOD\n";
    s << "set title '" << images[i] << "'\nplot ";
    for (std::size_t t = 0; t < trackers.size(); ++t)
      s << (t ? ", " : "") << "$d" << i << " using 1:" << t + 2 << " with linespoints lw 2 pt " << 5 + 2 * t
      << " title '" << trackers[t] << "'";
    s << "\n";
  }
  s << "unset multiplot\nset output\n";

  draw_with_gnuplot(s.str(), script, {png});
}

}  // namespace

std::vector<SweepModel> sweep_models() {
  const std::string m = models_dir();
  return {{"textured_box", m + "/textured_box/textured_box.obj", {}},
          {"two_region", m + "/two_region/object.obj", {m + "/two_region/region_body.obj", m + "/two_region/region_lid.obj"}},
          {"labelled_can",
           m + "/labelled_can/object.obj",
           {m + "/labelled_can/region_label.obj", m + "/labelled_can/region_caps.obj"}},
          {"textureless_mug", m + "/textureless_mug/textureless_mug.obj", {}}};
}

void run_sweep(const SweepOptions& options) {
  if (options.frames < 2) throw std::invalid_argument("sweep: --frames must be at least 2, got " + std::to_string(options.frames));
  SceneSettings scene;
  scene.frames = options.frames;
  if (options.quick) {
    scene.width = 320, scene.height = 240, scene.focal = 300.0;
    scene.frames = std::min(options.frames, 8);
  }
  std::optional<TrackerConfig> viewpoint_models;
  if (!options.viewpoint_models.empty()) viewpoint_models = load_tracker_config(options.viewpoint_models);

  const fs::path out(options.out);
  fs::create_directories(out);
  const SequenceCache cache(out / "sequences", scene);
  const CellTrackers trackers(out / "visp-models", viewpoint_models);
  const std::vector<SweepModel> models = sweep_models();
  const std::vector<SweepCell> cells = sweep_cells(models, options.quick);
  std::cerr << "sweep: " << cells.size() << " cells of " << scene.frames << " frames (" << scene.width << "x"
            << scene.height << "), sequences cached in " << (out / "sequences").string()
            << "; icgp generates each model's viewpoint models on first use (cached)\n";

  SweepProgress progress(cells.size());
  std::vector<SweepRow> rows;
  for (const SweepCell& cell : cells) {
    const std::vector<Frame> frames = load_frames(cache.folder(cell), cell.grey);
    const Mesh mesh = load_any_mesh(cell.model->mesh_path);
    for (const CellTrackers::Job& job : trackers.jobs(cell)) {
      const SingleThreadScope single_thread;
      const TrackingEvaluation evaluation = job.run(frames, cell.model->name, mesh);
      rows.push_back({cell.model->name, cell.depth_label(), cell.image_label(), job.name, evaluation.summary(),
                      lost_frames(evaluation)});
    }
    progress.cell_done(cell);
  }

  print_table(rows, scene.frames);
  std::printf("sweep took %s\n", clock_text(progress.elapsed()).c_str());
  if (!options.summary.empty()) {
    write_summary(rows, scene.frames, options.summary);
    std::printf("wrote %s\n", options.summary.c_str());
  }
  if (!options.plot.empty()) {
    const fs::path png = fs::absolute(options.plot);
    fs::create_directories(png.parent_path());
    plot_sweep(rows, out / "sweep_plot.gp", png.string());
    std::printf("plot: %s (mean translation error against depth noise, per image condition)\n", options.plot.c_str());
  }
  std::fflush(stdout);
}

}  // namespace icgp::app
