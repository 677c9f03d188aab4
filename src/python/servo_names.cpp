// SPDX-License-Identifier: GPL-2.0-or-later
#include "servo_names.h"

#include "icgp/io/yaml_reader.h"

namespace icgp::python {

namespace py = pybind11;

std::optional<servo::TrackerKind> tracker_kind(const py::handle& tracker) {
  if (tracker.is_none()) return std::nullopt;
  if (py::isinstance<py::str>(tracker))
    if (const std::optional<servo::TrackerKind> kind = servo::kind_named(tracker.cast<std::string>(), servo::tracker_names()))
      return kind;
  std::vector<std::string> quoted;
  for (const std::string& name : servo::names_in(servo::tracker_names())) quoted.push_back("'" + name + "'");
  throw py::value_error("tracker: expected " + yaml::join(quoted) + " or None (the scenario's), got " +
                        py::repr(tracker).cast<std::string>());
}

}  // namespace icgp::python
