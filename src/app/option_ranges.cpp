// SPDX-License-Identifier: GPL-2.0-or-later
#include "option_ranges.h"

#include <charconv>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace icgp::app {
namespace {

/// The whole of `text` as a T; false when it is not one (or does not fit).
template <typename T>
bool parse_whole(const std::string& text, T& value) {
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  return error == std::errc() && stop == end;
}

}  // namespace

CLI::Validator integer_in(long long min, long long max) {
  const std::string range = yaml::Interval{static_cast<double>(min), static_cast<double>(max)}.text();
  // CLI11 prefixes the option's name: "--frames: expected …".
  return CLI::Validator(
      [min, max, range](std::string& input) -> std::string {
        long long value = 0;
        if (parse_whole(input, value) && value >= min && value <= max) return {};
        return "expected an integer in " + range + ", got " + input;
      },
      "in " + range);
}

CLI::Validator number_in(const yaml::Interval& range) {
  return CLI::Validator(
      [range](std::string& input) -> std::string {
        double value = 0.0;
        if (parse_whole(input, value) && range.contains(value)) return {};
        return "expected a number in " + range.text() + ", got " + input;
      },
      "in " + range.text());
}

CLI::Validator image_side() { return integer_in(1, kMaxImageSide); }

void check_image_pixels(int width, int height, const char* width_option, const char* height_option) {
  const long long pixels = static_cast<long long>(width) * height;
  if (pixels <= kMaxImagePixels) return;
  throw std::invalid_argument(std::string(width_option) + " " + std::to_string(width) + " x " + height_option + " " +
                              std::to_string(height) + " = " + std::to_string(pixels) + " pixels, more than the " +
                              std::to_string(kMaxImagePixels) + " (" + std::to_string(kMaxImageSide) + " x " +
                              std::to_string(kMaxImagePixels / kMaxImageSide) + ") an image may have");
}

}  // namespace icgp::app
