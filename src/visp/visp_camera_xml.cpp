// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/visp/visp_camera_xml.h"

#include <array>
#include <cstdlib>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <visp3/core/vpException.h>
#include <visp3/mbt/vpMbtXmlGenericParser.h>

#include "icgp/base/standard_stream_capture.h"

namespace icgp {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error(path + ": " + what);
}

std::string number_text(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

/// ViSP's parser keeps the camera it was given for every field the file leaves out, so a
/// camera of this value tells which fields the file gives: no file writes it.
constexpr double kNotInFile = std::numeric_limits<double>::lowest();

/// ViSP's parser reads the leading number of an element's text and drops the rest
/// (<u0>3x</u0> is 3), so the text of every intrinsics element is checked first.
void check_number_elements(const std::string& path) {
  constexpr std::uintmax_t kMaxBytes = 1 << 20;
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error || size > kMaxBytes)
    fail(path, std::to_string(size) + " bytes (expected an XML file of at most " + std::to_string(kMaxBytes) + " bytes)");
  std::ifstream in(path, std::ios::binary);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  for (const std::string tag : {"px", "py", "u0", "v0"}) {
    const std::string open = "<" + tag + ">", close = "</" + tag + ">";
    for (std::size_t at = text.find(open); at != std::string::npos; at = text.find(open, at + 1)) {
      const std::size_t begin = at + open.size(), end = text.find(close, begin);
      if (end == std::string::npos) break;  // malformed XML: ViSP's parser says so
      const std::string value = text.substr(begin, end - begin);
      char* stop = nullptr;
      const double number = std::strtod(value.c_str(), &stop);
      while (stop && (*stop == ' ' || *stop == '\t' || *stop == '\r' || *stop == '\n')) ++stop;
      if (value.empty() || stop == value.c_str() || *stop != '\0' || !std::isfinite(number))
        fail(path, "<camera> <" + tag + ">: '" + value.substr(0, 40) + "' (expected a finite number)");
    }
  }
}

}  // namespace

Intrinsics read_visp_camera_xml(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) fail(path, "no such file");
  if (!std::filesystem::is_regular_file(path, error) || !std::ifstream(path)) fail(path, "cannot read the file");
  check_number_elements(path);

  // Any parser type but PROJECTION_ERROR_PARSER reads <camera>; the edge parser reads the
  // fewest other blocks.
  vpMbtXmlGenericParser parser(vpMbtXmlGenericParser::EDGE_PARSER);
  vpCameraParameters not_in_file;
  not_in_file.initPersProjWithoutDistortion(kNotInFile, kNotInFile, kNotInFile, kNotInFile);
  parser.setCameraParameters(not_in_file);
  parser.setVerbose(false);
  try {
    const StandardStreamCapture chatter(std::cout);
    parser.parse(path);
  } catch (const vpException& e) {
    // The file exists and is readable, so ViSP's "Cannot open file" means it is no XML;
    // the only other complaint about <camera> is a px or py of 0, which is also what it
    // reads from text that is no number.
    if (e.getCode() == vpException::ioError)
      fail(path, "not an XML file ViSP's parser reads (" + e.getStringMessage() + ")");
    fail(path, "<camera>: " + e.getStringMessage() + " (px and py must be positive numbers)");
  }
  vpCameraParameters camera;
  parser.getCameraParameters(camera);

  Intrinsics k;
  k.fu = camera.get_px();
  k.fv = camera.get_py();
  k.pu = camera.get_u0();
  k.pv = camera.get_v0();
  const std::array<std::pair<const char*, double>, 4> fields = {
      {{"px", k.fu}, {"py", k.fv}, {"u0", k.pu}, {"v0", k.pv}}};
  int missing = 0;
  for (const auto& [tag, value] : fields) missing += value == kNotInFile;
  if (missing == 4) fail(path, "no <camera> block with <px>, <py>, <u0> and <v0>");
  for (const auto& [tag, value] : fields) {
    const std::string name = tag;
    if (value == kNotInFile) fail(path, "<camera> block has no <" + name + ">");
    const bool focal = name == "px" || name == "py";
    if (!std::isfinite(value) || (focal && !(value > 0.0)))
      fail(path, "<camera> <" + name + "> must be a finite" + (focal ? " positive" : "") + " number, got " +
                     number_text(value));
  }
  return k;
}

SequenceOptions visp_sequence_options() {
  SequenceOptions options;
  options.read_camera_xml = read_visp_camera_xml;
  return options;
}

}  // namespace icgp
