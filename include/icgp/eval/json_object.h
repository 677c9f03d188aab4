// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace icgp {

/// A JSON object built field by field, written with its keys in insertion order so that
/// summaries read the same way every time. Values are numbers, strings, booleans, objects or
/// arrays of objects: all that evaluation summaries need, without a JSON library dependency.
class JsonObject {
 public:
  /// A non-finite number (an undefined mean, say) is written as null.
  JsonObject& add(const std::string& key, double value);
  JsonObject& add(const std::string& key, int value);
  JsonObject& add(const std::string& key, bool value);
  JsonObject& add(const std::string& key, const std::string& value);
  JsonObject& add(const std::string& key, const char* value) { return add(key, std::string(value)); }
  JsonObject& add(const std::string& key, std::vector<JsonObject> array);
  JsonObject& add(const std::string& key, JsonObject object);
  /// Appends every field of `other`, in its order.
  JsonObject& add_fields(const JsonObject& other);

  /// The object as indented JSON text (no trailing newline).
  std::string dump() const;
  /// dump() into a file, with a trailing newline; throws std::runtime_error naming the file
  /// when it cannot be written. The parent folder is created.
  void write(const std::string& path) const;

  /// An array of objects as indented JSON text, and into a file as write() does.
  static std::string dump_array(const std::vector<JsonObject>& array);
  static void write_array(const std::vector<JsonObject>& array, const std::string& path);

 private:
  using Value =
      std::variant<double, int, bool, std::string, std::vector<JsonObject>, std::shared_ptr<const JsonObject>>;
  void dump(std::string& out, int level) const;
  static void dump_array(std::string& out, const std::vector<JsonObject>& array, int level);

  std::vector<std::pair<std::string, Value>> fields_;
};

}  // namespace icgp
