// SPDX-License-Identifier: GPL-2.0-or-later
// Batch trials of the servo simulator (icgp._icgp.servo): used by icgp.batch.
#include <pybind11/pybind11.h>

#include "bindings.h"

namespace icgp::python {

namespace py = pybind11;

void register_trials(py::module_&) {}

}  // namespace icgp::python
