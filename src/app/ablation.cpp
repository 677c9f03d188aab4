// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp bench --ablation`: the analogue of the ICG+ paper's Tables III and IV on data with
// ground truth — ICG+ with each descriptor, and ICG+ without multi-region, texture, both,
// depth or region — on teabox-blender and on sequences rendered here of objects whose
// geometry is ambiguous but whose appearance is not.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "icgp/tracker/cue_registry.h"
#include "icgp/eval/json_object.h"
#include "icgp/eval/sequence.h"
#include "icgp/eval/single_body_tracker.h"
#include "icgp/eval/sequence_writer.h"
#include "icgp/io/mesh_loader.h"
#include "icgp/model/model_cache.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/visp_camera_xml.h"
#include "single_thread_scope.h"
#include "text_table.h"

namespace icgp::app {
namespace {

struct AblationSequence {
  std::string name;
  std::string directory;
  std::string mesh_path;
  TrackerConfig base;  ///< with `regions` set when the object has colour regions
};

struct AblationConfig {
  std::string name;
  std::vector<std::string> modalities;
  Descriptor descriptor;
  bool multi_region;
};

/// The paper's rows (Tables III and IV) on icgp's defaults: ICG+ with each descriptor, then
/// without each part. "ob" is oriented_brief, the defaults' descriptor.
std::vector<AblationConfig> ablation_configs() {
  const std::vector<std::string> all = {"region", "depth", "texture"};
  const Descriptor ob = Descriptor::kOrientedBrief;
  return {{"icg+ob (defaults)", all, ob, true},
          {"icg+orb", all, Descriptor::kOrb, true},
          {"icg+brisk", all, Descriptor::kBrisk, true},
          {"icg+sift", all, Descriptor::kSift, true},
          {"icg+freak", all, Descriptor::kFreak, true},
          {"icg+daisy", all, Descriptor::kDaisy, true},
          {"icg+ob-no-multiregion", all, ob, false},
          {"icg+ob-no-texture", {"region", "depth"}, ob, true},
          {"icg", {"region", "depth"}, ob, false},
          {"icg+ob-no-depth", {"region", "texture"}, ob, true},
          {"icg+ob-no-region", {"depth", "texture"}, ob, true}};
}

/// Renders (once; later runs reuse the files) a fast, noisy RGB-D sequence of a model,
/// optionally spinning about its own y axis (the models' up and symmetry axis).
std::string rendered_sequence(const std::string& name, const std::string& mesh_path, double spin = 0.0) {
  // The version in the folder name changes whenever these settings do.
  const std::filesystem::path dir =
      std::filesystem::path(default_model_cache_dir()) / "ablation-sequences" / (name + "-v1");
  if (std::filesystem::exists(dir / "sequence.yaml")) return dir.string();
  SequenceWriterOptions o;
  o.frame_count = 150;
  o.seed = 21;
  o.color_intrinsics = o.depth_intrinsics = Intrinsics::centred(640, 480, 600.0);
  o.depth_T_color = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.025, 0.0, 0.0));
  o.motion.speed = 4.0;
  o.noise.color_sigma = 4.0;
  o.noise.depth_sigma_at_1m = 0.005;
  o.noise.depth_dropout = 0.2;
  SequenceWriter writer(o);
  writer.add_object(name, load_mesh(mesh_path), Pose(), mesh_path, Eigen::Vector3d(0.0, spin, 0.0));
  writer.write(dir.string());
  return dir.string();
}

std::vector<AblationSequence> ablation_sequences() {
  const std::string models = models_dir();
  const std::string teabox = std::string(ICGP_SOURCE_TEST_DATA_DIR) + "/teabox-blender";
  TrackerConfig two_region, labelled_can;
  two_region.regions = {models + "/two_region/region_body.obj", models + "/two_region/region_lid.obj"};
  labelled_can.regions = {models + "/labelled_can/region_label.obj", models + "/labelled_can/region_caps.obj"};
  return {{"teabox-blender", teabox, teabox + "/teabox.cao", benchmark_tracker_config("")},
          {"labelled_cylinder",
           rendered_sequence("labelled_cylinder", models + "/labelled_cylinder/labelled_cylinder.obj"),
           models + "/labelled_cylinder/labelled_cylinder.obj", TrackerConfig{}},
          {"labelled_cylinder_spin",
           rendered_sequence("labelled_cylinder_spin", models + "/labelled_cylinder/labelled_cylinder.obj", 3.0),
           models + "/labelled_cylinder/labelled_cylinder.obj", TrackerConfig{}},
          {"labelled_can", rendered_sequence("labelled_can", models + "/labelled_can/object.obj"),
           models + "/labelled_can/object.obj", labelled_can},
          {"labelled_can_spin", rendered_sequence("labelled_can_spin", models + "/labelled_can/object.obj", 3.0),
           models + "/labelled_can/object.obj", labelled_can},
          {"two_region", rendered_sequence("two_region", models + "/two_region/object.obj"),
           models + "/two_region/object.obj", two_region}};
}

}  // namespace

void run_ablation(const std::string& summary_path, int frame_limit) {
  const SingleThreadScope single_thread;
  std::vector<JsonObject> json_rows;
  for (const AblationSequence& s : ablation_sequences()) {
    const Sequence sequence = Sequence::open(s.directory, visp_sequence_options());
    const Mesh mesh = load_any_mesh(s.mesh_path);
    const std::string body = sequence.objects().front().name;
    const int n = frame_limit > 0 ? std::min(frame_limit, sequence.size()) : sequence.size();
    std::vector<Frame> frames;
    for (int i = 0; i < n; ++i) frames.push_back(sequence.load(i));

    TextTable table({{"configuration", 24, true}, {"ADD AUC", 8}, {"ADD-S AUC", 9}, {"mean mm", 9}, {"mean deg", 9},
                     {"median ms", 10}, {"Hz", 8}});
    for (const AblationConfig& c : ablation_configs()) {
      TrackerConfig config = s.base;
      config.modalities = parse_cue_list(c.modalities);
      config.texture.descriptor = c.descriptor;
      if (!c.multi_region) config.regions.clear();
      std::cerr << s.name << ": " << c.name << " ...\n";
      const TrackingSummary r =
          evaluate_tracker(FrameSource::of(frames), body, mesh, config, *frames.front().truth(body)).summary();
      table.text(c.name).number(r.add_auc, 2).number(r.adds_auc, 2).number(r.mean_t_mm, 2).number(r.mean_r_deg, 2);
      table.number(r.median_ms, 2).number(r.hz, 0).end_row();
      json_rows.push_back(JsonObject().add("sequence", s.name).add("config", c.name).add_fields(r.to_json()));
    }
    std::printf("\n%s (%d frames)\n", s.name.c_str(), n);
    table.print();
    std::fflush(stdout);
  }
  std::printf("\nEvery row is icgp's defaults with the named change; ob = oriented_brief, the defaults' descriptor.\n"
              "multi-region applies to labelled_can, labelled_can_spin and two_region (the others have one colour region).\n");
  if (!summary_path.empty()) {
    JsonObject().add("rows", json_rows).write(summary_path);
    std::cout << "wrote " << summary_path << "\n";
  }
}

}  // namespace icgp::app
