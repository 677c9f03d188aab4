// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <array>
#include <cstdint>
#include <opencv2/features2d.hpp>
#include <utility>
#include <vector>

namespace icgp {

/// An ORB-style detector and binary descriptor, written from the papers: Rublee, Rabaud,
/// Konolige, Bradski, "ORB: an efficient alternative to SIFT or SURF", ICCV 2011, and, for
/// the test pattern, Calonder, Lepetit, Strecha, Fua, "BRIEF: Binary Robust Independent
/// Elementary Features", ECCV 2010. Made for the texture modality's focused crop, where it
/// does cv::ORB's work (one level, 300 features) in about a third of the time: 0.14 ms
/// against 0.41 ms on a 200×200 crop of the teabox sequence, one thread.
///
/// Detection (oFAST): FAST-9 corners (cv::FAST, non-maximum suppression) above
/// fast_threshold, only where the whole descriptor pattern and the orientation disk fit in
/// the image in every orientation (borderWidth() pixels from each edge). They are ranked by
/// the Harris response det(M) - 0.04 trace(M)², M the sum of the gradient's outer products
/// over a 7×7 window, gradients by central differences; the n_features best are kept (ties
/// by position, so the choice does not depend on the detector's order). Harris is computed
/// at the candidates only, not as a filter over the whole image.
///
/// Orientation: the intensity centroid of the disk of radius 15 around the keypoint (pixel
/// centres within 15 px): angle = atan2(m01, m10) (by cv::fastAtan2, within 0.3°), written
/// to KeyPoint::angle in degrees in [0, 360), cv::KeyPoint's convention (from +x towards +y
/// in image axes).
///
/// Descriptor (steered BRIEF): 256 tests, bit b in byte b / 8 at position b % 8 (least
/// significant first); test b is 1 when the 5×5 sub-window around the first point of
/// pair b is brighter than the one around the second. Sub-windows are compared by their
/// exact sums, which orders them as their means do (a mean image rounded to 8 bits, as
/// cv::blur makes, would add ties), read from one image of 5×5 box sums made per call
/// (running sums, several times faster than cv::blur here), so a test is two loads and a
/// compare. The pairs (pattern()) are BRIEF's G II: coordinates i.i.d. Gaussian with
/// σ = 31/5 around the keypoint, rounded to pixels and redrawn beyond |x|, |y| <= 13 so
/// that the sub-windows stay in the 31×31 patch. They are steered by the keypoint's angle
/// rounded to the nearest of 30 bins of 12°, from 30 precomputed rotated copies.
///
/// Deviations from the paper, and why:
///  - Single scale, no pyramid: the focused crop already brings the object to a fixed
///    scale, and one level is what the tracker ran cv::ORB with. Keypoints get size 31 and
///    octave 0.
///  - Steered BRIEF, not the learned rBRIEF: the paper learns its 256 tests on 300 000
///    keypoints of PASCAL 2006 images, a training set not reproduced here. As the paper
///    shows, steered BRIEF's bits are less balanced and more correlated than rBRIEF's,
///    which makes unrelated descriptors closer.
///  - The pattern is drawn from a generator written in oriented_brief.cpp (splitmix64 and
///    Box–Muller) rather than the standard library's distributions, whose output differs
///    between implementations.
///
/// Input: 8-bit grey, BGR or BGRA images (the latter converted to grey). A non-empty mask
/// drops the keypoints on its zero pixels. With useProvidedKeypoints the given keypoints
/// are described instead (those too close to the border or not finite are dropped): with
/// their own angle, or, when it is negative (cv::KeyPoint's default -1, "not set"), with
/// the intensity centroid's, which is then written to the keypoint.
///
/// Scratch buffers are kept as members, so the steady state (grey crops of the same width)
/// allocates only what cv::FAST and the output arrays do; an instance is therefore not
/// thread-safe: use one per thread.
class OrientedBrief : public cv::Feature2D {
 public:
  static constexpr int kPatchSize = 31;
  static constexpr int kPairs = 256;
  static constexpr int kAngleBins = 30;
  static constexpr int kSubWindowRadius = 2;  ///< 5×5 sub-windows
  static constexpr int kPatternRadius = kPatchSize / 2 - kSubWindowRadius;  ///< |x|, |y| <= 13
  static constexpr int kOrientationRadius = 15;
  static constexpr int kHarrisRadius = 3;  ///< 7×7 window
  static constexpr float kHarrisK = 0.04f;

  /// The two test points of a pair, offsets from the keypoint in pixels (unrotated).
  using Pair = std::pair<cv::Point, cv::Point>;

  /// n_features >= 1 and 1 <= fast_threshold <= 254; throws std::invalid_argument otherwise.
  static cv::Ptr<OrientedBrief> create(int n_features = 300, int fast_threshold = 20);

  OrientedBrief(int n_features, int fast_threshold);

  void detectAndCompute(cv::InputArray image, cv::InputArray mask, std::vector<cv::KeyPoint>& keypoints,
                        cv::OutputArray descriptors, bool useProvidedKeypoints = false) override;

  int descriptorSize() const override { return kPairs / 8; }
  int descriptorType() const override { return CV_8U; }
  int defaultNorm() const override { return cv::NORM_HAMMING; }
  cv::String getDefaultName() const override { return "icgp.OrientedBrief"; }

  /// The 256 unrotated test pairs (BRIEF's G II, fixed seed).
  static const std::array<Pair, kPairs>& pattern();

  /// The least distance, in pixels, between a described keypoint and the image edge
  /// (keypoint at pixel x needs borderWidth() <= x <= cols - 1 - borderWidth()): the reach
  /// of the rotated tests plus their sub-window, of the orientation disk, and of Harris.
  static int borderWidth();

 private:
  void detect_corners(const cv::Mat& grey, const cv::Mat& mask, std::vector<cv::KeyPoint>& keypoints) const;
  void describe(const cv::Mat& grey, const std::vector<cv::KeyPoint>& keypoints, cv::OutputArray descriptors);
  void update_offsets(int step);

  int n_features_;
  int fast_threshold_;
  cv::Mat box_sums_;                        ///< CV_16U, 5×5 sums of the grey image
  std::vector<std::uint16_t> column_sums_;  ///< one row of vertical 5-pixel sums, for box_sums_
  std::vector<int> offsets_;                ///< kAngleBins × kPairs × 2 rotated test points, in box_sums_ elements
  int offsets_step_ = 0;                    ///< the row step (in elements) offsets_ was made for
};

}  // namespace icgp
