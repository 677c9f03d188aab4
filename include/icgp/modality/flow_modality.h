// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "icgp/modality/frame_pyramids.h"
#include "icgp/modality/modality.h"
#include "icgp/modality/modality_params.h"
#include "icgp/modality/rendered_scene.h"
#include "icgp/modality/residual_noise.h"
#include "icgp/modality/surface_lifter.h"

namespace icgp {

/// Flow cue (ViSP's KLT tracker, in ICG+'s Newton step): Shi–Tomasi corners found on the
/// body are lifted onto its surface at the pose they were found at, tracked from frame to
/// frame with pyramidal Lucas–Kanade, and their reprojection errors are minimised with
/// Tukey weights on the errors' estimated scale (ResidualNoise).
///
/// Where the texture cue matches keypoints to a keyframe, which re-anchors after large
/// motion, the flow follows a few hundred corners with sub-pixel precision on smooth
/// motion: the two complement each other, as ViSP's KLT complements its moving edges.
///
/// Points are dropped when the flow fails, when tracking them back does not return them
/// (forward–backward check), when they leave the image or the camera's mask, and when
/// their surface turns away from the camera. Corners are found anew, in a focused render of
/// the scene at the converged pose, when too few survive or the body has turned since
/// (FlowParams::renew_fraction, renew_rotation_deg), and after an image of another size.
///
/// Quality: score is the share of the corners lifted at the last renewal that are still
/// followed with a non-zero robust weight, valid_fraction the share followed at all. The
/// cue abstains on the frame it starts on (its corners were lifted at the pose it would
/// judge) and with fewer than FlowParams::min_points corners.
class FlowModality : public Modality {
 public:
  /// A tracked corner: its body point and where the current frame shows it.
  struct Match {
    Eigen::Vector3f body_point;
    Eigen::Vector3f body_normal;  ///< zero when unknown (the corner was lifted at a crease)
    Eigen::Vector2f image_point;
    float weight = 1.f;
  };

  /// `color_camera` is the camera the corners are tracked in; `depth_camera` (may be empty)
  /// measures their occlusions when they are lifted.
  FlowModality(Body& body, FlowParams params, std::string color_camera, std::string depth_camera);

  std::string name() const override { return "flow"; }
  const std::string& camera() const override { return color_camera_; }
  /// A focused render of the scene where corners are found: at the start, and at a finish
  /// when they are due for renewal.
  std::vector<RenderRequest> render_requests(const Frame& frame, Stage stage) const override;
  void start(const Frame& frame, const Renders& renders) override;
  void correspondences(const Frame& frame, const Renders& renders, int corr_iter) override;
  CueTerms gradient_hessian(int corr_iter, int update_iter) override;
  double log_likelihood(int corr_iter) const override;
  void append_residuals(std::vector<double>& residuals, std::vector<double>& weights) const override;
  void append_image_features(std::vector<ImageFeature>& features) const override;
  void finish(const Frame& frame, const Renders& renders) override;
  ModalityQuality quality() const override { return quality_; }

  const FlowParams& params() const { return params_; }
  const std::vector<Match>& matches() const { return matches_; }

 private:
  const ColorImage& color_image(const Frame& frame) const;
  Pose camera_T_body() const;
  /// Makes `color` the current frame; false when its size differs from the last one's (the
  /// points then cannot be followed).
  bool load_image(const ColorImage& color);
  /// Where the body can be in the image at its current pose: the square around its sphere.
  cv::Rect body_region() const;
  void track_points(const PixelMask& mask);
  void drop_turned_away_points();
  bool renewal_due() const;
  std::optional<RenderRequest> corner_render(const Frame& frame) const;
  /// Finds corners on the body in the current image and lifts them at the current pose.
  void renew_points(const Frame& frame, const Renders& renders);
  cv::Mat body_mask(const FocusedRender& render, std::uint8_t body_id, const cv::Rect& roi) const;
  void update_weights(int corr_iter);
  double sigma(int corr_iter) const;
  double scale(int corr_iter) const;

  FlowParams params_;
  std::string color_camera_, depth_camera_;
  SurfaceLifter lifter_;
  Sphere sphere_;  ///< the body's bounding sphere: where corners are looked for
  Intrinsics intrinsics_;
  Pose camera_T_reference_;
  FramePyramids frames_;
  std::vector<Match> matches_;
  /// Points at the last renewal; kNeverLifted while the body was never in front of the camera.
  static constexpr int kNeverLifted = -1;
  int n_lifted_ = kNeverLifted;
  /// Of those, points followed out of the image or the mask, or turned away from the
  /// camera, since: no longer expected to match, so not counted against the score.
  int n_out_of_view_ = 0;
  Eigen::Matrix3d camera_R_body_at_renewal_ = Eigen::Matrix3d::Identity();
  bool size_changed_ = false;
  ResidualNoise noise_;
  int last_corr_iter_ = 0;
  int frames_since_start_ = 0;
  ModalityQuality quality_;
  std::vector<cv::Point2f> scratch_from_, scratch_to_, scratch_back_;
  std::vector<unsigned char> scratch_status_, scratch_back_status_;
  std::vector<float> scratch_error_;
};

}  // namespace icgp
