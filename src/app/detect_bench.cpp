// SPDX-License-Identifier: GPL-2.0-or-later
#include "detect_bench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "icgp/detection/body_detector.h"
#include "icgp/eval/json_object.h"
#include "icgp/eval/metrics.h"
#include "icgp/eval/sequence.h"
#include "icgp/eval/sequence_writer.h"
#include "icgp/render/sensor_effects.h"
#include "icgp/tracker/tracker_builder.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "sweep.h"

namespace icgp::app {
namespace {

namespace fs = std::filesystem;

/// A detection within this of the truth is right; a pose whose ADD-S is within it, an
/// equivalent one of a symmetric model.
constexpr double kRightMm = 5.0, kRightDeg = 5.0;

struct Sensor {
  std::string name;
  SensorNoise noise;
  bool grey = false;  ///< grey images, no depth
};

struct Tally {
  int frames = 0, right = 0, equivalent = 0, wrong = 0, not_found = 0;
  std::vector<double> ms;
  void add(const Tally& o) {
    frames += o.frames;
    right += o.right;
    equivalent += o.equivalent;
    wrong += o.wrong;
    not_found += o.not_found;
    ms.insert(ms.end(), o.ms.begin(), o.ms.end());
  }
};

std::vector<Sensor> sensors() {
  return {{"exact", SensorNoise{}, false},
          {"realsense", SensorNoise::realsense_class(), false},
          {"kinect", SensorNoise::kinect_class(), false},
          {"grey, no depth", SensorNoise{}, true}};
}

/// Camera distances to the object (the orbit's mean, ±0.1 m), covering 0.3-1.0 m.
const std::vector<double> kDistances = {0.4, 0.65, 0.9};

/// The cell's sequence: fast, wide orbits (so that the frames show the object from many
/// sides) in front of the clutter plane, rendered once under `root`.
std::string sequence_folder(const fs::path& root, const SweepModel& object, const Sensor& sensor, double distance,
                            int frames) {
  char name[128];
  std::snprintf(name, sizeof name, "%s-%s-%.2f-%d", object.name.c_str(), sensor.grey ? "exact" : sensor.name.c_str(),
                distance, frames);
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
  const fs::path partial = dir.string() + ".partial";
  fs::remove_all(partial);
  std::cerr << "bench --detect: rendering " << dir.filename().string() << "\n";
  SequenceWriter writer(o);
  writer.add_object(object.name, load_any_mesh(object.mesh_path), Pose(), object.mesh_path);
  writer.write(partial.string());
  fs::rename(partial, dir);
  return dir.string();
}

Tally detect_cell(const std::string& folder, const SweepModel& object, const Sensor& sensor, BodyDetector& detector,
                  const ModelPointErrors& surface) {
  SequenceOptions options;
  options.grey_without_depth = sensor.grey;
  const Sequence sequence = Sequence::open(folder, options);
  Tally t;
  for (int i = 0; i < sequence.size(); ++i) {
    const Frame frame = sequence.load(i);
    const auto begin = std::chrono::steady_clock::now();
    const Detection d = detector.detect(frame);
    t.ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count());
    ++t.frames;
    const Pose& truth = *frame.truth(object.name);
    if (!d.found) {
      ++t.not_found;
    } else if (translation_error_mm(d.reference_T_body, truth) <= kRightMm &&
               rotation_error_deg(d.reference_T_body, truth) <= kRightDeg) {
      ++t.right;
    } else if (1e3 * surface.adds(d.reference_T_body, truth) <= kRightMm) {
      ++t.equivalent;
    } else {
      ++t.wrong;
    }
  }
  return t;
}

}  // namespace

void run_detect_bench(const DetectBenchOptions& options) {
  const fs::path root(options.out);
  fs::create_directories(root);
  const std::vector<SweepModel> objects = sweep_models();
  const std::vector<Sensor> sensor_list = sensors();
  std::printf("%-16s %-15s %6s %7s %10s %6s %9s %10s %9s\n", "object", "sensor", "frames", "right", "equivalent",
              "wrong", "not found", "median ms", "p90 ms");
  std::vector<JsonObject> rows;
  const auto start = std::chrono::steady_clock::now();
  int cells_done = 0;
  const int cells = static_cast<int>(objects.size() * sensor_list.size());
  for (const SweepModel& object : objects) {
    const Mesh mesh = load_any_mesh(object.mesh_path);
    const ModelPointErrors surface(mesh);
    for (const Sensor& sensor : sensor_list) {
      TrackerConfig config;  // icgp's defaults
      config.regions = object.regions;
      if (sensor.grey)
        config.modalities.erase(std::remove(config.modalities.begin(), config.modalities.end(), CueKind::kDepth),
                                config.modalities.end());
      BodyDetector detector(config, mesh, object.name, configured_cameras(config));
      Tally tally;
      for (const double distance : kDistances)
        tally.add(detect_cell(sequence_folder(root, object, sensor, distance, options.frames), object, sensor, detector,
                              surface));
      std::printf("%-16s %-15s %6d %6.1f%% %9.1f%% %5.1f%% %8.1f%% %10.1f %9.1f\n", object.name.c_str(),
                  sensor.name.c_str(), tally.frames, 100.0 * tally.right / tally.frames,
                  100.0 * tally.equivalent / tally.frames, 100.0 * tally.wrong / tally.frames,
                  100.0 * tally.not_found / tally.frames, median(tally.ms), percentile(tally.ms, 0.9));
      std::fflush(stdout);
      rows.push_back(JsonObject()
                         .add("object", object.name)
                         .add("sensor", sensor.name)
                         .add("frames", tally.frames)
                         .add("right", tally.right)
                         .add("equivalent", tally.equivalent)
                         .add("wrong", tally.wrong)
                         .add("not_found", tally.not_found)
                         .add("median_ms", median(tally.ms))
                         .add("p90_ms", percentile(tally.ms, 0.9)));
      ++cells_done;
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::fprintf(stderr, "bench --detect: %d/%d rows, %.0f s, about %.0f s left\n", cells_done, cells, elapsed,
                   elapsed / cells_done * (cells - cells_done));
    }
  }
  std::printf("right: within %.0f mm and %.0f deg of the truth; equivalent: ADD-S within %.0f mm (a pose the model's "
              "symmetry cannot tell apart); frames at %.2f/%.2f/%.2f m, icgp's defaults, one thread\n",
              kRightMm, kRightDeg, kRightMm, kDistances[0], kDistances[1], kDistances[2]);
  if (!options.summary.empty()) {
    JsonObject().add("rows", rows).write(options.summary);
    std::cout << "wrote " << options.summary << "\n";
  }
}

}  // namespace icgp::app
