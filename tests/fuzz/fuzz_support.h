// SPDX-License-Identifier: GPL-2.0-or-later
// What the fuzz targets share. The loaders under test read paths, so each input is written
// to a file first; and a documented exception is the API's clean refusal of bad bytes, so
// it counts as success. Only crashes, sanitizer reports, hangs and leaks are findings.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <unistd.h>

namespace icgp::fuzz {

/// A scratch folder of this process, removed when the process ends normally (a crash
/// leaves it behind in the temporary directory, with the input that caused it).
class ScratchDir {
 public:
  ScratchDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "icgp-fuzz-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a scratch folder from " + pattern);
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ignored;  // best effort: never throw from a destructor at exit
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

inline const std::filesystem::path& scratch_dir() {
  static const ScratchDir dir;
  return dir.path();
}

/// Writes `size` bytes to `path` (replacing it); returns the path as a string.
inline std::string write_file(const std::filesystem::path& path, const std::uint8_t* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) throw std::runtime_error("fuzz harness: cannot write " + path.string());
  return path.string();
}

inline std::string write_file(const std::filesystem::path& path, const std::string& text) {
  return write_file(path, reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

/// Runs `call`; an exception of one of the `Refusal` types is the API's clean refusal of
/// bad bytes (the loaders' documented errors; vpMbIcgTracker's vpException). Any other
/// exception is a finding: std::bad_alloc or std::length_error (a size that reached an
/// allocator unchecked), std::out_of_range (an index unchecked), cv::Exception (bytes that
/// reached OpenCV unchecked), std::logic_error (a broken invariant). It is named on stderr
/// and the process aborts, as libFuzzer and the replay report a crash. With
/// ICGP_FUZZ_SHOW_REFUSALS set, each refusal's message goes to stderr: how to check that
/// the seeds are accepted, and that a refusal names what is wrong.
template <class... Refusal, class Call>
void refusing_cleanly(Call&& call) {
  static_assert(sizeof...(Refusal) > 0, "name the exception types that are clean refusals");
  static const bool show = std::getenv("ICGP_FUZZ_SHOW_REFUSALS") != nullptr;
  const auto refused = [](const std::exception& e) {
    if (show) std::cerr << "refused: " << e.what() << "\n";
  };
  try {
    call();
  } catch (const std::exception& e) {
    if (!(... || (dynamic_cast<const Refusal*>(&e) != nullptr))) {
      std::cerr << "fuzz: unexpected exception (not a clean refusal): " << e.what() << "\n";
      std::abort();
    }
    refused(e);
  }
}

/// The core loaders' documented errors: bad content (std::runtime_error and its subclasses:
/// ModelFileError, ScenarioError, the YAML reader's Error) and bad values
/// (std::invalid_argument).
template <class Call>
void refusing_like_a_loader(Call&& call) {
  refusing_cleanly<std::runtime_error, std::invalid_argument>(std::forward<Call>(call));
}

}  // namespace icgp::fuzz
