// SPDX-License-Identifier: GPL-2.0-or-later
// The project's one pseudo-random generator.
#pragma once

#include <cmath>
#include <cstdint>

namespace icgp {

/// splitmix64 (Steele, Lea, Flood, "Fast splittable pseudorandom number generators",
/// OOPSLA 2014): a few lines whose output is fully specified, unlike the standard library's
/// distributions, so that a seed gives the same sequence with every compiler. Models,
/// sequences and descriptor patterns made from a seed are reproducible with it.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}

  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1): the top 53 bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform in [low, high).
  double uniform(double low, double high) { return low + (high - low) * uniform(); }
  /// Standard normal (Box–Muller, one value of each pair: two draws a value).
  double normal() {
    const double u = 1.0 - uniform();  // (0, 1]: the logarithm stays finite
    return std::sqrt(-2.0 * std::log(u)) * std::cos(6.283185307179586 * uniform());
  }
  /// Uniform in [0, n) (multiply-shift; the bias of 2^-64 per value is far below anything seen).
  int below(int n) {
    return static_cast<int>((static_cast<unsigned __int128>(next()) * static_cast<unsigned>(n)) >> 64);
  }

 private:
  std::uint64_t state_;
};

/// The generator of one purpose (and one index, e.g. a frame's) of a seed: streams of
/// different purposes or indices do not depend on each other, so that changing what one
/// draws (the noise) moves nothing drawn from another (the camera's path).
inline SplitMix64 seeded_stream(std::uint64_t seed, std::uint64_t purpose, std::uint64_t index = 0) {
  SplitMix64 mixer(seed ^ (purpose << 56));
  return SplitMix64(mixer.next() ^ (index * 0xD1B54A32D192ED03ull));
}

}  // namespace icgp
