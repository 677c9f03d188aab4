// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/features/daisy.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <utility>

#include "grey_image.h"

namespace icgp {

namespace {

// A keypoint's σ's use its scale rounded to 1/16 octave (at most 2.2 % off), so that
// keypoints of about the same size share smoothed maps; grid positions use the exact scale.
constexpr double kSigmaStepsPerOctave = 16.0;
// Once smoothed to this σ (in its own pixels), a map may drop every other pixel: the
// Gaussian leaves 5e-4 of the amplitude at the new Nyquist frequency.
constexpr float kHalvingSigma = 2.5f;

/// One histogram to fill: from the maps smoothed to `sigma`, read at `at` (pixels).
struct Sample {
  float sigma;
  int row;        // keypoint / descriptor row
  int histogram;  // index into the grid
  cv::Point2f at;
};

/// Weight of a sample at angle 0 in the trigonometric (periodic sinc) interpolation of a
/// 2π-periodic function from n samples 2π/n apart, at angle x.
double periodic_sinc(double x, int n) {
  double sum = 1.0;
  for (int q = 1; 2 * q < n; ++q) sum += 2.0 * std::cos(q * x);
  if (n % 2 == 0) sum += std::cos(0.5 * n * x);
  return sum / n;
}

/// The H × (H + 2) matrix that turns the smoothed maps (D_x, D_y, |D_πn/H| for n < H; D_t
/// is the derivative along angle t) into the H bins max(D_t, 0) at t = angle + 2πo/H.
///
/// max(D, 0) = (D + |D|) / 2. D_t = cos t D_x + sin t D_y is exact for any t, also after
/// smoothing. |D_t| repeats every half turn and is smooth in t but for a kink, so H samples
/// over half a turn interpolate it closely: exactly at multiples of 180°/H and, for H = 8,
/// within 6.4 % of a single gradient's magnitude between them (next to the kink). Linear
/// interpolation between H maps of max(D, 0) would be 19 % off, and left 4× the descriptor
/// distance between an image and its copy rotated by 30°.
std::vector<float> steering(double angle, int n_orientations) {
  const int n = n_orientations;
  std::vector<double> kernel(n);  // |D| samples sit 2π/n apart in 2t
  for (int j = 0; j < n; ++j) kernel[j] = periodic_sinc(2.0 * angle - 2.0 * CV_PI * j / n, n);
  std::vector<float> weights(static_cast<std::size_t>(n) * (n + 2));
  for (int o = 0; o < n; ++o) {
    float* row = &weights[static_cast<std::size_t>(o) * (n + 2)];
    const double t = angle + 2.0 * CV_PI * o / n;
    row[0] = static_cast<float>(0.5 * std::cos(t));
    row[1] = static_cast<float>(0.5 * std::sin(t));
    for (int m = 0; m < n; ++m) row[2 + m] = static_cast<float>(0.5 * kernel[((m - 2 * o) % n + n) % n]);
  }
  return weights;
}

/// Pixel u of the result is pixel 2u of the map.
cv::Mat every_other_pixel(const cv::Mat& map) {
  cv::Mat half((map.rows + 1) / 2, (map.cols + 1) / 2, CV_32F);
  for (int v = 0; v < half.rows; ++v) {
    const float* in = map.ptr<float>(2 * v);
    float* out = half.ptr<float>(v);
    for (int u = 0; u < half.cols; ++u) out[u] = in[2 * u];
  }
  return half;
}

/// Derivative maps M under a growing Gaussian, by the paper's incremental convolution
/// G_σ2 * M = G_√(σ2² − σ1²) * (G_σ1 * M), on a resolution that halves as σ grows so
/// that wide Gaussians cost no more than narrow ones.
class SmoothedMaps {
 public:
  explicit SmoothedMaps(std::vector<cv::Mat> maps) : maps_(std::move(maps)) {}

  /// Smooths on up to sigma (full-resolution pixels); a smaller sigma changes nothing.
  void smooth_to(float sigma) {
    while (sigma > sigma_) {
      const float next = std::min(sigma, kHalvingSigma * static_cast<float>(step_));
      if (next > sigma_) {
        const double increment = std::sqrt(next * next - sigma_ * sigma_) / static_cast<double>(step_);
        // Zero outside: beyond the image there is no gradient.
        for (cv::Mat& map : maps_) cv::GaussianBlur(map, map, cv::Size(), increment, increment, cv::BORDER_CONSTANT);
        sigma_ = next;
      } else {
        for (cv::Mat& map : maps_) map = every_other_pixel(map);
        step_ *= 2;
      }
    }
  }

  /// All maps at p (full-resolution pixels), interpolated bilinearly; a point beyond the
  /// border reads the nearest border pixel.
  void sample(cv::Point2f p, float* values) const {
    const int cols = maps_.front().cols, rows = maps_.front().rows;
    const float x = std::clamp(p.x / static_cast<float>(step_), 0.f, static_cast<float>(cols - 1));
    const float y = std::clamp(p.y / static_cast<float>(step_), 0.f, static_cast<float>(rows - 1));
    const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
    const int x1 = std::min(x0 + 1, cols - 1), y1 = std::min(y0 + 1, rows - 1);
    const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
    for (std::size_t o = 0; o < maps_.size(); ++o) {
      const cv::Mat& m = maps_[o];
      const float top = (1.f - fx) * m.at<float>(y0, x0) + fx * m.at<float>(y0, x1);
      const float bottom = (1.f - fx) * m.at<float>(y1, x0) + fx * m.at<float>(y1, x1);
      values[o] = (1.f - fy) * top + fy * bottom;
    }
  }

 private:
  std::vector<cv::Mat> maps_;
  float sigma_ = 0.f;  // smoothing so far, in full-resolution pixels
  int step_ = 1;       // full-resolution pixels per map pixel
};

}  // namespace

cv::Ptr<Daisy> Daisy::create(float radius, int rings, int histograms_per_ring, int orientations,
                             bool use_keypoint_orientation, bool use_keypoint_scale) {
  return cv::makePtr<Daisy>(radius, rings, histograms_per_ring, orientations, use_keypoint_orientation,
                            use_keypoint_scale);
}

Daisy::Daisy(float radius, int rings, int histograms_per_ring, int orientations, bool use_keypoint_orientation,
             bool use_keypoint_scale)
    : radius_(radius),
      orientations_(orientations),
      use_keypoint_orientation_(use_keypoint_orientation),
      use_keypoint_scale_(use_keypoint_scale) {
  if (!(radius > 0.f) || !std::isfinite(radius) || rings < 1 || histograms_per_ring < 1 || orientations < 1)
    throw std::invalid_argument("Daisy needs radius > 0, rings >= 1, histograms_per_ring >= 1, orientations >= 1");
  // The paper's layout: ring i (1..Q) at R_i = R·i/Q, smoothed with σ_i = R_i / 2 so that
  // neighbouring histograms overlap alike on every ring; the centre shares σ_1.
  grid_.push_back({{0.f, 0.f}, 0.5f * radius / static_cast<float>(rings)});
  for (int i = 1; i <= rings; ++i) {
    const float ring_radius = radius * static_cast<float>(i) / static_cast<float>(rings);
    for (int j = 0; j < histograms_per_ring; ++j) {
      const double angle = 2.0 * CV_PI * j / histograms_per_ring;
      grid_.push_back(
          {{ring_radius * static_cast<float>(std::cos(angle)), ring_radius * static_cast<float>(std::sin(angle))},
           0.5f * ring_radius});
    }
  }
}

void Daisy::detectAndCompute(cv::InputArray image, cv::InputArray /*mask*/, std::vector<cv::KeyPoint>& keypoints,
                             cv::OutputArray descriptors, bool useProvidedKeypoints) {
  if (!useProvidedKeypoints)
    CV_Error(cv::Error::StsNotImplemented, "icgp::Daisy only describes given keypoints; detect them first");
  const cv::Size size = image.size();  // 0 × 0 when empty: every keypoint goes
  const float max_x = static_cast<float>(size.width - 1), max_y = static_cast<float>(size.height - 1);
  keypoints.erase(std::remove_if(keypoints.begin(), keypoints.end(),
                                 [&](const cv::KeyPoint& k) {
                                   return !(k.pt.x >= 0.f && k.pt.x <= max_x && k.pt.y >= 0.f && k.pt.y <= max_y);
                                 }),
                  keypoints.end());
  if (keypoints.empty()) {
    descriptors.release();
    return;
  }

  const cv::Mat grey = grey_image(image.getMat());
  cv::Mat intensity;
  grey.convertTo(intensity, CV_32F);
  cv::Mat dx, dy;  // central differences
  cv::Sobel(intensity, dx, CV_32F, 1, 0, 1, 0.5, 0.0, cv::BORDER_REPLICATE);
  cv::Sobel(intensity, dy, CV_32F, 0, 1, 1, 0.5, 0.0, cv::BORDER_REPLICATE);
  // D_x, D_y and |D_t| at t = πn/H: what steering() needs for the bins at any angle.
  const int n_maps = orientations_ + 2;
  std::vector<cv::Mat> maps{dx, dy};
  for (int n = 0; n < orientations_; ++n) {
    const double angle = CV_PI * n / orientations_;
    cv::Mat derivative;
    cv::addWeighted(dx, std::cos(angle), dy, std::sin(angle), 0.0, derivative);
    maps.push_back(cv::abs(derivative));
  }

  // Every histogram of every keypoint, then all of them in the order of their σ.
  // A grid larger than the image says nothing more: sizes beyond it are capped.
  const float max_scale = static_cast<float>(std::max(size.width, size.height)) / radius_;
  std::vector<Sample> samples;
  samples.reserve(keypoints.size() * grid_.size());
  std::vector<std::vector<float>> bins_from_maps(keypoints.size());
  for (std::size_t r = 0; r < keypoints.size(); ++r) {
    const cv::KeyPoint& k = keypoints[r];
    const bool scaled = use_keypoint_scale_ && std::isfinite(k.size) && k.size > 0.f;
    // Sizes below a pixel count as one pixel: σ must stay well above zero.
    const float scale = scaled ? std::min(std::max(k.size, 1.f) / kReferenceKeypointSize, max_scale) : 1.f;
    const float sigma_scale =
        static_cast<float>(std::exp2(std::round(std::log2(scale) * kSigmaStepsPerOctave) / kSigmaStepsPerOctave));
    const bool rotated = use_keypoint_orientation_ && std::isfinite(k.angle) && k.angle >= 0.f;
    const double angle = rotated ? std::fmod(static_cast<double>(k.angle), 360.0) * CV_PI / 180.0 : 0.0;
    const float cos_a = static_cast<float>(std::cos(angle)), sin_a = static_cast<float>(std::sin(angle));
    bins_from_maps[r] = steering(angle, orientations_);
    for (std::size_t h = 0; h < grid_.size(); ++h) {
      const cv::Point2f& d = grid_[h].offset;
      const cv::Point2f at = k.pt + scale * cv::Point2f(cos_a * d.x - sin_a * d.y, sin_a * d.x + cos_a * d.y);
      samples.push_back({grid_[h].sigma * sigma_scale, static_cast<int>(r), static_cast<int>(h), at});
    }
  }
  std::sort(samples.begin(), samples.end(), [](const Sample& a, const Sample& b) { return a.sigma < b.sigma; });

  descriptors.create(static_cast<int>(keypoints.size()), descriptorSize(), CV_32F);
  cv::Mat out = descriptors.getMat();
  SmoothedMaps smoothed(std::move(maps));
  std::vector<float> values(n_maps);
  for (const Sample& s : samples) {
    smoothed.smooth_to(s.sigma);
    smoothed.sample(s.at, values.data());
    const float* weights = bins_from_maps[s.row].data();
    float* histogram = out.ptr<float>(s.row) + s.histogram * orientations_;
    float norm = 0.f;
    for (int o = 0; o < orientations_; ++o, weights += n_maps) {
      float bin = 0.f;
      for (int m = 0; m < n_maps; ++m) bin += weights[m] * values[m];
      histogram[o] = std::max(bin, 0.f);  // the interpolation may undershoot a little
      norm += histogram[o] * histogram[o];
    }
    // The paper's "partial" normalisation: each histogram on its own to unit length.
    norm = std::sqrt(norm);
    for (int o = 0; o < orientations_; ++o) histogram[o] = norm > 0.f ? histogram[o] / norm : 0.f;
  }
}

}  // namespace icgp
