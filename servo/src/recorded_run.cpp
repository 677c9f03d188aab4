// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/servo/recorded_run.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <utility>
#include <visp3/core/vpThetaUVector.h>
#include <yaml-cpp/yaml.h>

#include "icgp/base/pose.h"
#include "icgp/servo/servo_report.h"

namespace icgp::servo {
namespace {

namespace fs = std::filesystem;

/// A θu vector read back from a log is a rotation's when its angle is at most π (as
/// vpThetaUVector gives it), with room for the 17 digits it was written with.
constexpr double kMaxRotationAngle = kPi + 1e-9;

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> fields;
  std::string::size_type begin = 0;
  for (std::string::size_type at; (at = line.find(separator, begin)) != std::string::npos; begin = at + 1)
    fields.push_back(line.substr(begin, at - begin));
  fields.push_back(line.substr(begin));
  return fields;
}

/// The log's lines, without line ends; trailing empty lines left out.
std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw LogError(path + ": cannot read the log");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  while (!lines.empty() && lines.back().empty()) lines.pop_back();
  return lines;
}

/// The header's columns by name, and the line's values by column name, with messages that
/// name the file, the line and the column.
class LogTable {
 public:
  LogTable(std::string path, const std::string& header) : path_(std::move(path)), names_(split(header, ',')) {
    for (std::size_t i = 0; i < names_.size(); ++i) index_.emplace(names_[i], i);
  }

  bool has(const std::string& column) const { return index_.count(column) > 0; }

  /// Throws unless the header has `column`; `why` says what it is needed for.
  void require(const std::string& column, const std::string& why) const {
    if (!has(column)) throw LogError(path_ + ":1: no column '" + column + "' (" + why + ")");
  }

  /// Makes `line` (the log's line `number`) the current one; throws unless it has a value
  /// per column.
  void read_line(const std::string& line, int number) {
    values_ = split(line, ',');
    line_ = number;
    if (values_.size() != names_.size())
      throw LogError(where() + std::to_string(values_.size()) + " values, but the header has " +
                     std::to_string(names_.size()) + " columns");
  }

  /// The current line's `column` as a number (NaN, Inf as the log writes them).
  double number(const std::string& column) const {
    const std::string& text = value(column);
    char* end = nullptr;
    const double x = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size()) fail(column, "expected a number, got '" + text + "'");
    return x;
  }
  double finite_number(const std::string& column) const {
    const double x = number(column);
    if (!std::isfinite(x)) fail(column, "expected a finite number, got '" + value(column) + "'");
    return x;
  }
  bool flag(const std::string& column) const {
    const std::string& text = value(column);
    if (text != "0" && text != "1") fail(column, "expected 0 or 1, got '" + text + "'");
    return text == "1";
  }

  [[noreturn]] void fail(const std::string& column, const std::string& what) const {
    throw LogError(where() + "column '" + column + "': " + what);
  }
  int line() const { return line_; }

 private:
  const std::string& value(const std::string& column) const { return values_[index_.at(column)]; }
  std::string where() const { return path_ + ":" + std::to_string(line_) + ": "; }

  std::string path_;
  std::vector<std::string> names_;
  std::map<std::string, std::size_t> index_;
  std::vector<std::string> values_;
  int line_ = 1;
};

/// The camera pose of the current line: kCameraPoseColumns, a translation and a θu rotation.
vpHomogeneousMatrix camera_pose(const LogTable& table) {
  double v[6];
  for (std::size_t i = 0; i < 6; ++i) v[i] = table.finite_number(kCameraPoseColumns[i]);
  const double angle = std::sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5]);
  if (angle > kMaxRotationAngle)
    table.fail(std::string(kCameraPoseColumns[3]) + "' to '" + kCameraPoseColumns[5],
               "(" + std::to_string(v[3]) + ", " + std::to_string(v[4]) + ", " + std::to_string(v[5]) +
                   ") is not a rotation's θu vector: its angle " + std::to_string(angle) +
                   " rad is more than π");
  return vpHomogeneousMatrix(vpTranslationVector(v[0], v[1], v[2]), vpThetaUVector(v[3], v[4], v[5]));
}

RecordedStep recorded_step(const LogTable& table) {
  RecordedStep step;
  step.line = table.line();
  step.time = table.finite_number("time");
  step.wMc = camera_pose(table);
  if (table.has("skipped")) step.skipped = table.flag("skipped");
  // The log writes millimetres and degrees.
  if (table.has("track_t_mm")) step.track_t = 1e-3 * table.number("track_t_mm");
  if (table.has("track_r_deg")) step.track_r = kPi / 180.0 * table.number("track_r_deg");
  return step;
}

/// The seed and scenario name of summary.json, when it gives them (a batch's summary, an
/// array of summaries of several trackers, gives no seed).
void read_summary(const std::string& path, RecordedRun& run) {
  YAML::Node json;
  try {
    json = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw LogError(path + ": not the summary of a run (" + e.what() + ")");
  }
  run.summary = path;
  if (!json.IsMap()) return;
  if (const YAML::Node scenario = json["scenario"]; scenario && scenario.IsScalar())
    run.scenario = scenario.as<std::string>();
  const YAML::Node seed = json["seed"];
  if (!seed || seed.IsNull()) return;
  const long long value = seed.IsScalar() ? seed.as<long long>(-1) : -1;  // -1: not an integer
  if (value < 0 || value > static_cast<long long>(std::numeric_limits<unsigned>::max()))
    throw LogError(path + ": seed: expected an integer in [0, " +
                   std::to_string(std::numeric_limits<unsigned>::max()) + "], got '" +
                   (seed.IsScalar() ? seed.Scalar() : std::string("a list or a map")) + "'");
  run.seed = static_cast<unsigned>(value);
}

}  // namespace

RecordedRun read_recorded_run(const std::string& log_csv) {
  const std::vector<std::string> lines = lines_of(log_csv);
  if (lines.empty()) throw LogError(log_csv + ": empty, not a log of `icgp servo` (log.csv)");
  LogTable table(log_csv, lines.front());
  table.require("time", "the simulated time of each step");
  for (const char* column : kCameraPoseColumns)
    table.require(column, "the camera's pose at each step, which logs of runs made before it was logged lack: run "
                          "the scenario again");
  RecordedRun run;
  run.log = log_csv;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    table.read_line(lines[i], static_cast<int>(i) + 1);
    run.steps.push_back(recorded_step(table));
  }
  if (run.steps.empty()) throw LogError(log_csv + ": no steps, only the header");
  const fs::path summary = fs::path(log_csv).parent_path() / "summary.json";
  std::error_code error;
  if (fs::is_regular_file(summary, error)) read_summary(summary.string(), run);
  return run;
}

}  // namespace icgp::servo
