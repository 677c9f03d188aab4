// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/eval/make_sequence.h"

#include <filesystem>

#include "icgp/eval/sequence_scene.h"
#include "icgp/render/egl_context.h"

namespace icgp {

std::string make_sequence(MakeSequenceRequest r, const std::string& models_dir, const ModelReader& read_model) {
  // Whole frames render faster on llvmpipe's raster threads (when nothing rendered before).
  choose_software_raster_threads(SoftwareRasterThreads::kPerCore);
  SequenceWriterOptions& w = r.writer;
  w.color_intrinsics = w.depth_intrinsics = Intrinsics::centred(r.width, r.height, r.focal);
  w.depth_T_color = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0 - r.baseline, 0.0, 0.0));
  if (r.stereo_baseline != 0.0) {
    // A rectified pair: the same camera, moved along the colour camera's x axis.
    w.stereo = true;
    w.stereo_intrinsics = w.color_intrinsics;
    w.stereo_T_color = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0 - r.stereo_baseline, 0.0, 0.0));
  }
  const std::string stereo = w.stereo ? " (stereo)" : "";
  SequenceWriter writer(w);
  if (!r.scene.empty()) {
    const std::vector<SceneBody> bodies = read_sequence_scene(r.scene, models_dir);
    add_scene_bodies(writer, bodies);
    writer.write(r.out);
    return std::to_string(w.frame_count) + " frames of " + std::to_string(bodies.size()) + " bodies of " + r.scene + stereo;
  }
  const std::string stem = std::filesystem::path(r.model).stem().string();
  writer.add_object(stem, read_model(r.model, r.scale), Pose(), std::filesystem::absolute(r.model).string(),
                    Eigen::Vector3d(0.0, r.spin, 0.0));
  writer.write(r.out);
  return std::to_string(w.frame_count) + " frames of '" + stem + "'" + stereo;
}

}  // namespace icgp
