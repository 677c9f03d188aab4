// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "icgp/geometry/mesh_edges.h"
#include "icgp/modality/modality.h"
#include "icgp/modality/modality_params.h"
#include "icgp/modality/residual_noise.h"

namespace icgp {

/// Edge cue (ViSP's moving edges, in ICG+'s Newton step): the model's visible creases are
/// sampled along their projection, and each sample looks along its image normal for the
/// step of brightness that best explains it: the strongest smoothed gradient across the
/// crease, discounted by its distance from the prediction. Samples are fused as point-to-line
/// distances, with Tukey weights on the distances' estimated scale (ResidualNoise).
///
/// The region cue sees the silhouette through colour statistics; where the object and its
/// background have alike colours, or the object is many-coloured, the creases between its
/// faces still show as the strongest gradients of the image.
///
/// Which samples are visible is decided at the predicted pose of a frame: creases with a face
/// towards the camera, and, when the body may hide parts of itself (not convex) or another
/// body may cover it, the samples a focused render shows unhidden. They are kept from frame to
/// frame until the camera has moved around the body by EdgeParams::resample_angle_deg, so
/// that a render is rarely needed on smooth motion. Each crease keeps
/// the sign of its step from frame to frame (its polarity), and each sample the size of its
/// step too, as moving edges keep their contrast: a sample then takes the step that looks
/// like its crease's, not the strongest texture or clutter nearby.
///
/// Quality: score is the share of visible samples matched with a non-zero robust weight,
/// valid_fraction the share matched at all. The cue abstains with fewer than
/// EdgeParams::min_points visible samples.
class EdgeModality : public Modality {
 public:
  /// A visible sample of a crease and, once matched, where the image shows it.
  struct Sample {
    Eigen::Vector3f body_point;
    Eigen::Vector3f body_direction;  ///< unit, along the crease
    int edge = 0;                    ///< index of its crease
    Eigen::Vector2f normal;          ///< unit image normal at the last search
    Eigen::Vector2f found;           ///< the matched step of brightness (when matched)
    float polarity = 0.f;            ///< sign of the matched gradient along the normal; 0: unmatched
    float step = 0.f;                ///< the matched gradient along the normal, grey levels per pixel
    /// The step it matched at the last converged pose with a non-zero weight (0: none yet):
    /// the next frame looks for a step of that sign and about that size.
    float contrast = 0.f;
    float weight = 0.f;              ///< robust weight; 0 when unmatched
    /// Its last search ran inside the image and the mask: the camera could see it, so the
    /// quality counts it.
    bool seen = false;
  };

  /// `color_camera` is the camera the creases are looked for in.
  EdgeModality(Body& body, EdgeParams params, std::string color_camera);

  std::string name() const override { return "edge"; }
  const std::string& camera() const override { return color_camera_; }
  /// The render that decides the visible samples, at the first correspondence iteration,
  /// when the body is not convex or another body may cover it.
  std::vector<RenderRequest> render_requests(const Frame& frame, Stage stage) const override;
  void start(const Frame& frame, const Renders& renders) override;
  void correspondences(const Frame& frame, const Renders& renders, int corr_iter) override;
  CueTerms gradient_hessian(int corr_iter, int update_iter) override;
  double log_likelihood(int corr_iter) const override;
  void append_residuals(std::vector<double>& residuals, std::vector<double>& weights) const override;
  void append_image_features(std::vector<ImageFeature>& features) const override;
  void finish(const Frame& frame, const Renders& renders) override;
  ModalityQuality quality() const override { return quality_; }

  const EdgeParams& params() const { return params_; }
  const std::vector<Sample>& samples() const { return samples_; }

 private:
  const ColorImage& color_image(const Frame& frame) const;
  Pose camera_T_body() const;
  std::optional<RenderRequest> visibility_render(const ColorImage& color) const;
  /// The smoothed brightness gradient over the square around the body, with room for the
  /// widest search.
  void compute_gradient(const ColorImage& color);
  /// Whether the camera moved around the body enough since the samples were chosen that
  /// others may show (EdgeParams::resample_angle_deg).
  bool resampling_due(const Pose& camera_T_body) const;
  /// Samples the creases visible at the current pose (`render`, if any, hides samples).
  void sample_creases(const FocusedRender* render);
  /// The gradient (du, dv) at image point `x`, bilinear; nullopt outside the computed region.
  std::optional<Eigen::Vector2f> gradient_at(const Eigen::Vector2f& x) const;
  /// Looks for each sample's step of brightness along its normal within `range` pixels,
  /// where `mask` lets it.
  void match(const PixelMask& mask, int range, double prior_sigma);
  /// n·(π(T X) − x_found) of a matched sample: its distance from the matched step along
  /// the normal it was matched on.
  float residual(const Sample& s, const Posef& camera_T_body) const;
  /// Each matched sample with a weight keeps its step (Sample::contrast); each crease the
  /// sign its samples' weighted steps agree on.
  void learn_contrasts();
  void update_weights(int corr_iter);
  double sigma(int corr_iter) const;

  EdgeParams params_;
  std::string color_camera_;
  std::vector<MeshEdge> creases_;
  bool convex_;
  Sphere sphere_;
  Intrinsics intrinsics_;
  Pose camera_T_reference_;
  cv::Mat gradient_u_, gradient_v_;  ///< CV_16SC1 Sobel derivatives over gradient_region_
  cv::Rect gradient_region_;
  std::vector<Sample> samples_;
  bool sampled_ = false;
  Eigen::Vector3d sampled_from_;  ///< the camera's centre in the body frame when samples_ were chosen
  /// Per crease: the sign of its step of brightness along the image normal that points to
  /// the crease's first end's left (0: not yet known).
  std::vector<float> polarity_;
  ResidualNoise noise_;
  int last_corr_iter_ = 0;
  ModalityQuality quality_;
  cv::Mat scratch_grey_;
  std::vector<float> scratch_along_;  ///< match(): the gradient across one sample's search line
};

}  // namespace icgp
