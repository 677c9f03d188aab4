// SPDX-License-Identifier: GPL-2.0-or-later
// The fuzz targets' line between a clean refusal and a finding (fuzz_support.h), checked
// on its own: `refusal_check refusal` throws a loader's documented error (a refusal, exit
// 0); `refusal_check bad_alloc` and `refusal_check logic_error` throw what bytes that reach
// an allocator unchecked or break an invariant throw (a finding: the process aborts).
#include <cstring>
#include <new>
#include <stdexcept>

#include "fuzz_support.h"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const char* mode = argv[1];
  icgp::fuzz::refusing_like_a_loader([mode] {
    if (std::strcmp(mode, "refusal") == 0) throw std::invalid_argument("a value out of range");
    if (std::strcmp(mode, "bad_alloc") == 0) throw std::bad_alloc();
    if (std::strcmp(mode, "logic_error") == 0) throw std::logic_error("an invariant broken");
  });
  return 0;
}
