// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <optional>
#include <string>
#include <vector>

#include "icgp/features/hamming_matching.h"
#include "icgp/modality/measured_occlusion.h"
#include "icgp/modality/rendered_scene.h"
#include "icgp/modality/modality.h"
#include "icgp/modality/modality_params.h"
#include "icgp/modality/residual_noise.h"
#include "icgp/modality/surface_lifter.h"

namespace icgp {

/// The extractor of `descriptor` set up with `params` (FREAK and DAISY are icgp::Freak /
/// icgp::Daisy, which describe given keypoints only; oriented_brief is icgp::OrientedBrief,
/// which detects its own, orb_n_features of them).
cv::Ptr<cv::Feature2D> make_descriptor(Descriptor descriptor, const TextureParams& params = {});

/// Detects keypoints and computes their descriptors in the focused crop of a colour image
/// (paper §IV): the square `square` cut out, converted to grey and resampled to
/// focused_image_size² pixels. FREAK and DAISY describe ORB keypoints; the others detect
/// their own.
class FeatureExtractor {
 public:
  explicit FeatureExtractor(const TextureParams& params);

  /// Keypoints in full-image coordinates into `points`, one descriptor row each into
  /// `descriptors`. A square outside the image gives none.
  void extract(const cv::Mat& image, const ImageSquare& square, std::vector<cv::Point2f>& points,
               cv::Mat& descriptors);
  /// The distance descriptors are compared with (cv::NORM_HAMMING or cv::NORM_L2).
  int norm() const { return descriptor_->defaultNorm(); }

 private:
  cv::Ptr<cv::Feature2D> detector_, descriptor_;
  int size_;
  cv::Mat crop_;  ///< the colour cut-out or warp, before grey conversion
  cv::Mat grey_;  ///< the focused grey image the detector reads (never shares crop_'s buffer)
  std::vector<cv::KeyPoint> keypoints_;
};

/// Keypoints of one frame lifted onto the body surface, with their descriptors.
struct Keyframe {
  std::vector<Eigen::Vector3f> body_points;
  std::vector<cv::Point2f> image_points;  ///< where each point was detected
  cv::Mat descriptors;                    ///< one row per point
  Eigen::Matrix3d camera_R_body = Eigen::Matrix3d::Identity();
  int age = 0;  ///< frames since it was made
};

/// Keypoint-based texture modality (paper §III-C): keypoints detected once per frame in
/// the focused crop around the body are matched to the current keyframe's 3D points, and
/// the Tukey-robust reprojection error of the pairs is minimised as re-weighted least
/// squares (ALGORITHMS.md §8).
///
/// Weights: with u = (e/c)², w(e) = 1 − u + u²/3 for e ≤ c and 1 / (3u) beyond, which is
/// 2·ρ_tuk(e)/e², so that w e² = 2ρ_tuk(e) ≈ e² for small errors (σ_t is then the
/// inliers' standard deviation, and w = 1 at e = 0). Weights are recomputed from the
/// current pose at every update and held fixed in between: log_likelihood() is
/// −Σ w_i e_i² / (2σ_t²) with the weights of the last update, whose derivative is the
/// gradient, and which equals −Σ ρ_tuk(e_i) / σ_t² at the pose they were computed at.
///
/// Quality: score is the share of keyframe points matched with a reprojection error below
/// c/2 after the frame converged (0 with fewer than 4 such inliers, too few to support a
/// pose); valid_fraction the share matched at all.
///
/// Noise: σ_t is estimated in every correspondence iteration from the u and v reprojection
/// errors of all matches, clamped between the noise floor and the iteration's
/// `standard_deviations` entry (ResidualNoise).
class TextureModality : public Modality {
 public:
  /// A matched pair: a keyframe point and where the current frame sees it.
  struct Match {
    Eigen::Vector3f body_point;
    Eigen::Vector2f image_point;
    int keyframe_index;
    float weight;
  };

  TextureModality(Body& body, TextureParams params);

  std::string name() const override { return "texture"; }
  const std::string& camera() const override { return params_.color_camera; }
  /// With other bodies, a focused render of the scene at the first correspondence
  /// iteration: keyframe points other bodies hide are not expected to match. A focused
  /// render of the scene when a keyframe is due: at the start, and at a finish
  /// after the keyframe_orientation_threshold_deg rotation or keyframe_max_age frames.
  std::vector<RenderRequest> render_requests(const Frame& frame, Stage stage) const override;
  void start(const Frame& frame, const Renders& renders) override;
  void correspondences(const Frame& frame, const Renders& renders, int corr_iter) override;
  CueTerms gradient_hessian(int corr_iter, int update_iter) override;
  double log_likelihood(int corr_iter) const override;
  void append_residuals(std::vector<double>& residuals, std::vector<double>& weights) const override;
  void append_image_features(std::vector<ImageFeature>& features) const override;
  void finish(const Frame& frame, const Renders& renders) override;
  ModalityQuality quality() const override { return quality_; }
  /// Its keyframes are lifted at estimated poses, and a keyframe lifted at a wrong pose
  /// matches itself: the scatter of its residuals cannot show that error, their distance
  /// from where the other cues put the body can, less what the others' own uncertainty
  /// spreads them there.
  bool weighs_against_others() const override { return params_.noise.estimate; }
  void others_estimate(const Vec6& step, const Mat66& covariance) override {
    others_step_ = step;
    others_covariance_ = covariance;
  }

  const TextureParams& params() const { return params_; }
  const Keyframe& keyframe() const { return keyframe_; }
  const std::vector<Match>& matches() const { return matches_; }

 private:
  const ColorImage& color_image(const Frame& frame) const;
  Pose camera_T_body() const;
  void detect(const Frame& frame);
  /// Keeps only the detected points on pixels the camera's mask allows.
  void drop_masked_points(const PixelMask& mask);
  /// The render a keyframe at the current pose reads; none when the body is not in front
  /// of the camera.
  std::optional<RenderRequest> keyframe_render(const Frame& frame) const;
  bool keyframe_due(const Pose& camera_T_body, int age) const;
  void make_keyframe(const Frame& frame, const Renders& renders);
  void match();
  void update_weights();
  /// `mask`: the colour camera's, whose excluded pixels no keyframe point is expected to match in.
  void update_quality(const PixelMask& mask);
  /// σ_t, pixels, for correspondence iteration `corr_iter`.
  double sigma(int corr_iter) const;
  void estimate_noise();

  TextureParams params_;
  FeatureExtractor extractor_;
  SurfaceLifter lifter_;
  cv::BFMatcher matcher_;
  SceneCrop crop_;  ///< of the scene's render; its sphere bounds the detection crop and keyframe renders
  RenderedScene scene_;  ///< this frame's render of the scene (empty without other bodies)
  Intrinsics intrinsics_;
  Pose camera_T_reference_;
  Vec6 others_step_ = Vec6::Zero();         ///< from the pose to the other cues' (others_estimate)
  Mat66 others_covariance_ = Mat66::Zero();  ///< of the other cues' pose (others_estimate)
  std::vector<cv::Point2f> points_;  ///< current frame's keypoints, full image
  cv::Mat descriptors_;
  std::vector<std::vector<cv::DMatch>> knn_;  ///< cv::BFMatcher's answer (L2 descriptors)
  std::vector<TwoNearest> nearest_;
  Keyframe keyframe_;
  std::vector<Match> matches_;
  ResidualNoise noise_;
  int last_corr_iter_ = 0;
  int frames_since_start_ = 0;
  ModalityQuality quality_;
};

}  // namespace icgp
