// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/features/oriented_brief.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "grey_image.h"
#include "icgp/base/splitmix64.h"

namespace icgp {

namespace {

// BRIEF's G II spread, σ = S / 5 for the patch size S: the paper's best pattern.
constexpr double kPatternSigma = OrientedBrief::kPatchSize / 5.0;
// Any fixed seed: it only has to be the same everywhere.
constexpr std::uint64_t kPatternSeed = 0x0b71ef2011ull;
// cv::FAST does not test the 3 pixels next to each edge (its circle's radius).
constexpr int kFastRadius = 3;

/// A test point: two i.i.d. N(0, σ²) coordinates by Box–Muller, rounded to pixels, drawn
/// again until the point's 5×5 sub-window lies in the 31×31 patch.
cv::Point gaussian_point(SplitMix64& rng) {
  for (;;) {
    // 1 - uniform() is in (0, 1], so the log is finite.
    const double radius = kPatternSigma * std::sqrt(-2.0 * std::log(1.0 - rng.uniform()));
    const double turn = 2.0 * CV_PI * rng.uniform();
    const cv::Point p(static_cast<int>(std::lround(radius * std::cos(turn))),
                      static_cast<int>(std::lround(radius * std::sin(turn))));
    if (std::abs(p.x) <= OrientedBrief::kPatternRadius && std::abs(p.y) <= OrientedBrief::kPatternRadius) return p;
  }
}

/// 256 pairs of gaussian_point()s. A pair of equal points would always give 0, and a pair
/// drawn twice (in either order) the same bit or its complement: both are drawn again.
std::array<OrientedBrief::Pair, OrientedBrief::kPairs> make_pattern() {
  SplitMix64 rng(kPatternSeed);
  std::array<OrientedBrief::Pair, OrientedBrief::kPairs> pairs;
  int n = 0;
  while (n < OrientedBrief::kPairs) {
    const cv::Point a = gaussian_point(rng), b = gaussian_point(rng);
    const bool repeated = std::any_of(pairs.begin(), pairs.begin() + n, [&](const OrientedBrief::Pair& p) {
      return (p.first == a && p.second == b) || (p.first == b && p.second == a);
    });
    if (a != b && !repeated) pairs[n++] = {a, b};
  }
  return pairs;
}

using RotatedPatterns = std::array<std::array<OrientedBrief::Pair, OrientedBrief::kPairs>, OrientedBrief::kAngleBins>;

/// The pattern turned by bin · 12° (from +x towards +y, as keypoint angles), rounded to pixels.
RotatedPatterns make_rotated_patterns() {
  RotatedPatterns rotated;
  for (int bin = 0; bin < OrientedBrief::kAngleBins; ++bin) {
    const double angle = 2.0 * CV_PI * bin / OrientedBrief::kAngleBins;
    const double c = std::cos(angle), s = std::sin(angle);
    auto turn = [&](const cv::Point& p) {
      return cv::Point(static_cast<int>(std::lround(c * p.x - s * p.y)),
                       static_cast<int>(std::lround(s * p.x + c * p.y)));
    };
    for (int b = 0; b < OrientedBrief::kPairs; ++b)
      rotated[bin][b] = {turn(OrientedBrief::pattern()[b].first), turn(OrientedBrief::pattern()[b].second)};
  }
  return rotated;
}

const RotatedPatterns& rotated_patterns() {
  static const RotatedPatterns rotated = make_rotated_patterns();
  return rotated;
}

/// The orientation disk over a fixed span of columns, so that the moments' sums vectorise:
/// row v spans u in [-extent(v), extent(v)] (the pixels whose centres lie within the
/// radius), stored by |v| as a mask (all bits set inside, 0 outside) and as the weight v
/// (0 outside).
struct DiskWeights {
  static constexpr int kSpan = 32;            ///< u from -16 to 15
  static constexpr int kFirst = -kSpan / 2;   ///< u of the span's first pixel
  using Row = std::array<std::int16_t, kSpan>;
  std::array<Row, OrientedBrief::kOrientationRadius + 1> inside, v;
};

DiskWeights make_disk_weights() {
  constexpr int r = OrientedBrief::kOrientationRadius;
  static_assert(-DiskWeights::kFirst >= r && DiskWeights::kSpan + DiskWeights::kFirst > r, "the span covers the disk");
  DiskWeights weights{};
  for (int v = 0; v <= r; ++v) {
    const int extent = static_cast<int>(std::floor(std::sqrt(static_cast<double>(r * r - v * v))));
    for (int j = 0; j < DiskWeights::kSpan; ++j) {
      if (std::abs(DiskWeights::kFirst + j) > extent) continue;
      weights.inside[v][j] = -1;
      weights.v[v][j] = static_cast<std::int16_t>(v);
    }
  }
  return weights;
}

/// See OrientedBrief::borderWidth(): the reach of every pixel read around a keypoint.
int compute_border_width() {
  int reach = 0;
  for (const auto& pairs : rotated_patterns())
    for (const auto& [a, b] : pairs)
      reach = std::max({reach, std::abs(a.x), std::abs(a.y), std::abs(b.x), std::abs(b.y)});
  // The disk's span reaches one column further left than the disk; Harris reads the
  // neighbours of its window and of the padded eighth column on the right.
  return std::max({reach + OrientedBrief::kSubWindowRadius, -DiskWeights::kFirst, OrientedBrief::kHarrisRadius + 2});
}

/// The Harris response at pixel `at`, in grey levels⁴; gradients are the central
/// differences (I(x + 1) - I(x - 1)) / 2, whose 1/2 is applied to the result at the end.
float harris_response(const cv::Mat& grey, cv::Point at) {
  // A window row, padded from 7 to 8 columns (the last masked out), is one vector of
  // 16-bit gradients whose products add up in pairs to 32 bits. The compiler does not
  // find this by itself: OpenCV's universal intrinsics spell it out, portably.
  constexpr int r = OrientedBrief::kHarrisRadius;
  static_assert(cv::v_int16x8::nlanes == 2 * r + 2, "a vector is a window row and one column");
  const cv::v_int16x8 inside(-1, -1, -1, -1, -1, -1, -1, 0);
  const std::ptrdiff_t step = static_cast<std::ptrdiff_t>(grey.step);
  auto load = [](const std::uint8_t* p) { return cv::v_reinterpret_as_s16(cv::v_load_expand(p)); };
  cv::v_int32x4 xx = cv::v_setzero_s32(), yy = cv::v_setzero_s32(), xy = cv::v_setzero_s32();
  for (int v = -r; v <= r; ++v) {
    const std::uint8_t* row = grey.ptr<std::uint8_t>(at.y + v) + at.x - r;
    const cv::v_int16x8 ix = (load(row + 1) - load(row - 1)) & inside;
    const cv::v_int16x8 iy = (load(row + step) - load(row - step)) & inside;
    xx += cv::v_dotprod(ix, ix);
    yy += cv::v_dotprod(iy, iy);
    xy += cv::v_dotprod(ix, iy);
  }
  const double sxx = cv::v_reduce_sum(xx), syy = cv::v_reduce_sum(yy), sxy = cv::v_reduce_sum(xy);
  const double trace = sxx + syy;
  const double det = sxx * syy - sxy * sxy;
  return static_cast<float>((det - OrientedBrief::kHarrisK * trace * trace) / 16.0);
}

/// The angle (degrees in [0, 360), from +x towards +y) from the keypoint at pixel `at` to
/// the intensity centroid of the disk around it: atan2(m01, m10) with m_pq = Σ u^p v^q I.
float centroid_angle(const cv::Mat& grey, cv::Point at) {
  static const DiskWeights weights = make_disk_weights();
  const std::ptrdiff_t step = static_cast<std::ptrdiff_t>(grey.step);
  const std::uint8_t* centre = grey.ptr<std::uint8_t>(at.y) + at.x + DiskWeights::kFirst;
  // Per column u of the disk: the sum of its pixels, Σ_v I, and Σ_v v I. Both fit 16 bits
  // (31 · 255 and (1 + ... + 15) · 255 = 30600 at most), so they add 8 columns at a time.
  DiskWeights::Row column, weighted{};
  for (int j = 0; j < DiskWeights::kSpan; ++j) column[j] = static_cast<std::int16_t>(weights.inside[0][j] & centre[j]);
  for (int v = 1; v <= OrientedBrief::kOrientationRadius; ++v) {
    const std::uint8_t* below = centre + v * step;
    const std::uint8_t* above = centre - v * step;
    for (int j = 0; j < DiskWeights::kSpan; ++j) {
      column[j] = static_cast<std::int16_t>(column[j] + (weights.inside[v][j] & (below[j] + above[j])));
      weighted[j] = static_cast<std::int16_t>(weighted[j] + weights.v[v][j] * (below[j] - above[j]));
    }
  }
  int m10 = 0, m01 = 0;
  for (int j = 0; j < DiskWeights::kSpan; ++j) {
    m10 += (DiskWeights::kFirst + j) * column[j];
    m01 += weighted[j];
  }
  // cv::fastAtan2 (about 0.3° accurate, far below the 12° bins) is 3 times faster than
  // std::atan2. Just below 360° its result may round to 360.
  const float degrees = cv::fastAtan2(static_cast<float>(m01), static_cast<float>(m10));
  return degrees < 360.f ? degrees : 0.f;
}

/// The rotated pattern closest to `degrees` (any finite value).
int angle_bin(float degrees) {
  constexpr float bin_degrees = 360.f / OrientedBrief::kAngleBins;
  const long bin = std::lround(std::fmod(degrees, 360.f) / bin_degrees) % OrientedBrief::kAngleBins;
  return static_cast<int>(bin < 0 ? bin + OrientedBrief::kAngleBins : bin);
}

/// Whether keypoint k has higher rank than l: larger Harris response, ties broken by position.
bool ranks_before(const cv::KeyPoint& k, const cv::KeyPoint& l) {
  if (k.response != l.response) return k.response > l.response;
  if (k.pt.y != l.pt.y) return k.pt.y < l.pt.y;
  return k.pt.x < l.pt.x;
}

/// The sums of `grey` over the 5×5 window around each pixel at least 2 pixels from the
/// edges (the others are left unset: described keypoints never reach them). The vertical
/// sums in `column` follow the window down, one row in and one out; both passes vectorise.
void box_sums_5x5(const cv::Mat& grey, cv::Mat& sums, std::vector<std::uint16_t>& column) {
  constexpr int r = OrientedBrief::kSubWindowRadius;
  const int rows = grey.rows, cols = grey.cols;
  CV_Assert(rows > 2 * r && cols > 2 * r);
  sums.create(grey.size(), CV_16U);
  column.assign(cols, 0);
  std::uint16_t* const col = column.data();
  for (int y = 0; y <= 2 * r; ++y) {
    const std::uint8_t* row = grey.ptr<std::uint8_t>(y);
    for (int x = 0; x < cols; ++x) col[x] = static_cast<std::uint16_t>(col[x] + row[x]);
  }
  for (int y = r;; ++y) {
    std::uint16_t* out = sums.ptr<std::uint16_t>(y);
    for (int x = r; x < cols - r; ++x)
      out[x] = static_cast<std::uint16_t>(col[x - 2] + col[x - 1] + col[x] + col[x + 1] + col[x + 2]);
    if (y + r + 1 == rows) break;
    const std::uint8_t* entering = grey.ptr<std::uint8_t>(y + r + 1);
    const std::uint8_t* leaving = grey.ptr<std::uint8_t>(y - r);
    for (int x = 0; x < cols; ++x) col[x] = static_cast<std::uint16_t>(col[x] + entering[x] - leaving[x]);
  }
}

/// The pixel a keypoint is at (its position rounded).
cv::Point pixel_of(const cv::KeyPoint& k) { return {cvFloor(k.pt.x + 0.5f), cvFloor(k.pt.y + 0.5f)}; }

/// Removes the keypoints that are too close to the border to be described (see
/// pixel_of()), not finite, or on a zero pixel of a non-empty mask.
void remove_undescribable(const cv::Size& size, const cv::Mat& mask, std::vector<cv::KeyPoint>& keypoints) {
  const int border = OrientedBrief::borderWidth();
  const float low = static_cast<float>(border) - 0.5f;
  const float high_x = static_cast<float>(size.width - border) - 0.5f;
  const float high_y = static_cast<float>(size.height - border) - 0.5f;
  auto drop = [&](const cv::KeyPoint& k) {
    // The comparisons are false for NaN.
    if (!(k.pt.x >= low && k.pt.x < high_x && k.pt.y >= low && k.pt.y < high_y) || !std::isfinite(k.angle)) return true;
    return !mask.empty() && mask.at<std::uint8_t>(pixel_of(k)) == 0;
  };
  keypoints.erase(std::remove_if(keypoints.begin(), keypoints.end(), drop), keypoints.end());
}

}  // namespace

const std::array<OrientedBrief::Pair, OrientedBrief::kPairs>& OrientedBrief::pattern() {
  static const auto pairs = make_pattern();
  return pairs;
}

int OrientedBrief::borderWidth() {
  static const int width = compute_border_width();
  return width;
}

cv::Ptr<OrientedBrief> OrientedBrief::create(int n_features, int fast_threshold) {
  return cv::makePtr<OrientedBrief>(n_features, fast_threshold);
}

OrientedBrief::OrientedBrief(int n_features, int fast_threshold)
    : n_features_(n_features), fast_threshold_(fast_threshold) {
  if (n_features < 1 || fast_threshold < 1 || fast_threshold > 254)
    throw std::invalid_argument("OrientedBrief needs n_features >= 1 and 1 <= fast_threshold <= 254");
}

void OrientedBrief::detectAndCompute(cv::InputArray image, cv::InputArray mask, std::vector<cv::KeyPoint>& keypoints,
                                     cv::OutputArray descriptors, bool useProvidedKeypoints) {
  if (image.empty()) {
    keypoints.clear();
    if (descriptors.needed()) descriptors.release();
    return;
  }
  CV_Assert(image.depth() == CV_8U);
  const cv::Mat grey = grey_image(image.getMat());
  const cv::Mat mask_image = mask.getMat();
  CV_Assert(mask_image.empty() || (mask_image.type() == CV_8UC1 && mask_image.size() == grey.size()));

  if (useProvidedKeypoints) {
    remove_undescribable(grey.size(), mask_image, keypoints);
    for (cv::KeyPoint& k : keypoints)
      if (k.angle < 0.f) k.angle = centroid_angle(grey, pixel_of(k));
  } else {
    detect_corners(grey, mask_image, keypoints);
  }
  if (!descriptors.needed()) return;
  if (keypoints.empty()) {
    descriptors.release();
    return;
  }
  describe(grey, keypoints, descriptors);
}

void OrientedBrief::detect_corners(const cv::Mat& grey, const cv::Mat& mask,
                                   std::vector<cv::KeyPoint>& keypoints) const {
  keypoints.clear();
  const int border = borderWidth();
  if (grey.cols <= 2 * border || grey.rows <= 2 * border) return;
  // FAST on the part where its corners are describable: cheaper than filtering afterwards.
  const int margin = border - kFastRadius;
  const cv::Rect inner(margin, margin, grey.cols - 2 * margin, grey.rows - 2 * margin);
  cv::FAST(grey(inner), keypoints, fast_threshold_, true, cv::FastFeatureDetector::TYPE_9_16);
  for (cv::KeyPoint& k : keypoints) k.pt += cv::Point2f(static_cast<float>(margin), static_cast<float>(margin));
  remove_undescribable(grey.size(), mask, keypoints);  // only the mask can remove corners here
  for (cv::KeyPoint& k : keypoints) k.response = harris_response(grey, pixel_of(k));
  if (keypoints.size() > static_cast<std::size_t>(n_features_)) {
    std::nth_element(keypoints.begin(), keypoints.begin() + n_features_, keypoints.end(), ranks_before);
    keypoints.resize(n_features_);
  }
  for (cv::KeyPoint& k : keypoints) {
    k.size = static_cast<float>(kPatchSize);
    k.octave = 0;
    k.angle = centroid_angle(grey, pixel_of(k));
  }
}

void OrientedBrief::update_offsets(int step) {
  if (step == offsets_step_) return;
  offsets_.resize(static_cast<std::size_t>(kAngleBins) * kPairs * 2);
  int* offset = offsets_.data();
  for (const auto& pairs : rotated_patterns())
    for (const auto& [a, b] : pairs) {
      *offset++ = a.y * step + a.x;
      *offset++ = b.y * step + b.x;
    }
  offsets_step_ = step;
}

void OrientedBrief::describe(const cv::Mat& grey, const std::vector<cv::KeyPoint>& keypoints,
                             cv::OutputArray descriptors) {
  box_sums_5x5(grey, box_sums_, column_sums_);
  update_offsets(static_cast<int>(box_sums_.step1()));
  descriptors.create(static_cast<int>(keypoints.size()), descriptorSize(), CV_8U);
  cv::Mat out = descriptors.getMat();
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    const cv::KeyPoint& k = keypoints[i];
    const cv::Point at = pixel_of(k);
    const std::uint16_t* centre = box_sums_.ptr<std::uint16_t>(at.y) + at.x;
    const int* offset = offsets_.data() + static_cast<std::size_t>(angle_bin(k.angle)) * kPairs * 2;
    std::uint8_t* bytes = out.ptr<std::uint8_t>(static_cast<int>(i));
    for (int byte = 0; byte < kPairs / 8; ++byte) {
      unsigned bits = 0;
      for (int bit = 0; bit < 8; ++bit, offset += 2) bits |= static_cast<unsigned>(centre[offset[0]] > centre[offset[1]]) << bit;
      bytes[byte] = static_cast<std::uint8_t>(bits);
    }
  }
}

}  // namespace icgp
