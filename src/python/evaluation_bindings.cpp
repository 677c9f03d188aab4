// SPDX-License-Identifier: GPL-2.0-or-later
// icgp.Evaluation: the errors, AUCs and timing `icgp track` reports, for poses tracked in
// Python.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <optional>

#include "bindings.h"
#include "icgp/eval/metrics.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "numpy_conversions.h"

namespace icgp::python {
namespace {

namespace py = pybind11;

/// The evaluation and the mesh it measures ADD on (TrackingEvaluation keeps its own samples).
struct Evaluation {
  explicit Evaluation(const std::filesystem::path& model, double scale)
      : evaluation(load_any_mesh(model.string(), scale)) {}
  TrackingEvaluation evaluation;
};

py::dict summary_dict(const TrackingSummary& s) {
  py::dict d;
  d["frames"] = s.frames;
  d["tracked"] = s.tracked;
  d["frames_with_truth"] = s.frames_with_truth;
  d["mean_t_mm"] = s.mean_t_mm;
  d["max_t_mm"] = s.max_t_mm;
  d["mean_r_deg"] = s.mean_r_deg;
  d["max_r_deg"] = s.max_r_deg;
  d["mean_add_mm"] = s.mean_add_mm;
  d["mean_adds_mm"] = s.mean_adds_mm;
  d["add_auc"] = s.add_auc;
  d["adds_auc"] = s.adds_auc;
  d["diameter_mm"] = s.diameter_mm;
  d["median_ms"] = s.median_ms;
  d["mean_ms"] = s.mean_ms;
  d["hz"] = s.hz;
  return d;
}

}  // namespace

void register_evaluation(py::module_& m) {
  py::class_<Evaluation>(m, "Evaluation", R"doc(The errors `icgp track` reports, for poses tracked in Python.

Evaluation(model, scale=1.0)

add(frame, pose, truth, tracked, ms, quality) records a frame (truth None when unknown) and
returns its errors; summary() gives the sequence's: translation and rotation mean/max
(mm, deg), ADD and ADD-S AUC (percent, 10 cm threshold, `model` sampled for ADD), and the
median and mean ms, as `icgp track --summary` writes them.
)doc")
      .def(py::init<const std::filesystem::path&, double>(), py::arg("model"), py::arg("scale") = 1.0)
      .def(
          "add",
          [](Evaluation& e, int frame, const py::handle& pose, const py::object& truth, bool tracked, double ms,
             double quality) {
            const std::optional<Pose> true_pose =
                truth.is_none() ? std::nullopt : std::optional<Pose>(icgp::python::pose(truth, "truth"));
            const FrameEvaluation& f =
                e.evaluation.add(frame, icgp::python::pose(pose, "pose"), true_pose, tracked, ms, quality);
            py::dict d;
            d["t_mm"] = f.t_mm;
            d["r_deg"] = f.r_deg;
            d["add_mm"] = 1000.0 * f.add_m;
            d["adds_mm"] = 1000.0 * f.adds_m;
            return d;
          },
          py::arg("frame"), py::arg("pose"), py::arg("truth"), py::arg("tracked") = true, py::arg("ms") = 0.0,
          py::arg("quality") = std::numeric_limits<double>::quiet_NaN(),
          "Records a frame; returns its errors (t_mm, r_deg, add_mm, adds_mm; NaN without truth).")
      .def("summary", [](const Evaluation& e) { return summary_dict(e.evaluation.summary()); },
           "The summary `icgp track --summary` writes, as a dict.")
      .def("write_csv", [](const Evaluation& e, const std::filesystem::path& path) { e.evaluation.write_csv(path.string()); },
           py::arg("path"), "Writes the per-frame CSV `icgp track --csv` writes.");
}

}  // namespace icgp::python
