// SPDX-License-Identifier: GPL-2.0-or-later
#include "servo_names.h"

namespace icgp::python {

namespace py = pybind11;
using servo::ControlLawKind;
using servo::RobotKind;
using servo::TrackerKind;

std::string robot_name(RobotKind robot) {
  switch (robot) {
    case RobotKind::kFreeFlyingCamera: return "free_flying";
    case RobotKind::kViper850EyeInHand: return "viper850_eye_in_hand";
    case RobotKind::kViper850EyeToHand: return "viper850_eye_to_hand";
    case RobotKind::kViper850Grasp: return "viper850_grasp";
  }
  return "?";
}

std::string law_name(ControlLawKind law) { return law == ControlLawKind::kPbvs ? "pbvs" : "ibvs"; }

std::string tracker_name(TrackerKind tracker) {
  switch (tracker) {
    case TrackerKind::kIcgp: return "icgp";
    case TrackerKind::kVisp: return "visp";
    case TrackerKind::kOracle: return "oracle";
  }
  return "?";
}

std::optional<TrackerKind> tracker_kind(const py::handle& tracker) {
  if (tracker.is_none()) return std::nullopt;
  if (py::isinstance<py::str>(tracker)) {
    const std::string name = tracker.cast<std::string>();
    for (TrackerKind kind : {TrackerKind::kIcgp, TrackerKind::kVisp, TrackerKind::kOracle})
      if (tracker_name(kind) == name) return kind;
  }
  throw py::value_error("tracker: expected 'icgp', 'visp', 'oracle' or None (the scenario's), got " + py::repr(tracker).cast<std::string>());
}

}  // namespace icgp::python
