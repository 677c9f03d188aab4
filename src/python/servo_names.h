// SPDX-License-Identifier: GPL-2.0-or-later
// The names the scenario files and `icgp servo` give robots, laws and trackers, for the
// servo bindings' arguments and properties.
#pragma once

#include <pybind11/pybind11.h>

#include <optional>
#include <string>

#include "icgp/servo/scenario.h"

namespace icgp::python {

std::string robot_name(servo::RobotKind robot);
std::string law_name(servo::ControlLawKind law);
std::string tracker_name(servo::TrackerKind tracker);
/// The tracker of a `tracker` argument: None (nullopt: the scenario's), "icgp", "visp" or
/// "oracle"; ValueError naming the argument otherwise.
std::optional<servo::TrackerKind> tracker_kind(const pybind11::handle& tracker);

}  // namespace icgp::python
