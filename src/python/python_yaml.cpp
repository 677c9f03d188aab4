// SPDX-License-Identifier: GPL-2.0-or-later
#include "python_yaml.h"

#include <pybind11/numpy.h>

#include "icgp/io/yaml_reader.h"

namespace icgp::python {

namespace py = pybind11;

YAML::Node yaml_node(const py::handle& value, const std::string& key) {
  const auto child_key = [&](const std::string& name) { return key.empty() ? name : key + "." + name; };
  if (py::isinstance<py::dict>(value)) {
    YAML::Node map(YAML::NodeType::Map);
    for (const auto& [name, item] : py::reinterpret_borrow<py::dict>(value)) {
      if (!py::isinstance<py::str>(name))
        throw py::type_error((key.empty() ? std::string("keyword arguments") : key) + ": expected string keys, got " +
                             py::repr(name).cast<std::string>());
      const std::string text = name.cast<std::string>();
      map[text] = yaml_node(item, child_key(text));
    }
    return map;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value) ||
      (py::isinstance<py::array>(value) && py::reinterpret_borrow<py::array>(value).ndim() == 1)) {
    YAML::Node sequence(YAML::NodeType::Sequence);
    std::size_t i = 0;
    for (const py::handle item : value) sequence.push_back(yaml_node(item, key + "[" + std::to_string(i++) + "]"));
    return sequence;
  }
  if (value.is_none()) return YAML::Node(YAML::NodeType::Null);
  // bool before int: Python's bool is an int.
  if (py::isinstance<py::bool_>(value)) return YAML::Node(value.cast<bool>() ? "true" : "false");
  if (py::isinstance<py::int_>(value)) return YAML::Node(py::str(value).cast<std::string>());
  if (py::isinstance<py::str>(value)) return YAML::Node(value.cast<std::string>());
  // Python floats and whatever converts to one (NumPy scalars).
  if (py::hasattr(value, "__float__")) return YAML::Node(yaml::exact_number(value.cast<double>()));
  throw py::type_error((key.empty() ? std::string("value") : key) +
                       ": expected a dict, list, number, bool or string, got " +
                       py::str(value.get_type().attr("__name__")).cast<std::string>());
}

}  // namespace icgp::python
