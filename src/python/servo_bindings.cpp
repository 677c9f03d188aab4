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
      .def_readonly("name", &servo::Scenario::name)
      .def_readonly("file", &servo::Scenario::file, "The YAML file it was read from.")
      .def_readwrite("seed", &servo::Scenario::seed, "Seed of the sensor noise and of the trials' random starts.")
      // Sent to other processes (Dask workers) as its file and seed, read again there: the
      // file and the models it names must be readable where the trial runs.
      .def(py::pickle([](const servo::Scenario& s) { return py::make_tuple(s.file, s.seed); },
                      [](const py::tuple& state) {
                        servo::Scenario s = servo::load_scenario(state[0].cast<std::string>(), models_dir());
                        s.seed = state[1].cast<unsigned>();
                        return s;
                      }));
  servo.def(
      "load_scenario",
      [](const std::filesystem::path& path) { return servo::load_scenario(path.string(), models_dir()); },
      py::arg("path"), "Reads a scenario file; models are named against icgp.models_dir().");
}

}  // namespace icgp::python
