// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/eval/json_object.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace icgp {

namespace {

void append_string(std::string& out, const std::string& text) {
  out += '"';
  for (const char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char escaped[8];
          std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
          out += escaped;
        } else {
          out += c;
        }
    }
  }
  out += '"';
}

void append_number(std::string& out, double value) {
  if (!std::isfinite(value)) {
    out += "null";
    return;
  }
  // 10 significant digits: exact enough for millimetres and milliseconds, short to read.
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", value);
  out += text;
}

std::string indentation(int level) { return std::string(2 * static_cast<std::size_t>(level), ' '); }

}  // namespace

JsonObject& JsonObject::add(const std::string& key, double value) {
  fields_.emplace_back(key, value);
  return *this;
}
JsonObject& JsonObject::add(const std::string& key, int value) {
  fields_.emplace_back(key, value);
  return *this;
}
JsonObject& JsonObject::add(const std::string& key, bool value) {
  fields_.emplace_back(key, value);
  return *this;
}
JsonObject& JsonObject::add(const std::string& key, const std::string& value) {
  fields_.emplace_back(key, value);
  return *this;
}
JsonObject& JsonObject::add(const std::string& key, std::vector<JsonObject> array) {
  fields_.emplace_back(key, std::move(array));
  return *this;
}

JsonObject& JsonObject::add(const std::string& key, JsonObject object) {
  fields_.emplace_back(key, std::make_shared<const JsonObject>(std::move(object)));
  return *this;
}

JsonObject& JsonObject::add_fields(const JsonObject& other) {
  fields_.insert(fields_.end(), other.fields_.begin(), other.fields_.end());
  return *this;
}

std::string JsonObject::dump() const {
  std::string out;
  dump(out, 0);
  return out;
}

void JsonObject::dump(std::string& out, int level) const {
  out += "{";
  for (std::size_t i = 0; i < fields_.size(); ++i) {
    out += i == 0 ? "\n" : ",\n";
    out += indentation(level + 1);
    append_string(out, fields_[i].first);
    out += ": ";
    const Value& value = fields_[i].second;
    if (const auto* number = std::get_if<double>(&value)) {
      append_number(out, *number);
    } else if (const auto* integer = std::get_if<int>(&value)) {
      out += std::to_string(*integer);
    } else if (const auto* flag = std::get_if<bool>(&value)) {
      out += *flag ? "true" : "false";
    } else if (const auto* text = std::get_if<std::string>(&value)) {
      append_string(out, *text);
    } else if (const auto* array = std::get_if<std::vector<JsonObject>>(&value)) {
      dump_array(out, *array, level + 1);
    } else {
      std::get<std::shared_ptr<const JsonObject>>(value)->dump(out, level + 1);
    }
  }
  if (!fields_.empty()) out += "\n" + indentation(level);
  out += "}";
}

void JsonObject::dump_array(std::string& out, const std::vector<JsonObject>& array, int level) {
  out += "[";
  for (std::size_t k = 0; k < array.size(); ++k) {
    out += k == 0 ? "\n" : ",\n";
    out += indentation(level + 1);
    array[k].dump(out, level + 1);
  }
  if (!array.empty()) out += "\n" + indentation(level);
  out += "]";
}

std::string JsonObject::dump_array(const std::vector<JsonObject>& array) {
  std::string out;
  dump_array(out, array, 0);
  return out;
}

namespace {

void write_json_text(const std::string& path, const std::string& text) {
  const std::filesystem::path file(path);
  std::error_code error;
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), error);
  std::ofstream out(file);
  out << text << "\n";
  if (!out) throw std::runtime_error("cannot write JSON file '" + path + "'");
}

}  // namespace

void JsonObject::write(const std::string& path) const { write_json_text(path, dump()); }

void JsonObject::write_array(const std::vector<JsonObject>& array, const std::string& path) {
  write_json_text(path, dump_array(array));
}

}  // namespace icgp
