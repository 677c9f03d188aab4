// SPDX-License-Identifier: GPL-2.0-or-later
// Reading YAML files whose every error names the file and the key of the value at fault:
// "<file>: <key.path>: expected <what>, got <value>". The tracker configuration, the servo
// scenarios and the icgp sequence files are read through it.
#pragma once

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "icgp/base/pose.h"

namespace icgp::yaml {

/// A YAML file that cannot be used. The message names the file and the key.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// How a map lists its keys when it meets one it does not know.
enum class KeyListWording {
  kExpectedOneOf,  ///< "unknown key (expected one of a, b)"
  kValidKeysOf,    ///< "unknown key (valid keys of <section>: a, b)", "(valid keys: a, b)" at the top
};

/// How one kind of file words its errors: each reader keeps the wording its tests, docs
/// and users know. The defaults are the servo scenarios' wording.
struct Wording {
  const char* file = "file";  ///< what the file is called in "no such …", "cannot read the …"
  bool echo_value = true;     ///< "expected X, got Y" (true) or "expected X"
  KeyListWording key_list = KeyListWording::kExpectedOneOf;
};

/// Where a value sits: the file and the dotted key path ("camera.noise.depth_dropout",
/// "objects[2].name").
struct Location {
  std::string file;
  std::string key;  ///< empty: the whole document
  Wording wording;

  Location child(const std::string& name) const;
  Location element(std::size_t index) const;
  /// Throws Error("<file>: <key>: <message>"), "<file>: <message>" for the document.
  [[noreturn]] void fail(const std::string& message) const;
};

/// What a value must be: `expected` completes "expected …", `ok` checks the converted value.
template <typename T>
struct Rule {
  const char* expected;
  bool (*ok)(const T&);
};

template <typename T>
bool any(const T&) {
  return true;
}

// The rules the readers share.
extern const Rule<double> kNumber;       ///< "a number": finite
extern const Rule<double> kPositive;     ///< "a positive number": finite, > 0
extern const Rule<double> kNonNegative;  ///< "a non-negative number": finite, ≥ 0
extern const Rule<double> kFraction;     ///< "a number in [0, 1]"
extern const Rule<int> kPositiveInt;     ///< "a positive integer"
extern const Rule<int> kNonNegativeInt;  ///< "a non-negative integer"
extern const Rule<bool> kBool;           ///< "true or false"
extern const Rule<std::string> kString;  ///< "a string"; `key:` alone is the empty string
extern const Rule<std::string> kNonEmptyString;  ///< "a non-empty string"

/// The numbers a value may take, written as the messages write them: "[0, 8192]",
/// "(0, 1000]", "[0, 1)". Bounded on both sides, so that no value can ask for unbounded
/// memory or time; the readers share it to word every range the same way.
struct Interval {
  double min = 0.0;
  double max = 0.0;
  bool open_below = false;  ///< min itself is outside: (min, …
  bool open_above = false;  ///< max itself is outside: …, max)

  /// Finite and within the bounds (NaN and infinities are not).
  bool contains(double value) const;
  std::string text() const;
};

/// A number as a person writes it: 1000000 rather than 1e+06, 0.5, -360.
std::string plain_number(double value);
/// The shortest text that reads back as the same double (0.05, not 0.050000000000000003):
/// what files icgp writes hold, so that reading them gives every bit back.
std::string exact_number(double value);

/// A value as the file wrote it, for messages: numbers as they are, other text quoted
/// ('fast'), lists in brackets, "a map", "nothing" for `key:` alone.
std::string describe(const YAML::Node& node);
/// "a, b, c".
std::string join(const std::vector<std::string>& items);

/// `node` converted by yaml-cpp (a number, an integer, true/false, a string or a list of
/// them); nullopt when it is none. `key:` alone is the empty string, not yaml-cpp's "null".
template <typename T>
std::optional<T> convert(const YAML::Node& node) {
  if constexpr (std::is_same_v<T, std::string>)
    if (node.IsNull()) return std::string();
  try {
    return node.as<T>();
  } catch (const YAML::Exception&) {
    return std::nullopt;
  }
}

/// A value of a file and where it is.
struct Value {
  YAML::Node node;
  Location at;

  /// Throws "expected <what>, got <the value>" (", got …" as the file's wording says).
  [[noreturn]] void expected(const std::string& what) const;

  /// The value converted to T and checked by `rule`; expected(rule.expected) otherwise.
  template <typename T>
  T as(const Rule<T>& rule) const {
    std::optional<T> value = convert<T>(node);
    if (!value || !rule.ok(*value)) expected(rule.expected);
    return std::move(*value);
  }

  /// A number within `range`; "expected a number in <range>, got <value>" otherwise.
  double number_in(const Interval& range) const;
  /// An integer within [min, max]; "expected an integer in [min, max], got <value>"
  /// otherwise (1.5 and 10^20 included, which do not convert).
  long long integer_in(long long min, long long max) const;

  /// The option the value names; "expected one of <names>" otherwise.
  template <typename E>
  E choice(const std::vector<std::pair<std::string, E>>& options) const {
    std::vector<std::string> names;
    for (const auto& [name, option] : options) {
      if (node.IsScalar() && node.Scalar() == name) return option;
      names.push_back(name);
    }
    expected("one of " + join(names));
  }

  /// The elements of a list, each with its location ("regions[2]"); expected(what) when
  /// the value is not a list.
  std::vector<Value> elements(const std::string& what) const;
};

/// The options of Value::choice for enumerators named by to_string(value), in order.
template <typename E, std::size_t N>
std::vector<std::pair<std::string, E>> named(const std::array<E, N>& values) {
  std::vector<std::pair<std::string, E>> options;
  for (const E value : values) options.emplace_back(to_string(value), value);
  return options;
}

/// Hands each entry of the map `value` to `read` in the file's order, each key checked just
/// before: one of `keys`, and not given twice. `key:` alone is an empty map. (Map checks
/// every key first; this reads a file's values and keys in the order they come.)
void for_each_entry(const Value& value, const std::vector<std::string>& keys,
                    const std::function<void(const std::string& key, const Value& value)>& read);
/// for_each_entry of a map of any keys.
void for_each_entry(const Value& value, const std::function<void(const std::string& key, const Value& value)>& read);

/// The entries of a map in the file's order, checked on construction: no key twice and,
/// when the map is given its keys, no other key. `key:` alone is an empty map.
class Map {
 public:
  /// A map of any keys (a format other programs may extend).
  explicit Map(const Value& value);
  /// A map of `keys` only.
  Map(const Value& value, std::vector<std::string> keys);

  /// The value of `key`, if the file gives one.
  std::optional<Value> get(const std::string& key) const;
  /// The value of `key`; "<key>: required" when the file does not give one.
  Value required(const std::string& key) const;

 private:
  Location at_;
  std::vector<std::pair<std::string, Value>> entries_;
};

/// A list of exactly N numbers, each within `range`; "expected a list of N numbers in
/// <range>, got …" otherwise.
template <int N>
Eigen::Matrix<double, N, 1> numbers(const Value& v, const Interval& range) {
  const std::string what = "a list of " + std::to_string(N) + " numbers in " + range.text();
  if (!v.node.IsSequence() || v.node.size() != static_cast<std::size_t>(N)) v.expected(what);
  Eigen::Matrix<double, N, 1> x;
  for (int i = 0; i < N; ++i) {
    const std::optional<double> element = convert<double>(v.node[i]);
    if (!element || !range.contains(*element)) v.expected(what);
    x[i] = *element;
  }
  return x;
}

/// Translations of poses in files, metres per axis.
inline constexpr Interval kPoseCoordinate{-100.0, 100.0};
/// θu components of poses in files, and angles in degrees.
inline constexpr Interval kAngleDeg{-360.0, 360.0};

/// A pose {t: [x, y, z] metres, r_deg: [ux, uy, uz] θu degrees}, a_T_b.
Pose pose(const Value& v);

/// The document of the YAML file `path`. Throws Error "<path>: no such <file>",
/// "<path>: cannot read the <file>" or "<path>: line L, column C: YAML syntax error: …",
/// <file> as `wording` calls it.
Value load_file(const std::string& path, const Wording& wording = {});

}  // namespace icgp::yaml
