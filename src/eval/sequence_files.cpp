// SPDX-License-Identifier: GPL-2.0-or-later
#include "sequence_files.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "icgp/eval/sequence.h"
#include "icgp/io/file_extension.h"

namespace icgp {

namespace fs = std::filesystem;

void fail(const fs::path& file, const std::string& what) { throw std::runtime_error(file.string() + ": " + what); }

std::string size_text(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

std::string read_text_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void require_file(const fs::path& path, const std::string& what) {
  if (!fs::is_regular_file(path)) fail(path, "missing " + what);
}

std::string numbered(const std::string& prefix, int index, int digits, const std::string& suffix) {
  char number[32];
  std::snprintf(number, sizeof number, "%0*d", digits, index);
  return prefix + number + suffix;
}

int count_numbered_files(const fs::path& folder, const std::string& prefix, int digits, const std::string& suffix,
                         int first) {
  std::set<int> indices;
  for (const auto& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (name.size() != prefix.size() + digits + suffix.size()) continue;
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    if (name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) continue;
    const std::string number = name.substr(prefix.size(), digits);
    if (!std::all_of(number.begin(), number.end(), [](unsigned char c) { return std::isdigit(c); })) continue;
    indices.insert(std::stoi(number));
  }
  if (indices.empty() || *indices.begin() != first)
    fail(folder / numbered(prefix, first, digits, suffix), "missing first frame file");
  int expected = first;
  for (const int index : indices) {
    if (index != expected)
      fail(folder / numbered(prefix, expected, digits, suffix),
           "missing frame file (the folder has frames up to " + numbered(prefix, *indices.rbegin(), digits, suffix) +
               ")");
    ++expected;
  }
  return static_cast<int>(indices.size());
}

std::vector<double> parse_numbers(const std::string& line, std::size_t expected, const fs::path& file, int line_no) {
  const std::string where = "line " + std::to_string(line_no) + ": ";
  std::vector<double> values;
  std::istringstream tokens(line);
  std::string token;
  while (tokens >> token) {
    char* end = nullptr;
    const double value = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0') fail(file, where + "'" + token + "' is not a number");
    values.push_back(value);
  }
  if (values.size() != expected)
    fail(file, where + "expected " + std::to_string(expected) + " numbers, found " + std::to_string(values.size()));
  return values;
}

bool is_blank(const std::string& line) {
  return std::all_of(line.begin(), line.end(), [](unsigned char c) { return std::isspace(c); });
}

/// Blender and ViSP write rotations in single precision, so orthonormality is only checked
/// loosely: the check is there to catch a wrong file (a projection matrix, a transposed
/// layout), not rounding.
Pose pose_from_row_major(const std::vector<double>& v, const fs::path& file, const std::string& where) {
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = v[4 * r + c];
  if (!m.allFinite()) fail(file, where + "matrix has non-finite entries");
  if (!m.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1), 1e-9))
    fail(file, where + "last row of the 4x4 matrix must be 0 0 0 1");
  const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
  if (!(R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-4) || R.determinant() < 0.0)
    fail(file, where + "top-left 3x3 block is not a rotation");
  return Pose(m);
}

Pose read_pose_matrix_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail(path, "cannot open file");
  std::vector<double> values;
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    if (is_blank(line)) continue;
    if (values.size() == 16) fail(path, "line " + std::to_string(line_no) + ": more than 4 rows");
    const std::vector<double> row = parse_numbers(line, 4, path, line_no);
    values.insert(values.end(), row.begin(), row.end());
  }
  if (values.size() != 16)
    fail(path, "expected 4 rows of 4 numbers, found " + std::to_string(values.size() / 4) + " rows");
  return pose_from_row_major(values, path, "");
}

namespace {

/// libjpeg decodes a JPEG cut short with only a warning on stderr, filling the missing rows
/// with grey, which tracks wrong. A complete file ends with the EOI marker (FF D9); only
/// padding may follow it.
bool jpeg_cut_short(const std::string& bytes) {
  const std::size_t end = bytes.find_last_not_of(std::string("\0 \r\n", 5));
  return end == std::string::npos || end < 1 || static_cast<unsigned char>(bytes[end - 1]) != 0xFF ||
         static_cast<unsigned char>(bytes[end]) != 0xD9;
}

}  // namespace

/// The file is read once: its bytes are checked, then decoded.
cv::Mat read_color_image(const fs::path& path) {
  require_file(path, "colour image");
  std::error_code error;
  if (fs::file_size(path, error) > std::uintmax_t(std::numeric_limits<int>::max()))
    fail(path, "larger than 2 GiB (expected a colour image file)");
  const std::string bytes = read_text_file(path);
  const std::string extension = lower_extension(path.string());
  if ((extension == ".jpg" || extension == ".jpeg") && jpeg_cut_short(bytes))
    fail(path, "the JPEG file is cut short (it does not end with the end-of-image marker FF D9); expected a complete image");
  cv::Mat image;
  if (!bytes.empty())
    image = cv::imdecode(cv::Mat(1, static_cast<int>(bytes.size()), CV_8UC1, const_cast<char*>(bytes.data())),
                         cv::IMREAD_COLOR);
  if (image.empty()) fail(path, "cannot decode colour image");
  return image;
}

}  // namespace icgp
