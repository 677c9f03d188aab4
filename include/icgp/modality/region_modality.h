// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "icgp/modality/color_histograms.h"
#include "icgp/modality/measured_occlusion.h"
#include "icgp/modality/modality.h"
#include "icgp/modality/modality_params.h"
#include "icgp/modality/rendered_scene.h"
#include "icgp/modality/residual_noise.h"
#include "icgp/modality/view_selector.h"
#include "icgp/model/viewpoint_model.h"

namespace icgp {

/// Colour-statistics contour alignment along sparse correspondence lines (SRT3D/ICG's
/// region modality, ALGORITHMS.md §4, §7).
///
/// Sub-pixel conventions, which decide the modality's bias: pixel (j, i) has its centre
/// at (u, v) = (j, i); a correspondence line samples whole pixels along its dominant axis,
/// and the offset Δr between the projected contour point and the centre of the sampled
/// pixels (measured along the normal) is carried into every later residual, so no
/// rounding ever shifts the estimated contour.
///
/// Noise: a line's pixel residual (projected minus most likely contour location) has the
/// variance σ_r²·σ_d²/σ_min²; σ_r is estimated in every correspondence iteration from the
/// residuals scaled by σ_min/σ_d, clamped between the noise floor and the iteration's
/// `standard_deviations` entry (ResidualNoise).
class RegionModality : public Modality {
 public:
  /// What the region model covers: the whole body, or one colour region of a multi-region
  /// body (paper §III-D), whose contour may border the body's other regions.
  enum class Extent { kWholeBody, kRegionOfBody };

  RegionModality(Body& body, std::shared_ptr<const ViewpointModel> model, RegionParams params,
                 Extent extent = Extent::kWholeBody);

  std::string name() const override { return "region"; }
  const std::string& camera() const override { return params_.color_camera; }
  /// With other bodies: a focused render of the scene at the first correspondence iteration
  /// (modeled occlusions, region checking).
  std::vector<RenderRequest> render_requests(const Frame& frame, Stage stage) const override;
  void start(const Frame& frame, const Renders& renders) override;
  void correspondences(const Frame& frame, const Renders& renders, int corr_iter) override;
  CueTerms gradient_hessian(int corr_iter, int update_iter) override;
  double log_likelihood(int corr_iter) const override;
  void append_residuals(std::vector<double>& residuals, std::vector<double>& weights) const override;
  void append_image_features(std::vector<ImageFeature>& features) const override;
  void finish(const Frame& frame, const Renders& renders) override;
  ModalityQuality quality() const override { return quality_; }

  const RegionParams& params() const { return params_; }
  /// The region viewpoint model (the detector's templates are its contour points).
  const ViewpointModel& model() const { return *model_; }

 private:
  /// A model contour point projected at the current pose.
  struct ProjectedPoint {
    Eigen::Vector2f centre;  ///< pixels
    Eigen::Vector2f normal;  ///< unit image direction, from the object outwards
    float depth;             ///< Z in the colour camera
    float foreground_px, background_px;
  };
  struct Line {
    Eigen::Vector3f body_point;
    Eigen::Vector2f centre;
    Eigen::Vector2f normal;
    float delta_r;        ///< sampled line centre minus projected point, along normal (px)
    float normal_factor;  ///< n̄ = |n_dominant| / scale: pixels along the normal -> segments
    float mean;           ///< μ of the contour-location distribution (segments)
    float variance;       ///< σ_d², clamped below by σ_min²
    float residual = 0.f;  ///< normalised_residual() at the pose of the correspondence search
    float weight = 1.f;    ///< robust weight of this correspondence pass (ResidualNoise::weight)
  };

  const ColorImage& color_image(const Frame& frame) const;
  bool project(const ModelPoint& point, const Posef& camera_T_body, const Intrinsics& k, ProjectedPoint& out) const;
  /// True when a measured depth hides the point (only when occlusion tests are active).
  bool hidden(const Frame& frame, const Eigen::Vector3f& body_point, const float* depth_offsets) const;
  /// True when the frame's render of the scene shows the point hidden by another body, or
  /// (region checking) its contour off the body's silhouette.
  bool ruled_out_by_scene(const ModelPoint& point, const Posef& camera_T_body, const float* depth_offsets) const;
  /// Counts foreground/background pixels along every visible line at the current pose.
  void count_line_pixels(const Frame& frame);
  /// Samples the line in scale space and fills its segment posteriors; false if it leaves the image.
  bool sample_segments(const cv::Mat& image, const ProjectedPoint& p, int scale, Line& line);
  /// A line's pixels: whole steps along the dominant axis, the other coordinate in 16.16
  /// fixed point (its integer part is the pixel's row or column).
  static constexpr int kFixedBits = 16;
  static constexpr float kFixedOne = 1 << kFixedBits;
  struct PixelWalk {
    const std::uint8_t* pixel;  ///< on the other axis' row or column 0
    std::ptrdiff_t dom_step;
    std::ptrdiff_t other_stride;
    std::int32_t other, other_step;
  };
  /// segment_f_ of the n_segments_ · scale pixels of `walk`, for images of kChannels channels.
  template <int kChannels>
  void segment_posteriors(PixelWalk walk, int scale);
  /// The line's contour posterior, its mean and variance, and its log when
  /// `log_distribution` is not null.
  void compute_distribution(Line& line, float* distribution, float* log_distribution) const;
  float line_position(const Line& line, const Posef& camera_T_body, const Intrinsics& k) const;
  void update_quality();
  /// σ_r, pixels, for correspondence iteration `corr_iter`.
  double sigma(int corr_iter) const;
  /// The line's residual (projected contour minus most likely contour location) in pixels,
  /// scaled by σ_min/σ_d: in units of σ_r for every line.
  float normalised_residual(const Line& line, const Posef& camera_T_body) const;
  /// Estimates the lines' noise and sets their robust weights for correspondence iteration
  /// `corr_iter` (ResidualNoise).
  void weigh_lines(const Posef& camera_T_body, int corr_iter);
  Posef camera_T_body(const ColorImage& image) const;

  std::shared_ptr<const ViewpointModel> model_;
  RegionParams params_;
  MeasuredOcclusion occlusion_;
  int occlusion_offset_index_;
  int modeled_offset_index_;  ///< depth offsets for the modeled-occlusion radius
  Extent extent_;
  SceneCrop crop_;  ///< of the scene's render
  RenderedScene scene_;  ///< this frame's render of the scene (empty without other bodies)
  std::optional<ColorHistograms> histograms_;
  /// False while a region of a body has not been seen since the start (it abstains).
  bool histograms_learnt_ = false;
  /// Smoothed step at the segment centres as h_b and h_f − h_b, so that a segment's term
  /// h_f P_f + h_b (1 − P_f) is one multiply-add.
  std::vector<float> step_b_, step_difference_;
  float min_variance_;                  ///< σ_min²
  int n_segments_;                      ///< function_length + distribution_length − 1

  Intrinsics intrinsics_;                 ///< of the colour camera at the last correspondences
  Posef camera_T_reference_;
  ViewSelector view_selector_;
  std::vector<Line> lines_;
  ResidualNoise noise_;
  ViewOcclusions occlusions_;  ///< measured
  ViewOcclusions ruled_out_;   ///< by the scene's render (ruled_out_by_scene)
  std::vector<float> distributions_;      ///< distribution_length per line
  std::vector<float> log_distributions_;  ///< their logs, after the global iterations
  // update_quality's per-line buffers, kept to spare an allocation each frame: the mass up
  // to each segment, where the contour projects, and its move per pixel of image shift.
  std::vector<float> cumulative_mass_;
  std::vector<float> contour_positions_;
  std::vector<Eigen::Vector2f> segments_per_pixel_;
  std::vector<float> segment_f_;          ///< scratch: segment foreground posteriors
  int n_considered_ = 0;
  /// Of those, the lines the model's geometry allows at the current pose (projected in
  /// front of the camera, foreground and background runs long enough) and the camera sees
  /// (inside the image and its mask): what the data may confirm or contradict.
  int n_measurable_ = 0;
  int last_corr_iter_ = 0;
  int frames_since_start_ = 0;
  ModalityQuality quality_;
};

}  // namespace icgp
