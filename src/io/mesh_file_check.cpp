// SPDX-License-Identifier: GPL-2.0-or-later
#include "mesh_file_check.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "icgp/io/file_extension.h"

namespace icgp {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxPlyHeaderBytes = 64 * 1024;

[[noreturn]] void refuse(const std::string& path, const std::string& what) {
  throw std::runtime_error("load_mesh: '" + path + "': " + what);
}

/// Bytes of one PLY scalar type; 0 for a name that is none.
std::size_t ply_type_size(const std::string& type) {
  static const std::map<std::string, std::size_t> sizes = {
      {"char", 1},  {"uchar", 1},  {"int8", 1},   {"uint8", 1},   {"short", 2},   {"ushort", 2},
      {"int16", 2}, {"uint16", 2}, {"int", 4},    {"uint", 4},    {"int32", 4},   {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto it = sizes.find(type);
  return it == sizes.end() ? 0 : it->second;
}

/// The header's grammar, and a lower bound of the body its elements need: fixed-size
/// properties in full, lists at least their count (binary), a character per value (ASCII).
void check_ply(const std::string& path, std::ifstream& in, std::uintmax_t file_size) {
  std::string header(kMaxPlyHeaderBytes, '\0');
  in.read(header.data(), static_cast<std::streamsize>(header.size()));
  header.resize(static_cast<std::size_t>(in.gcount()));
  if (header.compare(0, 3, "ply") != 0) refuse(path, "PLY file without the 'ply' magic line");
  // The header ends at a line that is "end_header" and nothing else (assimp hung on a file
  // whose end_header was the tail of a property line).
  std::size_t end = header.find("\nend_header");
  while (end != std::string::npos && end + 11 < header.size() && header[end + 11] != '\n' && header[end + 11] != '\r')
    end = header.find("\nend_header", end + 1);
  if (end == std::string::npos || end + 11 >= header.size())
    refuse(path, "PLY header without an 'end_header' line in its first " + std::to_string(kMaxPlyHeaderBytes) + " bytes");
  ++end;  // the line itself
  const std::size_t body_start = header.find('\n', end);
  const std::uintmax_t body_bytes = body_start == std::string::npos ? 0 : file_size - (body_start + 1);

  std::istringstream lines(header.substr(0, end));
  std::string line, format;
  int line_number = 0;
  bool in_element = false;
  std::uintmax_t count = 0, element_bytes = 0, needed = 0;
  const auto close_element = [&] {
    if (in_element) needed += count * element_bytes;
  };
  while (std::getline(lines, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    const auto bad = [&](const std::string& expected) {
      refuse(path, "PLY header line " + std::to_string(line_number) + " '" + line.substr(0, 60) + "' (expected " + expected + ")");
    };
    if (line_number == 1 || keyword == "comment" || keyword == "obj_info" || keyword.empty()) continue;
    if (keyword == "format") {
      std::string version;
      words >> format >> version;
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
        bad("format ascii, binary_little_endian or binary_big_endian");
    } else if (keyword == "element") {
      close_element();
      std::string name, number;
      words >> name >> number;
      if (name.empty() || number.empty() || number.size() > 10 ||
          !std::all_of(number.begin(), number.end(), [](unsigned char c) { return std::isdigit(c); }))
        bad("element <name> <count>");
      in_element = true;
      count = std::stoull(number);
      element_bytes = 0;
    } else if (keyword == "property") {
      if (!in_element) bad("a property after an element line");
      std::string type, name;
      words >> type;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type >> name;
        if (ply_type_size(count_type) == 0 || ply_type_size(item_type) == 0 || name.empty())
          bad("property list <count type> <item type> <name>");
        element_bytes += format == "ascii" ? 2 : ply_type_size(count_type);
      } else {
        words >> name;
        if (ply_type_size(type) == 0 || name.empty()) bad("property <type> <name> with a PLY type");
        element_bytes += format == "ascii" ? 2 : ply_type_size(type);
      }
    } else {
      bad("format, element, property, comment, obj_info or end_header");
    }
  }
  close_element();
  if (format.empty()) refuse(path, "PLY header without a format line");
  if (needed > body_bytes)
    refuse(path, "PLY header promises elements of at least " + std::to_string(needed) + " bytes, the file holds " +
                     std::to_string(body_bytes) + " after its header (expected a complete file)");
}

/// A binary STL is an 80-byte header, a triangle count and 50 bytes per triangle; ASCII
/// files start with "solid" (so may binary ones, whose size then decides).
void check_stl(const std::string& path, std::ifstream& in, std::uintmax_t file_size) {
  char head[84] = {};
  in.read(head, sizeof head);
  const bool starts_solid = in.gcount() >= 5 && std::string(head, 5) == "solid";
  if (in.gcount() < 84) {
    if (!starts_solid) refuse(path, "STL file of " + std::to_string(file_size) + " bytes (a binary STL has at least 84)");
    return;
  }
  const std::uintmax_t triangles = std::uintmax_t(static_cast<unsigned char>(head[80])) |
                                   std::uintmax_t(static_cast<unsigned char>(head[81])) << 8 |
                                   std::uintmax_t(static_cast<unsigned char>(head[82])) << 16 |
                                   std::uintmax_t(static_cast<unsigned char>(head[83])) << 24;
  if (84 + 50 * triangles != file_size && !starts_solid)
    refuse(path, "binary STL header counts " + std::to_string(triangles) + " triangles, which need " +
                     std::to_string(84 + 50 * triangles) + " bytes; the file has " + std::to_string(file_size));
}

}  // namespace

void check_mesh_file_structure(const std::string& path) {
  const std::string extension = lower_extension(path);
  if (extension != ".ply" && extension != ".stl") return;
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  if (ec || !in) refuse(path, "cannot be read");
  if (extension == ".ply") check_ply(path, in, size);
  if (extension == ".stl") check_stl(path, in, size);
}

}  // namespace icgp
