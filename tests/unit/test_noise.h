// SPDX-License-Identifier: GPL-2.0-or-later
// Another exposure of the same scene, for descriptor tests.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>

namespace icgp::test {

/// `image` (8-bit) with seeded Gaussian noise of `sigma` grey levels added.
inline cv::Mat with_noise(const cv::Mat& image, double sigma, std::uint64_t seed) {
  cv::Mat noise(image.size(), CV_32FC(image.channels())), noisy;
  cv::RNG(seed).fill(noise, cv::RNG::NORMAL, 0.0, sigma);
  cv::add(image, noise, noisy, cv::noArray(), image.depth());
  return noisy;
}

}  // namespace icgp::test
