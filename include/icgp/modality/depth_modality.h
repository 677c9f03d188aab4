// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <memory>
#include <opencv2/core/types.hpp>
#include <optional>
#include <vector>

#include "icgp/modality/dense_depth_sampling.h"
#include "icgp/modality/depth_correspondence.h"
#include "icgp/modality/measured_occlusion.h"
#include "icgp/modality/rendered_scene.h"
#include "icgp/modality/modality.h"
#include "icgp/modality/modality_params.h"
#include "icgp/modality/residual_noise.h"
#include "icgp/modality/view_selector.h"
#include "icgp/model/viewpoint_model.h"

namespace icgp {

/// Point-to-plane alignment of the body's surface with the measured points of a depth
/// camera: sparse model points paired with their closest measurements (ICG's depth
/// modality, ALGORITHMS.md §5, §7), or, dense, every sampled pixel where a render shows
/// the body paired with the surface seen there (docs/configuration.md, dense depth).
///
/// Noise: a point's standard deviation is σ·Z (σ in metres at 1 m). σ is estimated in every
/// correspondence iteration from the point-to-plane residuals divided by Z, clamped between
/// the noise floor and the iteration's `standard_deviations` entry (ResidualNoise).
class DepthModality : public Modality {
 public:
  /// Where the correspondences come from.
  enum class Sampling {
    kModelPoints,  ///< the depth viewpoint model's sparse points
    kDense,        ///< the render's pixel lattice (DenseDepthSampling with params.dense)
  };
  DepthModality(Body& body, std::shared_ptr<const ViewpointModel> model, DepthParams params,
                Sampling sampling = Sampling::kModelPoints);

  std::string name() const override { return "depth"; }
  const std::string& camera() const override { return params_.depth_camera; }
  /// Model points, with other bodies and model_occlusions: a focused render of the scene in
  /// the depth camera at the first correspondence iteration. Dense: the render of the
  /// sampling lattice in every correspondence iteration.
  std::vector<RenderRequest> render_requests(const Frame& frame, Stage stage) const override;
  void start(const Frame& frame, const Renders& renders) override;
  void correspondences(const Frame& frame, const Renders& renders, int corr_iter) override;
  CueTerms gradient_hessian(int corr_iter, int update_iter) override;
  double log_likelihood(int corr_iter) const override;
  void append_residuals(std::vector<double>& residuals, std::vector<double>& weights) const override;
  void finish(const Frame& frame, const Renders& renders) override;
  ModalityQuality quality() const override { return quality_; }

  const DepthParams& params() const { return params_; }
  /// The depth viewpoint model (the detector checks hypotheses against its surface points).
  const ViewpointModel& model() const { return *model_; }

 private:
  /// The frame's image of the depth camera; nullptr when it delivered no depth this frame.
  const DepthImage* depth_image(const Frame& frame) const;
  /// How a correspondence pass searches the depth image around each point.
  struct Search {
    float considered_distance;  ///< metres
    int step;                   ///< pixels between samples, on the image lattice of its multiples
    bool projected_pixel;       ///< also try the pixel the point projects to
  };
  Search search_of_pass(const DepthImage& depth, const Posef& depth_T_body, int corr_iter) const;
  /// The model points' correspondences of iteration `corr_iter`.
  void model_point_correspondences(const DepthImage& depth, const Renders& renders, int corr_iter);
  /// The dense correspondences of iteration `corr_iter`.
  void dense_correspondences(const DepthImage& depth, const Renders& renders, int corr_iter);
  /// The searched measurement closest to `point` within the considered distance; sets
  /// `saw_depth` when any searched pixel held a valid depth.
  bool find_closest_measurement(const DepthImage& depth, const Eigen::Vector3f& point, const Search& search,
                                Eigen::Vector3f& closest, bool& saw_depth) const;
  Posef depth_T_body() const;

  /// The standard deviation at 1 m for correspondence iteration `corr_iter`.
  double sigma(int corr_iter) const;
  void estimate_noise();
  void update_quality();

  std::shared_ptr<const ViewpointModel> model_;
  DepthParams params_;
  MeasuredOcclusion occlusion_;
  int occlusion_offset_index_;
  int modeled_offset_index_;  ///< depth offsets for the modeled-occlusion radius
  SceneCrop crop_;            ///< of the scene's render
  RenderedScene scene_;       ///< this frame's render of the scene (empty without other bodies)
  Posef depth_T_reference_;
  ViewSelector view_selector_;
  std::optional<DenseDepthSampling> dense_;  ///< set for Sampling::kDense
  std::vector<DepthCorrespondence> correspondences_;
  ResidualNoise noise_;
  ViewOcclusions occlusions_;  ///< measured
  ViewOcclusions hidden_by_bodies_;  ///< modeled, in scene_
  int n_considered_ = 0;
  /// Of those, hidden by other bodies or outside the depth image or its mask: not expected
  /// to find data, so not counted against the score.
  int n_not_expected_ = 0;
  int last_corr_iter_ = 0;
  bool saw_depth_ = false;  ///< any valid depth where the last correspondences searched
  std::vector<cv::Point> projected_pixels_;  ///< kept for its capacity
  int frames_since_start_ = 0;
  ModalityQuality quality_;
};

}  // namespace icgp
