// SPDX-License-Identifier: GPL-2.0-or-later
// icgp.Evaluation: the errors, AUCs and timing `icgp track` reports, for poses tracked in
// Python.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <utility>

#include "bindings.h"
#include "icgp/eval/metrics.h"
#include "icgp/eval/sequence.h"
#include "icgp/eval/sequence_run.h"
#include "icgp/eval/single_body_tracker.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "numpy_conversions.h"

namespace icgp::python {
namespace {

namespace py = pybind11;

/// The evaluation and the mesh it measures ADD on (TrackingEvaluation keeps its own samples).
struct Evaluation {
  explicit Evaluation(const std::filesystem::path& model, double scale)
      : evaluation(load_any_mesh(model.string(), scale)) {}
  explicit Evaluation(TrackingEvaluation done) : evaluation(std::move(done)) {}
  TrackingEvaluation evaluation;
};

/// icgp.evaluate_tracker: the sequence's object tracked by icgp's tracker from the first
/// frame's ground truth, as `icgp bench` runs it (eval/single_body_tracker.h).
Evaluation evaluate(const Sequence& sequence, const py::object& model, const py::object& config, int frames,
                    const py::dict& settings) {
  if (sequence.objects().size() != 1)
    throw std::invalid_argument("evaluate_tracker: the sequence in " + sequence.directory() + " has " +
                                std::to_string(sequence.objects().size()) + " objects; expected one");
  const SequenceObject& object = sequence.objects().front();
  const std::string model_path = model.is_none() ? object.mesh_path : py::str(model).cast<std::string>();
  if (model_path.empty())
    throw std::invalid_argument("evaluate_tracker: the sequence in " + sequence.directory() +
                                " names no model for '" + object.name + "': give model=");
  const FrameSource source = FrameSource::of(sequence, frames);
  if (source.count == 0) throw std::invalid_argument("evaluate_tracker: no frames to track");
  const Pose* truth = source.load(0).truth(object.name);
  if (!truth)
    throw std::invalid_argument("evaluate_tracker: the first frame of " + sequence.directory() +
                                " has no ground truth for '" + object.name + "' to start from");
  const Pose start = *truth;  // the run reads the frame again into the source's frame
  const Mesh mesh = load_any_mesh(model_path);
  const TrackerConfig tracker_config = icgp::python::tracker_config(config, settings);
  py::gil_scoped_release released;
  return Evaluation(evaluate_tracker(source, object.name, mesh, tracker_config, start));
}

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

  m.def(
      "evaluate_tracker",
      [](const Sequence& sequence, const py::object& model, const py::object& config, int frames,
         const py::kwargs& settings) { return evaluate(sequence, model, config, frames, settings); },
      py::arg("sequence"), py::arg("model") = py::none(), py::arg("config") = py::none(), py::kw_only(),
      py::arg("frames") = -1,
      R"doc(Tracks a sequence's object with icgp's tracker as `icgp bench` does, and returns its Evaluation.

The same loop as every icgp command and benchmark: start at the first frame's ground truth, track
every frame (the first included), time the tracking call alone. `model` defaults to the
sequence's; `config` is None, a YAML file or a dict, keyword settings read over it (as Tracker);
`frames` limits the run to the first frames (-1: all).)doc");
}

}  // namespace icgp::python
