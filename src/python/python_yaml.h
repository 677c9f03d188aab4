// SPDX-License-Identifier: GPL-2.0-or-later
// Keyword arguments as the YAML the configuration readers take, so that a configuration
// given in Python is checked by the same rules, with the same messages, as a file.
#pragma once

#include <pybind11/pybind11.h>
#include <yaml-cpp/yaml.h>

namespace icgp::python {

/// dicts become maps, lists, tuples and 1-D arrays sequences, and bool, int, float and str
/// scalars (floats written so that they read back exactly). Throws TypeError naming the key
/// of a value of any other type.
YAML::Node yaml_node(const pybind11::handle& value, const std::string& key = "");

}  // namespace icgp::python
