// SPDX-License-Identifier: GPL-2.0-or-later
#include "detect_bench.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "icgp/detection/body_detector.h"
#include "icgp/detection/mesh_symmetries.h"
#include "icgp/eval/gnuplot.h"
#include "icgp/eval/json_object.h"
#include "icgp/eval/metrics.h"
#include "icgp/eval/sequence.h"
#include "icgp/eval/sequence_writer.h"
#include "icgp/render/renderer.h"
#include "icgp/render/sensor_effects.h"
#include "icgp/tracker/tracker_builder.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/keypoint_baseline.h"
#include "commands.h"
#include "sweep.h"
#include "text_table.h"

namespace icgp::app {
namespace {

namespace fs = std::filesystem;

/// A detection within this of the truth is right; a pose whose ADD-S is within it, an
/// equivalent one of a symmetric model.
constexpr double kRightMm = 5.0, kRightDeg = 5.0;

/// A detected pose this far from the truth and from each pose the model's symmetries make
/// equivalent to it, or any pose in a frame without the object, would send a robot
/// somewhere else: the bench counts them apart.
constexpr double kFarMm = 50.0, kFarDeg = 15.0;

/// Camera distances to the object (the orbit's mean, ±0.1 m), covering 0.3-1.0 m.
const std::vector<double> kDistances = {0.4, 0.65, 0.9};

struct Sensor {
  std::string name;
  SensorNoise noise;
  bool grey = false;  ///< grey images, no depth
};

const Sensor kExact{"exact", SensorNoise{}, false};
const Sensor kRealSense{"realsense", SensorNoise::realsense_class(), false};
const Sensor kKinect{"kinect", SensorNoise::kinect_class(), false};
const Sensor kGrey{"grey, no depth", SensorNoise{}, true};

/// What stands around the object.
enum class Scene {
  kPlain,        ///< the object before the clutter plane
  kDistractors,  ///< the sweep's other objects beside it, painted in its mean colour
  kOccluded,     ///< a bar between camera and object, covering a changing part of it
  kEmpty,        ///< the other objects, and the object itself out of view
  kTable,        ///< the object lying on a plain white table, as a camera with auto-exposure sees it
};

std::string scene_name(Scene scene) {
  switch (scene) {
    case Scene::kPlain: return "plain";
    case Scene::kDistractors: return "distractors";
    case Scene::kOccluded: return "occluded";
    case Scene::kEmpty: return "no object";
    case Scene::kTable: return "on a table";
  }
  return "";
}

struct Row {
  Scene scene;
  Sensor sensor;
};

/// Every object's rows: each sensor class on the plain scene, then the harder scenes with
/// RealSense-class depth and in grey without depth.
std::vector<Row> rows() {
  std::vector<Row> r;
  for (const Sensor& s : {kExact, kRealSense, kKinect, kGrey}) r.push_back({Scene::kPlain, s});
  for (const Scene scene : {Scene::kDistractors, Scene::kOccluded, Scene::kEmpty, Scene::kTable})
    for (const Sensor& s : {kRealSense, kGrey}) r.push_back({scene, s});
  return r;
}

/// The sweep's objects and a textureless figurine that no other benchmark tracks: a shape
/// with nothing but its silhouette and relief to go by.
std::vector<SweepModel> detect_models() {
  std::vector<SweepModel> objects = sweep_models();
  objects.push_back({"figurine", models_dir() + "/figurine/figurine.obj", {}});
  return objects;
}

enum class Outcome { kRight, kEquivalent, kWrong, kNotFound };

/// A pose against the truth.
struct Judged {
  Outcome outcome = Outcome::kNotFound;
  double t_mm = 0.0, r_deg = 0.0;  ///< of a found pose from the truth (infinite with no object)
  bool far = false;                ///< found, and sent somewhere else (kFarMm, kFarDeg)
};

/// One frame's results: icgp's detector and, for a textured object, vpKeyPoint's.
struct FrameResult {
  Judged icgp;
  double ms = 0.0;
  std::optional<Judged> baseline;
  double baseline_ms = 0.0;
  double occlusion = 0.0;  ///< share of the object's pixels hidden by the bar
};

/// The mean colour of a mesh (its textures' and flat colours'), linear RGB.
Eigen::Vector3f mean_colour(const Mesh& mesh) {
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  for (const MeshPart& part : mesh.parts) {
    if (part.material.texture_bgr.empty()) {
      sum += part.material.diffuse_rgb;
      continue;
    }
    const cv::Scalar bgr = cv::mean(part.material.texture_bgr);
    for (int c = 0; c < 3; ++c) sum[c] += static_cast<float>(std::pow(bgr[2 - c] / 255.0, 2.2));  // sRGB -> linear
  }
  return sum / static_cast<float>(mesh.parts.size());
}

Mesh painted(Mesh mesh, const Eigen::Vector3f& rgb) {
  for (MeshPart& part : mesh.parts) {
    part.material.texture_bgr.release();
    part.texcoords.clear();
    part.material.diffuse_rgb = rgb;
  }
  return mesh;
}

/// The bar of the occluded scene, as thick as a third of the object's bounding sphere.
Mesh occluding_bar(const Mesh& object) {
  const double radius = bounding_sphere(object).radius;
  return box_mesh(Eigen::Vector3d(0.6 * radius, 1.0, 0.6 * radius), Eigen::Vector3f(0.5f, 0.5f, 0.5f));
}

/// The table scene's camera: RealSense-class noise, a hand-held exposure of 1/60 s (the
/// bench's frames are half a second apart) and an auto-exposure that hunts by ±30 %.
void table_camera(SequenceWriterOptions& o) {
  o.noise = SensorNoise::realsense_class();
  o.motion_blur = MotionBlur{4, o.frame_rate / 60.0};
  o.gain_variation = 0.3;
}

/// A plain white table top under the object, touching its lowest point (it lies on its -Z
/// side, so the camera's orbit sees it from above and the sides).
BackgroundPlane table_under(const Mesh& mesh) {
  Eigen::Vector3f lowest, highest;
  mesh.bounds(lowest, highest);
  BackgroundPlane table;
  table.distance = -lowest.z();
  table.texture_bgr = cv::Mat(8, 8, CV_8UC3, cv::Scalar(215, 220, 222));
  return table;
}

/// The cell's sequence: fast, wide orbits (so that the frames show the object from many
/// sides) in front of the clutter plane, with the scene's props, rendered once under `root`.
/// The table scene's sequence serves both of its rows (the grey one reads its colour only).
std::string sequence_folder(const fs::path& root, const SweepModel& object, const std::vector<SweepModel>& all,
                            Scene scene, const Sensor& sensor, double distance, int frames) {
  char name[160];
  std::snprintf(name, sizeof name, "%s%s-%s-%.2f-%d", object.name.c_str(),
                scene == Scene::kPlain         ? ""
                : scene == Scene::kDistractors ? "-distractors"
                : scene == Scene::kOccluded    ? "-occluded"
                : scene == Scene::kTable       ? "-table"
                                               : "-empty",
                scene == Scene::kTable ? "realsense" : sensor.grey ? "exact" : sensor.name.c_str(), distance, frames);
  const fs::path dir = root / name;
  if (fs::is_regular_file(dir / "sequence.yaml")) return dir.string();
  SequenceWriterOptions o;
  o.frame_count = frames;
  o.frame_rate = 2.0;  // frames far apart in time: poses far apart on the orbit
  o.seed = 11;
  o.color_intrinsics = o.depth_intrinsics = Intrinsics::centred(640, 480, 600.0);
  o.depth_T_color = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.025, 0.0, 0.0));
  o.motion.distance = distance;
  o.motion.speed = 3.0;
  o.noise = sensor.grey ? SensorNoise{} : sensor.noise;
  o.antialias_samples = 4;
  o.progress = false;
  const Mesh mesh = load_any_mesh(object.mesh_path);
  if (scene == Scene::kTable) {
    table_camera(o);
    o.background = table_under(mesh);
  }
  const fs::path partial = dir.string() + ".partial";
  fs::remove_all(partial);
  std::cerr << "bench --detect: rendering " << dir.filename().string() << "\n";
  SequenceWriter writer(o);
  const double radius = bounding_sphere(mesh).radius;
  // The object itself; out of view, behind the clutter plane, in the scene without it.
  const Pose hidden(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.0, -3.0));
  writer.add_object(object.name, mesh, scene == Scene::kEmpty ? hidden : Pose(), object.mesh_path);
  if (scene == Scene::kDistractors || scene == Scene::kEmpty) {
    // The other objects around it, a hand's width apart; beside the object they wear its
    // mean colour, so that only shape and texture tell them apart.
    const Eigen::Vector3f colour = mean_colour(mesh);
    const std::array<Eigen::Vector2d, 3> directions = {Eigen::Vector2d(1.0, 0.2), Eigen::Vector2d(-1.0, 0.4),
                                                       Eigen::Vector2d(0.1, -1.0)};
    std::size_t k = 0;
    for (const SweepModel& other : all) {
      if (other.name == object.name || k == directions.size()) continue;
      const Mesh other_mesh = load_any_mesh(other.mesh_path);
      const double gap = radius + bounding_sphere(other_mesh).radius + 0.02;
      const Eigen::Vector2d at = gap * directions[k++].normalized();
      writer.add_object(other.name, scene == Scene::kDistractors ? painted(other_mesh, colour) : other_mesh,
                        Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(at.x(), at.y(), 0.0)));
    }
  }
  if (scene == Scene::kOccluded) {
    // A grey bar standing in front of the object, off its centre: as the camera swings,
    // it covers none to about a third of the object.
    writer.add_object("occluder", occluding_bar(mesh),
                      Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.6 * radius, 0.0, 1.8 * radius)));
  }
  writer.write(partial.string());
  fs::rename(partial, dir);
  return dir.string();
}

/// The share of the object's pixels the occluder hides at the frame's true poses.
class OcclusionMeter {
 public:
  OcclusionMeter(const Mesh& object, const Mesh& occluder, const Intrinsics& camera)
      : camera_(camera), object_(renderer_.add_body(object, 1)), occluder_(renderer_.add_body(occluder, 2)) {}

  double occlusion(const Frame& frame, const std::string& object) {
    const Pose* object_pose = frame.truth(object);
    const Pose* occluder_pose = frame.truth("occluder");
    if (!object_pose || !occluder_pose) return 0.0;
    renderer_.set_body_pose(object_, *object_pose);
    renderer_.set_body_pose(occluder_, *occluder_pose);
    renderer_.set_body_visible(occluder_, false);
    const int alone = cv::countNonZero(renderer_.render(camera_, Pose(), kRenderIds).ids == 1);
    renderer_.set_body_visible(occluder_, true);
    const int seen = cv::countNonZero(renderer_.render(camera_, Pose(), kRenderIds).ids == 1);
    return alone > 0 ? 1.0 - static_cast<double>(seen) / alone : 0.0;
  }

 private:
  Renderer renderer_;
  Intrinsics camera_;
  Renderer::BodyHandle object_, occluder_;
};

/// Judges found poses of one object: right within kRightMm and kRightDeg, equivalent when
/// its ADD-S is within kRightMm, and far off when it is beyond kFarMm or kFarDeg of the truth
/// and of each pose the model's symmetries (as its detector finds them) make equivalent to
/// it: a symmetric twin whose sampled ADD-S comes out a little over kRightMm is not far off.
class PoseJudge {
 public:
  explicit PoseJudge(const Mesh& mesh) : surface_(mesh), symmetries_(mesh_symmetries(mesh)) {}

  /// `truth` null: a frame without the object, where any pose is wrong and far off.
  Judged judge(const Pose& estimate, const Pose* truth) const {
    Judged j;
    if (!truth) {
      j.outcome = Outcome::kWrong;
      j.t_mm = j.r_deg = std::numeric_limits<double>::infinity();
      j.far = true;
      return j;
    }
    j.t_mm = translation_error_mm(estimate, *truth);
    j.r_deg = rotation_error_deg(estimate, *truth);
    if (j.t_mm <= kRightMm && j.r_deg <= kRightDeg) {
      j.outcome = Outcome::kRight;
    } else if (1e3 * surface_.adds(estimate, *truth) <= kRightMm) {
      j.outcome = Outcome::kEquivalent;
    } else {
      j.outcome = Outcome::kWrong;
      j.far = !near(estimate, *truth) && std::none_of(symmetries_.begin(), symmetries_.end(), [&](const Pose& symmetry) {
                return near(estimate, *truth * symmetry);
              });
    }
    return j;
  }

 private:
  static bool near(const Pose& estimate, const Pose& truth) {
    return translation_error_mm(estimate, truth) <= kFarMm && rotation_error_deg(estimate, truth) <= kFarDeg;
  }

  ModelPointErrors surface_;
  std::vector<Pose> symmetries_;
};

double elapsed_ms(std::chrono::steady_clock::time_point begin) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
}

std::vector<FrameResult> detect_cell(const std::string& folder, const SweepModel& object, const Row& row,
                                     BodyDetector& detector, KeypointBaseline* baseline,
                                     const PoseJudge& judge, OcclusionMeter* occlusion) {
  SequenceOptions options;
  options.grey_without_depth = row.sensor.grey;
  const Sequence sequence = Sequence::open(folder, options);
  std::vector<FrameResult> results;
  for (int i = 0; i < sequence.size(); ++i) {
    const Frame frame = sequence.load(i);
    const Pose* truth = row.scene == Scene::kEmpty ? nullptr : frame.truth(object.name);
    FrameResult r;
    auto begin = std::chrono::steady_clock::now();
    const Detection d = detector.detect(frame);
    r.ms = elapsed_ms(begin);
    if (d.found) r.icgp = judge.judge(d.reference_T_body, truth);
    if (baseline) {
      cv::Mat grey = frame.colors.front().image;
      if (grey.channels() == 3) cv::cvtColor(grey, grey, cv::COLOR_BGR2GRAY);
      begin = std::chrono::steady_clock::now();
      const std::optional<Pose> pose = baseline->locate(grey, frame.colors.front().intrinsics);
      r.baseline_ms = elapsed_ms(begin);
      r.baseline = pose ? judge.judge(*pose, truth) : Judged{};
    }
    if (occlusion) r.occlusion = occlusion->occlusion(frame, object.name);
    results.push_back(r);
  }
  return results;
}

/// Counts of one tracker's outcomes over a row.
struct Tally {
  int frames = 0, right = 0, equivalent = 0, wrong = 0, not_found = 0;
  int far_wrong = 0;                    ///< wrong and far off (Judged::far)
  std::vector<double> ms, t_mm, r_deg;  ///< t_mm, r_deg: of the right ones
  /// The frame (1, 2, ...) on which the object is first found right or equivalent, worst
  /// over the row's sequences; 0 when one of them never finds it.
  int first_found = 1;
  int frames_in_sequence = 0, found_on = 0;  ///< of the sequence being added
  void start_sequence() { frames_in_sequence = found_on = 0; }
  void end_sequence() { first_found = found_on == 0 || first_found == 0 ? 0 : std::max(first_found, found_on); }
  void add(const Judged& judged, double time) {
    const Outcome o = judged.outcome;
    ++frames;
    ++frames_in_sequence;
    ms.push_back(time);
    if (found_on == 0 && (o == Outcome::kRight || o == Outcome::kEquivalent)) found_on = frames_in_sequence;
    far_wrong += judged.far;
    switch (o) {
      case Outcome::kRight:
        ++right;
        t_mm.push_back(judged.t_mm);
        r_deg.push_back(judged.r_deg);
        break;
      case Outcome::kEquivalent: ++equivalent; break;
      case Outcome::kWrong: ++wrong; break;
      case Outcome::kNotFound: ++not_found; break;
    }
  }
  double share(int n) const { return frames ? 100.0 * n / frames : 0.0; }
  JsonObject json() const {
    return JsonObject()
        .add("frames", frames)
        .add("right", right)
        .add("equivalent", equivalent)
        .add("wrong", wrong)
        .add("not_found", not_found)
        .add("far_wrong", far_wrong)
        .add("first_found", first_found)
        .add("median_t_mm", t_mm.empty() ? -1.0 : median(t_mm))
        .add("median_r_deg", r_deg.empty() ? -1.0 : median(r_deg))
        .add("median_ms", median(ms))
        .add("p90_ms", percentile(ms, 0.9));
  }
};

/// Poses sent far away over the whole bench (Judged::far), counted apart in the frames with
/// the object in view and in those without it.
struct FarWrongCount {
  struct Count {
    int icgp = 0, icgp_frames = 0, baseline = 0, baseline_frames = 0;
  };
  Count with_object, without_object;
  void add(const Tally& icgp_row, const std::optional<Tally>& baseline_row, bool object_in_view) {
    Count& c = object_in_view ? with_object : without_object;
    c.icgp += icgp_row.far_wrong;
    c.icgp_frames += icgp_row.frames;
    if (!baseline_row) return;
    c.baseline += baseline_row->far_wrong;
    c.baseline_frames += baseline_row->frames;
  }
  void print() const {
    std::printf("poses found more than %.0f mm or %.0f deg off the truth and its symmetric twins (not equivalent): "
                "icgp %d of %d frames, vpKeyPoint %d of %d frames; poses found in frames without the object: icgp %d "
                "of %d, vpKeyPoint %d of %d\n",
                kFarMm, kFarDeg, with_object.icgp, with_object.icgp_frames, with_object.baseline,
                with_object.baseline_frames, without_object.icgp, without_object.icgp_frames, without_object.baseline,
                without_object.baseline_frames);
  }
  JsonObject json() const {
    return JsonObject()
        .add("icgp", with_object.icgp + without_object.icgp)
        .add("icgp_frames", with_object.icgp_frames + without_object.icgp_frames)
        .add("vpKeyPoint", with_object.baseline + without_object.baseline)
        .add("vpKeyPoint_frames", with_object.baseline_frames + without_object.baseline_frames)
        .add("icgp_with_object", with_object.icgp)
        .add("icgp_without_object", without_object.icgp)
        .add("vpKeyPoint_with_object", with_object.baseline)
        .add("vpKeyPoint_without_object", without_object.baseline);
  }
};

const char* const kOcclusionBinNames[] = {"0-10 %", "10-20 %", "20-30 %", "30 % and more"};

/// Success (right or equivalent) against the occluded share, in bins, for one line.
struct OcclusionLine {
  std::string title;
  static constexpr int kBins = 4;  ///< 0-10, 10-20, 20-30, 30+ %
  std::array<int, kBins> frames{}, found{};
  void add(double occlusion, Outcome o) {
    const int bin = std::min(kBins - 1, static_cast<int>(occlusion * 10.0));
    ++frames[bin];
    found[bin] += o == Outcome::kRight || o == Outcome::kEquivalent;
  }
};

void plot_occlusion(const std::vector<OcclusionLine>& lines, const fs::path& script, const std::string& png) {
  std::ostringstream s;
  s << gnuplot_png_preamble("icgp bench --detect", "gnuplot " + script.filename().string(), 900, 520);
  s << "set output '" << png << "'\n";
  s << "set yrange [0:105]\n";
  s << "set xtics ('0-10 %%' 0, '10-20 %%' 1, '20-30 %%' 2, '30 %% and more' 3)\nset xrange [-0.3:3.3]\n";
  s << "set xlabel 'share of the object hidden by the bar'\nset ylabel 'found within 5 mm / 5 deg or equivalent (%)'\n";
  s << "set key below\nset title 'icgp bench --detect: detection under partial occlusion'\n";
  s << "$d << EOD\n";
  for (int b = 0; b < OcclusionLine::kBins; ++b) {
    s << b;
    for (const OcclusionLine& l : lines)
      s << " " << (l.frames[b] ? std::to_string(100.0 * l.found[b] / l.frames[b]) : std::string("NaN"));
    s << "\n";
  }
  s << "EOD\nplot ";
  for (std::size_t i = 0; i < lines.size(); ++i)
    s << (i ? ", " : "") << "$d using 1:" << i + 2 << " with linespoints lw 2 pt " << 5 + 2 * i << " title '"
      << lines[i].title << "'";
  s << "\nset output\n";
  draw_with_gnuplot(s.str(), script, {png});
}

/// The table of outcomes, printed a row at a time as each finishes.
TextTable outcome_table() {
  const std::vector<TableColumn> shares = {{"right", 7}, {"equiv", 7}, {"wrong", 7}, {"miss", 7}};
  return TextTable(columns({{"object", 16, true}, {"scene", 11, true}, {"sensor", 15, true}, {"frames", 6}},
                           {shares, {{"t mm", 5}, {"r deg", 5}, {"ms", 6}, {"p90", 6}, {"1st", 4}, {"|", 1}}, shares, {{"ms", 6}}}),
                   {{"", 4}, {"icgp", 9}, {"|", 1}, {"vpKeyPoint", 5}});
}

void print_row(TextTable& table, const std::string& object, const Row& row, const Tally& icgp,
               const std::optional<Tally>& baseline) {
  const auto shares = [&table](const Tally& t) {
    table.percent(t.share(t.right)).percent(t.share(t.equivalent)).percent(t.share(t.wrong)).percent(t.share(t.not_found));
  };
  table.text(object).text(scene_name(row.scene)).text(row.sensor.name).integer(icgp.frames);
  shares(icgp);
  table.number(icgp.t_mm.empty() ? -1.0 : median(icgp.t_mm), 2).number(icgp.r_deg.empty() ? -1.0 : median(icgp.r_deg), 2);
  table.number(median(icgp.ms), 0).number(percentile(icgp.ms, 0.9), 0);
  table.text(row.scene == Scene::kEmpty ? "" : icgp.first_found == 0 ? "none" : std::to_string(icgp.first_found));
  if (baseline) {
    table.text("|");
    shares(*baseline);
    table.number(median(baseline->ms), 0);
  } else {
    for (int i = 0; i < 6; ++i) table.text("");
  }
  table.end_row();
  table.print_last_row();
  std::fflush(stdout);
}

}  // namespace

void run_detect_bench(const DetectBenchOptions& options) {
  const fs::path root(options.out);
  fs::create_directories(root);
  const std::vector<SweepModel> all_objects = detect_models();
  std::vector<SweepModel> objects;
  for (const SweepModel& m : all_objects)
    if (options.objects.empty() ||
        std::find(options.objects.begin(), options.objects.end(), m.name) != options.objects.end())
      objects.push_back(m);
  for (const std::string& name : options.objects)
    if (std::none_of(all_objects.begin(), all_objects.end(), [&](const SweepModel& m) { return m.name == name; }))
      throw std::invalid_argument("bench --detect --object: '" + name +
                                  "' is none of the bench's objects (textured_box, two_region, labelled_can, "
                                  "textureless_mug, figurine)");
  const std::vector<Row> row_list = rows();
  TextTable table = outcome_table();
  table.print_header();
  std::vector<JsonObject> json_rows;
  FarWrongCount far_wrong;
  OcclusionLine icgp_rgbd{"icgp, RealSense-class RGB-D (" + std::to_string(objects.size()) + " objects)"}, icgp_grey{"icgp, grey (textured objects)"},
      vp_grey{"vpKeyPoint, grey (textured objects)"};
  const auto start = std::chrono::steady_clock::now();
  int rows_done = 0;
  const int row_count = static_cast<int>(objects.size() * row_list.size());
  for (const SweepModel& object : objects) {
    const Mesh mesh = load_any_mesh(object.mesh_path);
    const PoseJudge judge(mesh);
    auto renderer = std::make_shared<SceneRenderer>();
    std::unique_ptr<KeypointBaseline> baseline;
    if (has_texture(mesh))
      baseline = std::make_unique<KeypointBaseline>(render_training_views(*renderer, Body{object.name, mesh, Pose()}));
    OcclusionMeter occlusion(mesh, occluding_bar(mesh), Intrinsics::centred(640, 480, 600.0));
    for (const Row& row : row_list) {
      TrackerConfig config;  // icgp's defaults
      config.regions = object.regions;
      if (row.sensor.grey)
        config.modalities.erase(std::remove(config.modalities.begin(), config.modalities.end(), cue::kDepth),
                                config.modalities.end());
      BodyDetector detector(config, mesh, object.name, configured_cameras(config), renderer);
      Tally icgp;
      std::optional<Tally> vp;
      if (baseline) vp.emplace();
      for (const double distance : kDistances) {
        const std::string folder =
            sequence_folder(root, object, all_objects, row.scene, row.sensor, distance, options.frames);
        icgp.start_sequence();
        if (vp) vp->start_sequence();
        for (const FrameResult& f : detect_cell(folder, object, row, detector, baseline.get(), judge,
                                                row.scene == Scene::kOccluded ? &occlusion : nullptr)) {
          icgp.add(f.icgp, f.ms);
          if (vp) vp->add(*f.baseline, f.baseline_ms);
          if (row.scene != Scene::kOccluded) continue;
          if (!row.sensor.grey) icgp_rgbd.add(f.occlusion, f.icgp.outcome);
          if (row.sensor.grey && vp) {  // grey: the textured objects, where vpKeyPoint runs too
            icgp_grey.add(f.occlusion, f.icgp.outcome);
            vp_grey.add(f.occlusion, f.baseline->outcome);
          }
        }
        icgp.end_sequence();
        if (vp) vp->end_sequence();
      }
      far_wrong.add(icgp, vp, row.scene != Scene::kEmpty);
      print_row(table, object.name, row, icgp, vp);
      JsonObject json = JsonObject()
                            .add("object", object.name)
                            .add("scene", scene_name(row.scene))
                            .add("sensor", row.sensor.name)
                            .add("icgp", icgp.json());
      if (vp) json.add("vpKeyPoint", vp->json());
      json_rows.push_back(json);
      ++rows_done;
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::fprintf(stderr, "bench --detect: %d/%d rows, %.0f s, about %.0f s left\n", rows_done, row_count, elapsed,
                   elapsed / rows_done * (row_count - rows_done));
    }
  }
  std::printf(
      "right: within %.0f mm and %.0f deg of the truth (t mm, r deg: their medians); equiv: ADD-S within %.0f mm (a "
      "pose the model's symmetry cannot tell apart); miss: not found; 1st: the frame on which the object is first "
      "found right or equivalent, the latest of the row's %zu sequences. On frames without the object every pose is "
      "wrong and 'miss' is the right answer. Frames at %.2f/%.2f/%.2f m, icgp's defaults, one thread; vpKeyPoint as "
      "ViSP's tutorial sets it, trained on the same renders (grey image only)\n",
      kRightMm, kRightDeg, kRightMm, kDistances.size(), kDistances[0], kDistances[1], kDistances[2]);
  far_wrong.print();
  std::vector<JsonObject> json_occlusion;
  for (const OcclusionLine& line : {icgp_rgbd, icgp_grey, vp_grey}) {
    std::printf("occlusion, %-38s", line.title.c_str());
    std::vector<JsonObject> bins;
    for (int b = 0; b < OcclusionLine::kBins; ++b) {
      std::printf("  %s: %5.1f%% of %3d", kOcclusionBinNames[b],
                  line.frames[b] ? 100.0 * line.found[b] / line.frames[b] : 0.0, line.frames[b]);
      bins.push_back(JsonObject().add("bin", kOcclusionBinNames[b]).add("frames", line.frames[b]).add("found", line.found[b]));
    }
    std::printf("\n");
    json_occlusion.push_back(JsonObject().add("line", line.title).add("bins", bins));
  }
  if (!options.summary.empty()) {
    JsonObject()
        .add("rows", json_rows)
        .add("occlusion", json_occlusion)
        .add("far_wrong", far_wrong.json())
        .write(options.summary);
    std::cout << "wrote " << options.summary << "\n";
  }
  plot_occlusion({icgp_rgbd, icgp_grey, vp_grey}, root / "occlusion.gp", fs::absolute(options.plot).string());
  std::cout << "plot " << options.plot << "\n";
}

}  // namespace icgp::app
