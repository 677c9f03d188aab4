// SPDX-License-Identifier: GPL-2.0-or-later
// The tracker argument of the servo bindings, named as scenario files name trackers
// (servo::tracker_names).
#pragma once

#include <pybind11/pybind11.h>

#include <optional>

#include "icgp/servo/scenario.h"

namespace icgp::python {

/// The tracker of a `tracker` argument: None (nullopt: the scenario's), "icgp", "visp",
/// "oracle" or "image_oracle"; ValueError naming the argument otherwise.
std::optional<servo::TrackerKind> tracker_kind(const pybind11::handle& tracker);

}  // namespace icgp::python
