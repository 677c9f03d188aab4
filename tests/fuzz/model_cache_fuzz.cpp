// SPDX-License-Identifier: GPL-2.0-or-later
// The viewpoint-model cache reader (icgp::load_viewpoint_model) on arbitrary bytes. A file
// it accepts is then read through the model's accessors, everything a tracker would touch,
// so that a size check that passes too much shows up as an out-of-bounds read.
#include "fuzz_support.h"
#include "icgp/model/model_cache.h"

namespace {

/// Sums every value the model exposes (the sum itself is irrelevant; reading is the test).
float touch_everything(const icgp::ViewpointModel& model) {
  float sum = 0.f;
  for (int v = 0; v < model.n_views(); ++v) {
    sum += model.view(v).direction.sum();
    const icgp::ModelPoint* points = model.points(v);
    for (int p = 0; p < model.n_points(); ++p) {
      sum += points[p].position.sum() + points[p].normal.sum();
      const float* offsets = model.depth_offsets(v, p);
      for (int k = 0; k < model.n_depth_offsets(); ++k) sum += offsets[k];
    }
    sum += static_cast<float>(model.view_point_count(v));
  }
  return sum;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path file = icgp::fuzz::scratch_dir() / "model.icgpmodel";
  icgp::fuzz::write_file(file, data, size);
  icgp::fuzz::refusing_like_a_loader([] {
    const icgp::ViewpointModel model = icgp::load_viewpoint_model(file.string());
    volatile float sink = touch_everything(model);
    (void)sink;
  });
  return 0;
}
