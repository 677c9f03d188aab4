// SPDX-License-Identifier: GPL-2.0-or-later
// icgp._icgp.servo: scenarios of the servo simulator (wrapped by the icgp.servo module).
#include <pybind11/pybind11.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>

#include "bindings.h"
#include "icgp/servo/scenario.h"

namespace icgp::python {

namespace py = pybind11;

void register_servo(py::module_& m) {
  py::module_ servo = m.def_submodule("servo", "The servo simulator's C++ side (use icgp.servo)");
  py::class_<servo::Scenario>(servo, "Scenario", "A servo scenario read from its YAML file (icgp.servo.load_scenario).")
      .def_readonly("name", &servo::Scenario::name);
  servo.def(
      "load_scenario",
      [](const std::filesystem::path& path) { return servo::load_scenario(path.string(), models_dir()); },
      py::arg("path"), "Reads a scenario file; models are named against icgp.models_dir().");
}

}  // namespace icgp::python
