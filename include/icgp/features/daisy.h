// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <opencv2/features2d.hpp>
#include <vector>

namespace icgp {

/// The DAISY descriptor (Tola, Lepetit, Fua, TPAMI 2010) for sparse keypoints, e.g. ORB's.
///
/// For H orientations o the orientation maps G_o = max(∂I/∂o, 0) (∂I/∂o = cos·I_x + sin·I_y,
/// central differences) are smoothed with Gaussians and sampled at a grid of 1 + Q·T points:
/// the keypoint itself and Q rings of T points at radii R_i = R·i/Q (i = 1..Q). A point on
/// ring i is smoothed with σ_i = R_i / 2 = R·i/(2Q) (the paper's Σ_i = R(i+1)/(2Q) with its
/// i counted from 0), the centre with σ_1. Each of the 1 + Q·T histograms of H values is
/// normalised to unit L2 norm (the paper's "partial" normalisation); a histogram with no
/// gradient at all stays zero.
///
/// Angles follow cv::KeyPoint: measured from +x towards +y in image axes. Ring point j and
/// orientation bin o lie at the angles 2πj/T and 2πo/H, plus the keypoint angle when
/// use_keypoint_orientation is on (and the keypoint has one, angle >= 0).
///
/// As in the paper, the smoothed maps are dense: one incremental convolution per distinct σ
/// serves every keypoint (for ORB's 300 keypoints in a 200×200 crop about 9× faster than
/// Gaussian sums in a window around each keypoint), with the resolution halved once σ
/// allows it; histograms are read by bilinear interpolation. A keypoint's σ's use its scale
/// rounded to 1/16 octave. For any keypoint angle the bins come from H + 2 smoothed maps
/// (∂I/∂x, ∂I/∂y and |∂I/∂t| at t = πn/H) rather than from H rotated ones, as
/// max(D, 0) = (D + |D|) / 2: exact at multiples of 180°/H, close in between (see daisy.cpp).
///
/// Borders: there is no gradient outside the image, and grid points beyond the border read
/// the smoothed maps at the nearest border pixel. Keypoints whose centre is outside the
/// image (or not finite) are removed from the list, as cv::Feature2D::compute allows;
/// keypoint sizes beyond the image are capped.
class Daisy : public cv::Feature2D {
 public:
  /// With use_keypoint_scale, a keypoint of this size (ORB's on its finest level) is
  /// described with `radius`; others scale the grid and the σ's by size / this.
  static constexpr float kReferenceKeypointSize = 31.f;

  /// One histogram of the descriptor: where it is sampled relative to the keypoint (for
  /// angle 0 and the reference size) and the σ of the Gaussian that smooths it.
  struct GridPoint {
    cv::Point2f offset;
    float sigma;
  };

  /// radius R > 0, rings Q >= 1, histograms_per_ring T >= 1, orientations H >= 1;
  /// throws std::invalid_argument otherwise. The defaults are the paper's (200 floats).
  static cv::Ptr<Daisy> create(float radius = 15.f, int rings = 3, int histograms_per_ring = 8, int orientations = 8,
                               bool use_keypoint_orientation = true, bool use_keypoint_scale = true);

  Daisy(float radius, int rings, int histograms_per_ring, int orientations, bool use_keypoint_orientation,
        bool use_keypoint_scale);

  /// Describes the given keypoints only (useProvidedKeypoints must be true; the mask is
  /// not used). Accepts 1-, 3- or 4-channel 8-bit, 16-bit or float images; descriptors
  /// get one CV_32F row per kept keypoint.
  void detectAndCompute(cv::InputArray image, cv::InputArray mask, std::vector<cv::KeyPoint>& keypoints,
                        cv::OutputArray descriptors, bool useProvidedKeypoints = false) override;

  int descriptorSize() const override { return static_cast<int>(grid_.size()) * orientations_; }
  int descriptorType() const override { return CV_32F; }
  int defaultNorm() const override { return cv::NORM_L2; }
  cv::String getDefaultName() const override { return "icgp.Daisy"; }

  /// The histograms in descriptor order: centre, then ring 1..Q, each ring by j = 0..T-1.
  const std::vector<GridPoint>& grid() const { return grid_; }

 private:
  float radius_;
  int orientations_;
  bool use_keypoint_orientation_;
  bool use_keypoint_scale_;
  std::vector<GridPoint> grid_;
};

}  // namespace icgp
