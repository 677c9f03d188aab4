// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/io/cao_file_check.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "icgp/io/file_extension.h"

namespace icgp {
namespace {

namespace fs = std::filesystem;

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

std::string trimmed(const std::string& s) {
  const auto first = std::find_if_not(s.begin(), s.end(), is_space);
  const auto last = std::find_if_not(s.rbegin(), s.rend(), is_space).base();
  return first < last ? std::string(first, last) : std::string();
}

/// A shown value: bounded, so a megabyte token does not make a megabyte message.
std::string shown(const std::string& value) {
  std::string text = value.size() > 40 ? value.substr(0, 40) + "..." : value;
  for (char& c : text)
    if (static_cast<unsigned char>(c) < 32) c = '?';
  return "'" + text + "'";
}

/// A decimal number as std::istream >> double reads one: [sign] digits [. digits] [e [sign] digits].
/// strtod alone would also take "inf", "nan" and hexadecimal, which ViSP's stream does not.
bool parse_decimal(const std::string& token, double& value) {
  std::size_t i = 0, digits = 0;
  if (i < token.size() && (token[i] == '+' || token[i] == '-')) ++i;
  for (; i < token.size() && std::isdigit(static_cast<unsigned char>(token[i])); ++i) ++digits;
  if (i < token.size() && token[i] == '.')
    for (++i; i < token.size() && std::isdigit(static_cast<unsigned char>(token[i])); ++i) ++digits;
  if (digits == 0) return false;
  if (i < token.size() && (token[i] == 'e' || token[i] == 'E')) {
    ++i;
    if (i < token.size() && (token[i] == '+' || token[i] == '-')) ++i;
    std::size_t exponent_digits = 0;
    for (; i < token.size() && std::isdigit(static_cast<unsigned char>(token[i])); ++i) ++exponent_digits;
    if (exponent_digits == 0) return false;
  }
  if (i != token.size()) return false;
  errno = 0;
  value = std::strtod(token.c_str(), nullptr);
  return errno != ERANGE && std::isfinite(value);
}

std::string range_text(std::size_t lo, std::size_t hi) { return std::to_string(lo) + " to " + std::to_string(hi); }

/// One .cao file read with the stream operations of ViSP 3.5's loadCAOModel (a token is
/// what operator>> takes: whitespace, newlines included, is skipped before it; '#' lines
/// are skipped only where ViSP calls removeComment, at the start of each record).
class CaoFileReader {
 public:
  CaoFileReader(std::string path, std::string text) : path_(std::move(path)), text_(std::move(text)) {}

  const std::string& path() const { return path_; }

  [[noreturn]] void fail_at(std::size_t position, const std::string& field, const std::string& value,
                            const std::string& expected) const {
    const long line = 1 + std::count(text_.begin(), text_.begin() + static_cast<long>(std::min(position, text_.size())), '\n');
    throw std::invalid_argument(path_ + ":" + std::to_string(line) + ": " + field + ": " + value + " (expected " +
                                expected + ")");
  }
  [[noreturn]] void fail(const std::string& field, const std::string& value, const std::string& expected) const {
    fail_at(token_start_, field, value, expected);
  }

  /// ViSP's removeComment: whole lines starting with '#' at the current position.
  void skip_comment_lines() {
    while (pos_ < text_.size() && text_[pos_] == '#') {
      // ViSP skips at most 256 characters of a comment line; the rest would be read as data.
      const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
      if (end - pos_ > CaoLimits::kMaxLineLength + 1)
        fail_at(pos_, "comment", std::to_string(end - pos_) + " characters",
                "at most " + std::to_string(CaoLimits::kMaxLineLength + 1) + ": ViSP's parser skips no more of a comment line");
      skip_line();
    }
  }

  bool at_end() const { return pos_ >= text_.size(); }
  char next_char() const { return at_end() ? '\0' : text_[pos_]; }

  /// True when only whitespace and '#' lines remain: an optional section is absent.
  bool only_blank_or_comments_remain() const {
    std::size_t p = pos_;
    while (p < text_.size()) {
      if (text_[p] == '#') {
        p = text_.find('\n', p);
        if (p == std::string::npos) return true;
      } else if (!is_space(text_[p])) {
        return false;
      }
      ++p;
    }
    return true;
  }

  /// The rest of a version, count or point line, which ViSP skips with ignore(256, '\n'):
  /// that throws at the end of the file, and leaves what goes on past 255 characters to be
  /// read as the next data.
  void skip_rest_of_line(const std::string& record) {
    const std::size_t end = text_.find('\n', pos_);
    if (end == std::string::npos)
      fail_without_line_break(record);
    if (end - pos_ > CaoLimits::kMaxLineLength)
      fail_at(pos_, record, "the line goes on for " + std::to_string(end - pos_) + " characters after its numbers",
              "at most " + std::to_string(CaoLimits::kMaxLineLength) + ": ViSP's parser skips no more of the line");
    pos_ = end + 1;
  }

  /// Skips the rest of a count line; true when the file ended instead.
  bool skip_rest_of_line_or_end(const std::string& record) {
    if (text_.find('\n', pos_) == std::string::npos) {
      pos_ = text_.size();
      return true;
    }
    skip_rest_of_line(record);
    return false;
  }

  /// The rest of a line, face, cylinder or circle record (its parameters), which ViSP 3.5
  /// reads up to '\n', '\r' or "\r\n", of any length. A lone '\r' ends the record, so what
  /// follows it on the same line is the next record: reading past it would check other
  /// indices than the ones ViSP's parser uses, and it does not bound all of them. At the end
  /// of the file the rest must not be empty (ViSP's reader then fails).
  void skip_record_end(const std::string& record) {
    const std::size_t end = text_.find_first_of("\r\n", pos_);
    if (end == std::string::npos) {
      if (pos_ == text_.size())
        fail_without_line_break(record);
      pos_ = text_.size();
      return;
    }
    pos_ = end + (text_.compare(end, 2, "\r\n") == 0 ? 2 : 1);
  }

  std::size_t count(const std::string& field, std::size_t min, std::size_t max) {
    const std::string token = next_token(field, range_text(min, max));
    const std::size_t value = unsigned_value(token, field, range_text(min, max));
    if (value < min || value > max) fail(field, token, range_text(min, max));
    return value;
  }

  std::size_t index(const std::string& field, std::size_t size, const std::string& of_what) {
    const std::string expected =
        size == 0 ? "an index, but there are no " + of_what : "an index of the " + of_what + ", 0 to " + std::to_string(size - 1);
    const std::string token = next_token(field, expected);
    const std::size_t value = unsigned_value(token, field, expected);
    if (value >= size) fail(field, token, expected);
    return value;
  }

  double real(const std::string& field, double min, double max, bool min_exclusive) {
    std::ostringstream expected;
    expected << "a decimal number " << (min_exclusive ? "> " : "from ") << min << (min_exclusive ? " and <= " : " to ")
             << max;
    const std::string token = next_token(field, expected.str());
    double value = 0.0;
    if (!parse_decimal(token, value) || value < min || value > max || (min_exclusive && value == min))
      fail(field, shown(token), expected.str());
    return value;
  }

  void integer(const std::string& field) {
    const std::string token = next_token(field, "an integer");
    char* end = nullptr;
    errno = 0;
    const long value = std::strtol(token.c_str(), &end, 10);
    if (token.empty() || *end != '\0' || errno == ERANGE || value < INT_MIN || value > INT_MAX ||
        !(std::isdigit(static_cast<unsigned char>(token.back()))))
      fail(field, shown(token), "an integer");
  }

  /// ViSP's version line: 'V' then an integer read by operator>>.
  int version() {
    token_start_ = pos_;
    if (next_char() != 'V')
      fail("version", at_end() ? "end of file" : shown(text_.substr(pos_, text_.find('\n', pos_) - pos_)),
           "'V1' or 'V2' as the first line that is not a '#' comment");
    ++pos_;
    const std::string token = next_token("version", "V followed by a number");
    const std::size_t value = unsigned_value(token, "version", "V followed by a number");
    return value > 1000 ? 0 : static_cast<int>(value);
  }

  /// A whole line, as std::getline reads it: up to '\n', which must be there (ViSP's stream
  /// throws at the end of the file).
  std::string line(const std::string& record) {
    token_start_ = pos_;
    const std::size_t end = text_.find('\n', pos_);
    if (end == std::string::npos)
      fail_without_line_break(record);
    std::string whole = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    return whole;
  }

 private:
  [[noreturn]] void fail_without_line_break(const std::string& record) const {
    fail_at(text_.size(), record, "the file ends without a line break after it",
            "a line break: ViSP's parser fails at the end of the file there");
  }

  void skip_line() {
    const std::size_t end = text_.find('\n', pos_);
    pos_ = end == std::string::npos ? text_.size() : end + 1;
  }

  std::string next_token(const std::string& field, const std::string& expected) {
    while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
    token_start_ = pos_;
    if (at_end()) fail(field, "end of file", expected);
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }

  std::size_t unsigned_value(const std::string& token, const std::string& field, const std::string& expected) const {
    // operator>> into an unsigned would take "-1" as 4294967295; only plain digits are counts.
    if (token.empty() || token.size() > 9 ||
        !std::all_of(token.begin(), token.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
      fail(field, shown(token), expected);
    return static_cast<std::size_t>(std::stoul(token));
  }

  std::string path_;
  std::string text_;
  std::size_t pos_ = 0;
  std::size_t token_start_ = 0;
};

std::string read_file_bounded(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw std::invalid_argument(what + "'" + path + "': no such file (expected a ViSP .cao model file)");
  const auto size = fs::file_size(path, ec);
  if (ec || size > CaoLimits::kMaxFileBytes)
    throw std::invalid_argument(what + "'" + path + "': " + (ec ? "its size cannot be read" : std::to_string(size) + " bytes") +
                                " (expected at most " + std::to_string(CaoLimits::kMaxFileBytes) + " bytes)");
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in && !in.eof()) throw std::invalid_argument(what + "'" + path + "': cannot be read");
  return text;
}

/// The three numbers of a load() transform: "[a; b; c]", each optionally followed by "deg"
/// or "rad" for tu (ViSP reads them with atof, which takes garbage as 0; here it is refused).
void check_load_vector(const CaoFileReader& reader, const std::string& name, std::string values, bool angles) {
  const std::string expected = name + "=[x; y; z] with three decimal numbers" + (angles ? ", each optionally in deg or rad" : "");
  const std::size_t close = values.find(']');
  if (close == std::string::npos) reader.fail("load() " + name, shown(values), expected);
  values = values.substr(0, close);
  std::vector<std::string> parts;
  std::stringstream stream(values);
  for (std::string part; std::getline(stream, part, ';');) parts.push_back(trimmed(part));
  if (parts.size() != 3) reader.fail("load() " + name, shown(values), expected);
  for (std::string part : parts) {
    if (angles)
      for (const char* unit : {"deg", "rad"})
        if (part.size() > 3 && part.compare(part.size() - 3, 3, unit) == 0) part = trimmed(part.substr(0, part.size() - 3));
    double value = 0.0;
    if (!parse_decimal(part, value) || std::abs(value) > CaoLimits::kMaxCoordinate)
      reader.fail("load() " + name, shown(part), expected + " within +-" + std::to_string(int(CaoLimits::kMaxCoordinate)));
  }
}

class CaoModelCheck {
 public:
  CaoFileSummary run(const std::string& path) {
    check_file(fs::absolute(path).lexically_normal().string(), path, "");
    return summary_;
  }

 private:
  void check_file(const std::string& canonical, const std::string& shown_path, const std::string& included_from) {
    if (++summary_.files > CaoLimits::kMaxFilesLoaded)
      throw std::invalid_argument(included_from + "load(): more than " + std::to_string(CaoLimits::kMaxFilesLoaded) +
                                  " files loaded in all (expected at most that many, includes counted each time)");
    chain_.push_back(canonical);
    CaoFileReader reader(shown_path, read_file_bounded(shown_path, included_from));

    reader.skip_comment_lines();
    const int version = reader.version();
    reader.skip_rest_of_line("version");
    reader.skip_comment_lines();

    bool loads_files = false;
    while (reader.next_char() == 'l' || reader.next_char() == 'L') {
      const std::string line = reader.line("load()");
      if (line.compare(0, 4, "load") == 0) {
        check_load(reader, line);
        loads_files = true;
      }
      reader.skip_comment_lines();
    }

    const std::size_t points = reader.count("number of points", loads_files ? 0 : 1, CaoLimits::kMaxRecords);
    reader.skip_rest_of_line("number of points");
    std::vector<Eigen::Vector3d> xyz(points);
    for (std::size_t k = 0; k < points; ++k) {
      reader.skip_comment_lines();
      const std::string name = "point " + std::to_string(k);
      for (int axis = 0; axis < 3; ++axis)
        xyz[k][axis] = reader.real(name + " " + "xyz"[axis], -CaoLimits::kMaxCoordinate, CaoLimits::kMaxCoordinate, false);
      if (version == 2) {
        reader.integer(name + " image i");
        reader.integer(name + " image j");
      }
      reader.skip_rest_of_line(name);
    }
    summary_.points += points;

    reader.skip_comment_lines();
    const std::size_t lines = reader.count("number of lines", 0, CaoLimits::kMaxRecords);
    reader.skip_rest_of_line("number of lines");
    for (std::size_t k = 0; k < lines; ++k) {
      reader.skip_comment_lines();
      const std::string name = "line " + std::to_string(k);
      reader.index(name + " first point", points, "points");
      reader.index(name + " second point", points, "points");
      reader.skip_record_end(name);
    }
    summary_.lines += lines;

    check_faces(reader, "faces from lines", lines, "lines", 1, CaoLimits::kMaxFaceCorners / 2, 2);
    check_faces(reader, "faces from points", points, "points", 2, CaoLimits::kMaxFaceCorners, 1);

    // Cylinders and circles may be left out (older files); what is there must be whole.
    reader.skip_comment_lines();
    if (!reader.only_blank_or_comments_remain()) {
      const std::size_t cylinders = reader.count("number of cylinders", 0, CaoLimits::kMaxRecords);
      const bool ended = reader.skip_rest_of_line_or_end("number of cylinders");
      for (std::size_t k = 0; k < cylinders; ++k) {
        reader.skip_comment_lines();
        const std::string name = "cylinder " + std::to_string(k);
        const std::size_t a = reader.index(name + " first axis point", points, "points");
        const std::size_t b = reader.index(name + " second axis point", points, "points");
        reader.real(name + " radius", 0.0, CaoLimits::kMaxCoordinate, true);
        if (xyz[a] == xyz[b])
          reader.fail(name + " axis", "points " + std::to_string(a) + " and " + std::to_string(b) + " coincide",
                      "two distinct points");
        reader.skip_record_end(name);
      }
      summary_.cylinders += cylinders;
      reader.skip_comment_lines();
      if (!ended && !reader.only_blank_or_comments_remain()) {
        const std::size_t circles = reader.count("number of circles", 0, CaoLimits::kMaxRecords);
        reader.skip_rest_of_line_or_end("number of circles");
        for (std::size_t k = 0; k < circles; ++k) {
          reader.skip_comment_lines();
          const std::string name = "circle " + std::to_string(k);
          reader.real(name + " radius", 0.0, CaoLimits::kMaxCoordinate, true);
          const std::size_t c = reader.index(name + " centre point", points, "points");
          const std::size_t p = reader.index(name + " second point", points, "points");
          const std::size_t q = reader.index(name + " third point", points, "points");
          const Eigen::Vector3d u = xyz[p] - xyz[c], v = xyz[q] - xyz[c];
          if (!(u.cross(v).norm() > 1e-12 * u.norm() * v.norm()))
            reader.fail(name + " plane", "points " + std::to_string(c) + ", " + std::to_string(p) + " and " +
                                             std::to_string(q) + " are collinear",
                        "a centre and two points spanning the circle's plane");
          reader.skip_record_end(name);
        }
        summary_.circles += circles;
      }
    }
    chain_.pop_back();
  }

  void check_faces(CaoFileReader& reader, const std::string& section, std::size_t available, const std::string& of_what,
                   std::size_t min_refs, std::size_t max_refs, std::size_t corners_per_ref) {
    reader.skip_comment_lines();
    const std::size_t faces = reader.count("number of " + section, 0, CaoLimits::kMaxRecords);
    reader.skip_rest_of_line("number of " + section);
    const std::string singular = section.substr(0, 4) + section.substr(5);  // "face from lines"
    for (std::size_t k = 0; k < faces; ++k) {
      reader.skip_comment_lines();
      const std::string name = "face " + std::to_string(k) + " (" + singular + ")";
      const std::size_t n = reader.count(name + " number of " + of_what, min_refs, max_refs);
      for (std::size_t i = 0; i < n; ++i) reader.index(name + " " + of_what.substr(0, of_what.size() - 1) + " " + std::to_string(i), available, of_what);
      reader.skip_record_end(name);
      summary_.face_corners += n * corners_per_ref;
    }
    summary_.faces += faces;
  }

  /// load("path", t=[..], tu=[..]): the path is resolved against the including file's folder.
  void check_load(const CaoFileReader& reader, const std::string& line) {
    const std::string expected = "load(\"file.cao\"), optionally with , t=[x; y; z] and , tu=[rx; ry; rz]";
    if (line.size() < 6 || line[4] != '(') reader.fail("load()", shown(line), expected);
    std::string inside = line.substr(5);
    inside = inside.substr(0, inside.find(')'));
    std::vector<std::string> params;
    std::stringstream stream(inside);
    for (std::string part; std::getline(stream, part, ',');) params.push_back(trimmed(part));
    if (params.empty() || params[0].size() < 3 || params[0].front() != '"' || params[0].find('"', 1) == std::string::npos)
      reader.fail("load() file", shown(line), expected);
    const std::string reference = params[0].substr(1, params[0].find('"', 1) - 1);
    if (reference.empty()) reader.fail("load() file", shown(line), expected);
    for (std::size_t i = 1; i < params.size(); ++i) {
      if (params[i].compare(0, 3, "t=[") == 0)
        check_load_vector(reader, "t", params[i].substr(3), false);
      else if (params[i].compare(0, 4, "tu=[") == 0)
        check_load_vector(reader, "tu", params[i].substr(4), true);
      else
        reader.fail("load() argument", shown(params[i]), expected);
    }
    fs::path included = reference;
    if (included.is_relative()) included = fs::path(reader.path()).parent_path() / included;
    const std::string canonical = fs::absolute(included).lexically_normal().string();
    if (std::find(chain_.begin(), chain_.end(), canonical) != chain_.end())
      reader.fail("load() file", shown(reference), "a file that does not load itself through its includes");
    std::error_code ec;
    if (!fs::is_regular_file(included, ec)) reader.fail("load() file", shown(included.string()), "an existing .cao file");
    check_file(canonical, included.string(), reader.path() + ": load(\"" + reference + "\"): ");
  }

  CaoFileSummary summary_;
  std::vector<std::string> chain_;  ///< files being read, outermost first: a cycle comes back to one
};

}  // namespace

CaoFileSummary check_cao_file(const std::string& path) { return CaoModelCheck().run(path); }

bool is_cao_path(const std::string& path) { return lower_extension(path) == ".cao"; }

}  // namespace icgp
