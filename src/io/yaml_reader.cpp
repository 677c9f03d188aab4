// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/io/yaml_reader.h"

#include <charconv>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

namespace icgp::yaml {

namespace fs = std::filesystem;

constexpr Rule<double> kNumber{"a number", [](const double& v) { return std::isfinite(v); }};
constexpr Rule<double> kPositive{"a positive number", [](const double& v) { return std::isfinite(v) && v > 0.0; }};
constexpr Rule<double> kNonNegative{"a non-negative number",
                                    [](const double& v) { return std::isfinite(v) && v >= 0.0; }};
constexpr Rule<double> kFraction{"a number in [0, 1]", [](const double& v) { return v >= 0.0 && v <= 1.0; }};
constexpr Rule<int> kPositiveInt{"a positive integer", [](const int& v) { return v > 0; }};
constexpr Rule<int> kNonNegativeInt{"a non-negative integer", [](const int& v) { return v >= 0; }};
constexpr Rule<bool> kBool{"true or false", any<bool>};
constexpr Rule<std::string> kString{"a string", any<std::string>};
constexpr Rule<std::string> kNonEmptyString{"a non-empty string", [](const std::string& v) { return !v.empty(); }};

bool Interval::contains(double value) const {
  if (!std::isfinite(value)) return false;
  const bool above_min = open_below ? value > min : value >= min;
  const bool below_max = open_above ? value < max : value <= max;
  return above_min && below_max;
}

std::string Interval::text() const {
  return (open_below ? "(" : "[") + plain_number(min) + ", " + plain_number(max) + (open_above ? ")" : "]");
}

std::string plain_number(double value) {
  char text[32];
  // Whole numbers up to 2^53 are exact in a double: print every digit, no exponent.
  if (std::isfinite(value) && std::abs(value) <= 9007199254740992.0 && value == std::trunc(value))
    std::snprintf(text, sizeof text, "%.0f", value);
  else
    std::snprintf(text, sizeof text, "%.15g", value);
  return text;
}

std::string exact_number(double value) {
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof(text), value).ptr);
}

std::string describe(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  if (node.IsScalar()) {
    double number = 0.0;
    const bool numeric = YAML::convert<double>::decode(node, number);
    return numeric ? node.Scalar() : "'" + node.Scalar() + "'";
  }
  if (node.IsSequence()) {
    std::string text;
    for (const auto& item : node) text += (text.empty() ? "" : ", ") + describe(item);
    return "[" + text + "]";
  }
  return "a map";
}

std::string join(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
  return text;
}

Location Location::child(const std::string& name) const {
  return {file, key.empty() ? name : key + "." + name, wording};
}

Location Location::element(std::size_t index) const { return {file, key + "[" + std::to_string(index) + "]", wording}; }

void Location::fail(const std::string& message) const {
  throw Error(file + ": " + (key.empty() ? "" : key + ": ") + message);
}

void Value::expected(const std::string& what) const {
  at.fail("expected " + what + (at.wording.echo_value ? ", got " + describe(node) : ""));
}

std::vector<Value> Value::elements(const std::string& what) const {
  if (!node.IsSequence()) expected(what);
  std::vector<Value> values;
  for (std::size_t i = 0; i < node.size(); ++i) values.push_back({node[i], at.element(i)});
  return values;
}

double Value::number_in(const Interval& range) const {
  const std::optional<double> value = convert<double>(node);
  if (!value || !range.contains(*value)) expected("a number in " + range.text());
  return *value;
}

long long Value::integer_in(long long min, long long max) const {
  const std::optional<long long> value = convert<long long>(node);
  if (!value || *value < min || *value > max)
    expected("an integer in " + Interval{static_cast<double>(min), static_cast<double>(max)}.text());
  return *value;
}

namespace {

/// for_each_entry, with any key when `keys` is null.
void visit_entries(const Value& value, const std::vector<std::string>* keys,
                   const std::function<void(const std::string&, const Value&)>& read) {
  if (value.node.IsNull()) return;
  if (!value.node.IsMap()) value.expected(keys ? "a map with the keys " + join(*keys) : std::string("a map"));
  const Location& map = value.at;
  std::set<std::string> seen;
  for (const auto& entry : value.node) {
    const std::string name = entry.first.IsScalar() ? entry.first.Scalar() : describe(entry.first);
    const Location at = map.child(name);
    if (keys && std::find(keys->begin(), keys->end(), name) == keys->end()) {
      if (map.wording.key_list == KeyListWording::kExpectedOneOf)
        at.fail("unknown key (expected one of " + join(*keys) + ")");
      at.fail("unknown key (valid keys" + (map.key.empty() ? "" : " of " + map.key) + ": " + join(*keys) + ")");
    }
    if (!seen.insert(name).second) at.fail("duplicate key");
    read(name, {entry.second, at});
  }
}

}  // namespace

void for_each_entry(const Value& value, const std::vector<std::string>& keys,
                    const std::function<void(const std::string& key, const Value& value)>& read) {
  visit_entries(value, &keys, read);
}

void for_each_entry(const Value& value, const std::function<void(const std::string& key, const Value& value)>& read) {
  visit_entries(value, nullptr, read);
}

Map::Map(const Value& value) : at_(value.at) {
  visit_entries(value, nullptr, [this](const std::string& key, const Value& v) { entries_.emplace_back(key, v); });
}

Map::Map(const Value& value, std::vector<std::string> keys) : at_(value.at) {
  visit_entries(value, &keys, [this](const std::string& key, const Value& v) { entries_.emplace_back(key, v); });
}

std::optional<Value> Map::get(const std::string& key) const {
  for (const auto& [name, value] : entries_)
    if (name == key) return value;
  return std::nullopt;
}

Value Map::required(const std::string& key) const {
  if (std::optional<Value> value = get(key)) return *value;
  at_.child(key).fail("required");
}

Value load_file(const std::string& path, const Wording& wording) {
  const Location document{path, "", wording};
  std::error_code error;
  std::ifstream in(path);
  if (!fs::is_regular_file(path, error) || !in)
    document.fail(fs::exists(path, error) ? std::string("cannot read the ") + wording.file
                                          : std::string("no such ") + wording.file);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  try {
    return {YAML::Load(text), document};
  } catch (const YAML::ParserException& e) {
    document.fail("line " + std::to_string(e.mark.line + 1) + ", column " + std::to_string(e.mark.column + 1) +
                  ": YAML syntax error: " + e.msg);
  }
}

Pose pose(const Value& v) {
  const Map s(v, {"t", "r_deg"});
  const Eigen::Vector3d t = numbers<3>(s.required("t"), kPoseCoordinate);
  const Eigen::Vector3d r = numbers<3>(s.required("r_deg"), kAngleDeg) * (kPi / 180.0);
  return Pose::from_rotation_vector(r, t);
}

}  // namespace icgp::yaml
