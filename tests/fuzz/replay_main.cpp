// SPDX-License-Identifier: GPL-2.0-or-later
// Replays saved inputs through a fuzz target without libFuzzer, so that the normal build
// runs every seed and every input that once crashed: `fuzz_replay_<target> DIR...` feeds
// each file of each DIR (sorted, dot files skipped) to LLVMFuzzerTestOneInput, after the
// target's LLVMFuzzerInitialize when it has one. A crash, or an exception the target does
// not count as a clean refusal (fuzz_support.h), ends the process as it would end the
// fuzzer. Every DIR must exist, and one given with --nonempty must hold at least one input,
// so that a lost or misnamed corpus or regression folder does not pass silently.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);
// Optional, as for libFuzzer: a target's one-time set-up.
extern "C" __attribute__((weak)) int LLVMFuzzerInitialize(int* argc, char*** argv);

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> inputs_in(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().filename().string().rfind('.', 0) != 0) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::uint8_t> read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

int main(int argc, char** argv) {
  if (LLVMFuzzerInitialize) LLVMFuzzerInitialize(&argc, &argv);
  int replayed = 0;
  bool nonempty = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--nonempty") == 0) {
      nonempty = true;
      continue;
    }
    if (!fs::is_directory(argv[i])) {
      std::cerr << "fuzz replay: " << argv[i] << " is not a folder\n";
      return 1;
    }
    const std::vector<fs::path> files = inputs_in(argv[i]);
    if (nonempty && files.empty()) {
      std::cerr << "fuzz replay: " << argv[i] << " holds no inputs\n";
      return 1;
    }
    nonempty = false;
    for (const fs::path& file : files) {
      std::cout << "replaying " << file.string() << std::endl;  // flushed: names the input of a crash
      const std::vector<std::uint8_t> bytes = read_bytes(file);
      LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
      ++replayed;
    }
  }
  std::cout << "fuzz replay: " << replayed << " inputs, no crash\n";
  return 0;
}
