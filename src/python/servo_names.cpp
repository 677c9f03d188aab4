// SPDX-License-Identifier: GPL-2.0-or-later
#include "servo_names.h"

namespace icgp::python {

namespace py = pybind11;

std::optional<servo::TrackerKind> tracker_kind(const py::handle& tracker) {
  if (tracker.is_none()) return std::nullopt;
  if (py::isinstance<py::str>(tracker)) {
    const std::string name = tracker.cast<std::string>();
    for (const auto& [known, kind] : servo::tracker_names())
      if (known == name) return kind;
  }
  std::string names;
  for (const auto& [known, kind] : servo::tracker_names()) names += "'" + known + "', ";
  throw py::value_error("tracker: expected " + names.substr(0, names.size() - 2) + " or None (the scenario's), got " +
                        py::repr(tracker).cast<std::string>());
}

}  // namespace icgp::python
