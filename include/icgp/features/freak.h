// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <array>
#include <cstdint>
#include <opencv2/features2d.hpp>
#include <utility>
#include <vector>

namespace icgp {

/// The FREAK binary descriptor (Alahi, Ortiz, Vandergheynst, "FREAK: Fast Retina Keypoint",
/// CVPR 2012), written from the paper, for keypoints of another detector (ORB's in ICG+).
///
/// Retinal pattern: 43 receptive fields, a centre and 7 rings of 6. Ring k (0 = outermost)
/// has radius q^k (q = 2/3) times the outer radius, and odd rings are turned by 30° so that
/// each field sits between two of the next ring, as in the paper's figure. A field's size
/// grows with its ring's radius like the retina's: it is the mean over a square of half
/// side r_k / 2 (a box stand-in for the paper's Gaussian, read from an integral image), so
/// fields overlap their neighbours. Squares stay axis-aligned when the pattern turns;
/// their corners are bilinear in the integral image, which makes a field's mean the exact
/// area average over the square even at sub-pixel positions.
///
/// Orientation (orientation_normalized): the paper's local-gradient sum over 45 pairs,
/// O = Σ (I_a - I_b) (P_a - P_b) / |P_a - P_b|, on the unturned pattern. The pairs join
/// the fields of each of the 5 outer rings that are 120° or 180° apart (9 per ring); each
/// ring's set is invariant under its 60° turns, so for a linear ramp O points exactly
/// along the gradient, with no preferred direction. The pattern is then turned by
/// atan2(O_y, O_x), which is also written to the keypoint's angle (degrees, cv::KeyPoint's
/// convention: from +x towards +y).
///
/// Descriptor: bit b is 1 when field a_b is brighter than field c_b (I_a - I_c > 0), for
/// the 512 pairs of descriptorPairs(), stored byte b / 8, bit b % 8 (least significant
/// first). The paper learns its pairs on 50 000 keypoints (high variance, low
/// correlation); without such a set they are chosen by a fixed rule, see descriptorPairs().
///
/// Scale (scale_normalized): a keypoint of size kReferenceKeypointSize (ORB's on its finest
/// level) gets an outer ring of radius pattern_scale pixels; other sizes scale the pattern
/// with size / kReferenceKeypointSize. Scales from 1/2 to 2^n_octaves / 2 are covered;
/// sizes beyond are described at the nearest covered scale. Without scale normalisation
/// every keypoint gets the reference pattern.
///
/// Borders: keypoints whose pattern does not fit in the image at their scale (in any
/// orientation) are removed from the list, as cv::Feature2D::compute allows.
class Freak : public cv::Feature2D {
 public:
  static constexpr int kRings = 7;
  static constexpr int kFieldsPerRing = 6;
  static constexpr int kFields = kRings * kFieldsPerRing + 1;  ///< the centre is the last field
  static constexpr int kPairs = 512;
  static constexpr int kCascades = 4;  ///< of kPairs / kCascades pairs each, coarse to fine
  static constexpr float kReferenceKeypointSize = 31.f;

  /// One receptive field of the unturned pattern at unit outer radius.
  struct Field {
    cv::Point2f offset;
    float half_size;  ///< half the side of the square whose mean is the field's intensity
    int ring;         ///< 0 (outermost) .. kRings - 1, kRings for the centre
  };
  using Pair = std::pair<std::uint8_t, std::uint8_t>;  ///< indices into pattern()

  /// pattern_scale > 0 and n_octaves >= 1; throws std::invalid_argument otherwise.
  static cv::Ptr<Freak> create(bool orientation_normalized = true, bool scale_normalized = true,
                               float pattern_scale = 22.0f, int n_octaves = 4);

  Freak(bool orientation_normalized, bool scale_normalized, float pattern_scale, int n_octaves);

  /// Describes the given keypoints only (useProvidedKeypoints must be true); keypoints
  /// outside a non-empty mask are dropped too. Accepts 1-, 3- or 4-channel (BGR, BGRA)
  /// images of depth 8U, 16U or 32F; descriptors get one 64-byte row per kept keypoint.
  void detectAndCompute(cv::InputArray image, cv::InputArray mask, std::vector<cv::KeyPoint>& keypoints,
                        cv::OutputArray descriptors, bool useProvidedKeypoints = false) override;

  int descriptorSize() const override { return kPairs / 8; }
  int descriptorType() const override { return CV_8U; }
  int defaultNorm() const override { return cv::NORM_HAMMING; }
  cv::String getDefaultName() const override { return "icgp.Freak"; }

  static const std::array<Field, kFields>& pattern();

  /// The 512 descriptor pairs, coarse to fine (the paper's first cascades compare mostly
  /// peripheral fields, the last the fovea). A fixed rule stands in for the paper's
  /// learning (keep high-variance pairs, drop those correlated with pairs already kept):
  /// (1) Candidates are the pairs whose rings differ by at most 2, the centre counting as
  /// ring 7. With 3 or more rings between them (radius ratio q^3 ≈ 0.3), the inner ring
  /// is small and close to the centre next to the outer field's distance and size, so the
  /// outer field's bits against its 6 fields (and the centre) are nearly the same bit:
  /// the correlated pairs the paper's filter removes. That leaves 513 pairs.
  /// (2) They are sorted by the sum of their two rings (outer = coarse first), ties by ring
  /// difference (wider first) then by field index, and the first 512 kept; the one left
  /// out is the finest of all (the centre against ring 6). The 4 cascades of 128 then
  /// cover ring sums 0-3, 3-6, 6-9 and 9-13, and every field takes part.
  /// Not reproduced: the learned pairs' avoidance of biased bits. After orientation
  /// normalisation a pair stretched along the gradient (the pattern's x) is mostly 1 or
  /// mostly 0, so unrelated descriptors differ in about 30 % of the bits, not 50 %.
  static const std::array<Pair, kPairs>& descriptorPairs();

 private:
  void describe(const cv::Mat& sums, cv::KeyPoint& keypoint, std::uint8_t* descriptor) const;
  float scale_of(const cv::KeyPoint& keypoint) const;

  bool orientation_normalized_;
  bool scale_normalized_;
  float pattern_scale_;
  float min_scale_, max_scale_;
};

}  // namespace icgp
