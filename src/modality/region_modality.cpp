// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/modality/region_modality.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "icgp/geometry/rounding.h"
#include "icgp/modality/contour_posterior.h"
#include "icgp/modality/iteration_value.h"

namespace icgp {
namespace {

/// How far (px, in each image direction) the colour image may be registered off the pose
/// the other cues hold. A colour camera and a depth camera calibrated 1-2 px off in their
/// principal points and 0.2 deg in their extrinsics put the fused pose's contour 3-4 px off
/// the colours' edge (the two-colour box in the realistic servo cell: its region scores rose
/// from 0.26 and 0.37 at no shift to 0.70 and 0.65 at 4 px and no further): the score must
/// not call such a pose wrong. A wrong pose leaves its lines off by more, and in directions
/// no single shift explains.
constexpr int kRegistrationTolerancePx = 4;

/// Agreement window of a line: the contour-location mass within this many segments of
/// where the model's contour projects.
constexpr float kAgreementSegments = 1.5f;

}  // namespace

RegionModality::RegionModality(Body& body, std::shared_ptr<const ViewpointModel> model, RegionParams params,
                               Extent extent)
    : Modality(body),
      model_(std::move(model)),
      params_(std::move(params)),
      extent_(extent),
      crop_(body, params_.color_camera, params_.occlusion.render_size),
      noise_(params_.noise) {
  if (!model_ || model_->kind() != ViewpointModel::Kind::kRegion)
    throw std::invalid_argument("region modality of '" + body.name + "' needs a region viewpoint model");
  occlusion_ = {params_.occlusion.radius, params_.occlusion.threshold};
  occlusion_offset_index_ = depth_offset_index(*model_, params_.occlusion.radius);
  modeled_offset_index_ = depth_offset_index(*model_, params_.occlusion.modeled_radius);
  n_segments_ = params_.function_length + params_.distribution_length - 1;

  // Smoothed step at the segment centres x_i = i − (function_length − 1)/2 (§4).
  const double alpha = params_.function_amplitude, slope = params_.function_slope;
  for (int i = 0; i < params_.function_length; ++i) {
    const double x = i - (params_.function_length - 1) / 2.0;
    const double h_f = slope > 0.0 ? 0.5 - alpha * std::tanh(x / (2.0 * slope)) : 0.5 - alpha * ((x > 0) - (x < 0));
    step_b_.push_back(static_cast<float>(1.0 - h_f));
    step_difference_.push_back(static_cast<float>(2.0 * h_f - 1.0));  // h_f − h_b
  }
  const double atanh_2alpha = std::atanh(2.0 * alpha);
  min_variance_ = static_cast<float>(std::max(1.0 / (2.0 * atanh_2alpha * atanh_2alpha), slope));

  lines_.reserve(params_.n_lines_max);
  distributions_.resize(static_cast<std::size_t>(params_.n_lines_max) * params_.distribution_length);
  log_distributions_.resize(distributions_.size());
  segment_f_.resize(n_segments_);
}

const ColorImage& RegionModality::color_image(const Frame& frame) const {
  const ColorImage* image = frame.find_color(params_.color_camera);
  if (!image)
    throw std::invalid_argument("region modality of '" + body().name + "': the frame has no colour camera '" +
                                params_.color_camera + "'");
  if (image->image.depth() != CV_8U || (image->image.channels() != 1 && image->image.channels() != 3))
    throw std::invalid_argument("region modality of '" + body().name + "': camera '" + params_.color_camera +
                                "' must give an 8-bit grey or BGR image");
  if (image->image.cols != image->intrinsics.width || image->image.rows != image->intrinsics.height)
    throw std::invalid_argument("region modality of '" + body().name + "': camera '" + params_.color_camera +
                                "' image is " + std::to_string(image->image.cols) + "x" +
                                std::to_string(image->image.rows) + " but its intrinsics are for " +
                                std::to_string(image->intrinsics.width) + "x" +
                                std::to_string(image->intrinsics.height));
  return *image;
}

Posef RegionModality::camera_T_body(const ColorImage& image) const {
  return (image.camera_T_reference * body().reference_T_body).cast<float>();
}

bool RegionModality::project(const ModelPoint& point, const Posef& camera_T_body, const Intrinsics& k,
                             ProjectedPoint& out) const {
  const Eigen::Vector3f X = camera_T_body * point.position;
  if (X.z() <= 0.f) return false;
  out.centre = k.project<float>(X);
  // The image direction of the contour normal is the projection's derivative along it,
  // exact also far from the optical axis.
  const Eigen::Vector2f direction = k.projection_jacobian<float>(X) * (camera_T_body.rotation() * point.normal);
  const float norm = direction.norm();
  if (!(norm > 1e-6f)) return false;
  out.normal = direction / norm;
  out.depth = X.z();
  const float px_per_metre = static_cast<float>(k.fu) / X.z();
  out.foreground_px = point.foreground_distance * px_per_metre;
  out.background_px = point.background_distance * px_per_metre;
  return true;
}

bool RegionModality::hidden(const Frame& frame, const Eigen::Vector3f& body_point, const float* depth_offsets) const {
  if (!params_.occlusion.measure || params_.depth_camera.empty() ||
      frames_since_start_ < params_.n_unoccluded_iterations)
    return false;
  const DepthImage* depth = frame.find_depth(params_.depth_camera);
  if (!depth || !depth->delivered()) return false;
  const Eigen::Vector3f X = (depth->camera_T_reference * body().reference_T_body).cast<float>() * body_point;
  return occlusion_.occluded(*depth, X, depth_offsets[occlusion_offset_index_]);
}

std::vector<RenderRequest> RegionModality::render_requests(const Frame& frame, Stage stage) const {
  if (!params_.occlusion.model && !params_.region_checking) return {};
  const ColorImage& image = color_image(frame);
  if (std::optional<RenderRequest> request =
          crop_.request(stage, image.intrinsics, image.camera_T_reference))
    return {*request};
  return {};
}

bool RegionModality::ruled_out_by_scene(const ModelPoint& point, const Posef& camera_T_body,
                                        const float* depth_offsets) const {
  if (scene_.empty()) return false;
  const Eigen::Vector3f X = camera_T_body * point.position;
  const OcclusionParams& o = params_.occlusion;
  if (o.model && scene_.hidden(X, depth_offsets[modeled_offset_index_], o.modeled_radius, o.modeled_threshold))
    return true;
  ProjectedPoint p;
  return params_.region_checking && project(point, camera_T_body, intrinsics_, p) &&
         !scene_.on_silhouette(X, p.normal, extent_ == Extent::kWholeBody);
}

void RegionModality::count_line_pixels(const Frame& frame) {
  const ColorImage& image = color_image(frame);
  const Intrinsics& k = image.intrinsics;
  const Posef pose = camera_T_body(image);
  const int view = view_selector_.select(*model_, pose.inverse().translation().normalized());
  const int n = std::min(model_->view_point_count(view), params_.n_lines_max);
  const ModelPoint* points = model_->points(view);
  const float start = static_cast<float>(params_.unconsidered_line_length);
  const float max_length = static_cast<float>(params_.max_considered_line_length);

  histograms_->clear_counts();
  ProjectedPoint p;
  for (int i = 0; i < n; ++i) {
    // What this frame's correspondences found hidden (by another body, or measured) still
    // is at its final pose.
    if (ruled_out_.measured(view, i) && ruled_out_.occluded(i)) continue;
    const bool occluded = occlusions_.measured(view, i)
                              ? occlusions_.occluded(i)
                              : hidden(frame, points[i].position, model_->depth_offsets(view, i));
    if (occluded || !project(points[i], pose, k, p)) continue;
    auto walk = [&](float length, float sign, bool foreground) {
      for (float t = start; t <= length; t += 1.f) {
        const Eigen::Vector2f x = p.centre + sign * t * p.normal;
        const int col = round_to_int(x.x()), row = round_to_int(x.y());
        if (col < 0 || row < 0 || col >= image.image.cols || row >= image.image.rows) return;
        if (foreground)
          histograms_->add_foreground(image.image, row, col);
        else
          histograms_->add_background(image.image, row, col);
      }
    };
    walk(std::min(max_length, p.foreground_px), -1.f, true);
    walk(std::min(max_length, p.background_px), 1.f, false);
  }
}

void RegionModality::start(const Frame& frame, const Renders&) {
  frames_since_start_ = 0;
  view_selector_.reset();  // a start owes nothing to the views of earlier frames
  noise_.reset();
  occlusions_.reset();
  ruled_out_.reset();
  scene_ = {};
  histograms_.emplace(params_.n_histogram_bins, color_image(frame).image.channels());
  count_line_pixels(frame);
  // A colour region or a whole body out of view (behind the others, past the image border:
  // a second body not yet in view) has no pixels to learn from: the cue abstains, the
  // body is reported lost rather than its start refused, and its colours are learnt in
  // finish() once they are in view.
  histograms_learnt_ = histograms_->set_from_counts();
}

bool RegionModality::sample_segments(const cv::Mat& image, const ProjectedPoint& p, int scale, Line& line) {
  const bool along_u = std::abs(p.normal.x()) >= std::abs(p.normal.y());
  const float n_dom = along_u ? p.normal.x() : p.normal.y();
  const float n_other = along_u ? p.normal.y() : p.normal.x();
  const float c_dom = along_u ? p.centre.x() : p.centre.y();
  const float c_other = along_u ? p.centre.y() : p.centre.x();
  const int sign = n_dom > 0.f ? 1 : -1;
  const int n_pixels = n_segments_ * scale;
  const float half = (n_pixels - 1) / 2.f;

  // Whole-pixel samples along the dominant axis, placed so their midpoint is nearest to
  // the projected point; Δr keeps the remaining offset (|Δr| <= 0.5 / |n_dom| px).
  const int first = round_to_int(c_dom - sign * half);
  const float middle = first + sign * half;
  line.delta_r = (middle - c_dom) / n_dom;
  line.normal_factor = std::abs(n_dom) / static_cast<float>(scale);

  const float slope = n_other / n_dom;  // other-axis pixels per dominant-axis pixel along +n
  const int last = first + sign * (n_pixels - 1);
  const int dom_limit = along_u ? image.cols : image.rows, other_limit = along_u ? image.rows : image.cols;
  const float other_first = c_other + (first - c_dom) * slope, other_last = c_other + (last - c_dom) * slope;
  if (std::min(first, last) < 0 || std::max(first, last) >= dom_limit ||
      round_to_int(std::min(other_first, other_last)) < 0 || round_to_int(std::max(other_first, other_last)) >= other_limit)
    return false;

  // Pixel addresses: the dominant axis is the column (along_u) or the row. The other
  // coordinate advances in 16.16 fixed point, so a pixel's row (or column) is a shift of
  // it rather than a float rounding (the step's rounding error stays below 0.002 px over
  // the longest line).
  PixelWalk walk;
  const std::ptrdiff_t pixel_size = image.channels(), row_size = static_cast<std::ptrdiff_t>(image.step);
  const std::ptrdiff_t dom_stride = along_u ? pixel_size : row_size;
  walk.other_stride = along_u ? row_size : pixel_size;
  walk.pixel = image.data + first * dom_stride;
  walk.dom_step = sign * dom_stride;
  walk.other = static_cast<std::int32_t>(std::floor((other_first + 0.5f) * kFixedOne));
  walk.other_step = static_cast<std::int32_t>(std::lround(sign * slope * kFixedOne));
  if (image.channels() == 3)
    segment_posteriors<3>(walk, scale);
  else
    segment_posteriors<1>(walk, scale);
  return true;
}

template <int kChannels>
void RegionModality::segment_posteriors(PixelWalk walk, int scale) {
  // A segment's foreground probability is the normalised product of its pixels'
  // posteriors, Π P_f / (Π P_f + Π P_b). Posteriors are at least 1e-3, so products of the
  // (at most a few) pixels of a segment stay far from float underflow.
  for (int s = 0; s < n_segments_; ++s) {
    float pf = 1.f, pb = 1.f;
    for (int i = 0; i < scale; ++i, walk.pixel += walk.dom_step, walk.other += walk.other_step) {
      const float posterior =
          histograms_->foreground_posterior<kChannels>(walk.pixel + (walk.other >> kFixedBits) * walk.other_stride);
      pf *= posterior;
      pb *= 1.f - posterior;
    }
    segment_f_[s] = pf / (pf + pb);
  }
}

void RegionModality::compute_distribution(Line& line, float* distribution, float* log_distribution) const {
  const int n_dist = params_.distribution_length;
  // Position d's product over the function's segments i, with i outermost so that the
  // inner loop runs over contiguous positions (vectorised); each product still multiplies
  // its factors in the order of i.
  std::fill(distribution, distribution + n_dist, 1.f);
  for (int i = 0; i < params_.function_length; ++i) {
    const float b = step_b_[i], difference = step_difference_[i];
    const float* f = segment_f_.data() + i;
    for (int d = 0; d < n_dist; ++d) distribution[d] *= b + difference * f[d];
  }
  float sum = 0.f;
  for (int d = 0; d < n_dist; ++d) sum += distribution[d];
  const float centre = (n_dist - 1) / 2.f;
  float mean = 0.f;
  for (int d = 0; d < n_dist; ++d) {
    distribution[d] /= sum;
    mean += distribution[d] * (d - centre);
  }
  float variance = 0.f;
  for (int d = 0; d < n_dist; ++d) variance += distribution[d] * (d - centre - mean) * (d - centre - mean);
  line.mean = mean;
  line.variance = std::max(variance, min_variance_);
  if (log_distribution)
    for (int d = 0; d < n_dist; ++d) log_distribution[d] = std::log(distribution[d]);
}

void RegionModality::correspondences(const Frame& frame, const Renders& renders, int corr_iter) {
  const ColorImage& image = color_image(frame);
  if (image.image.channels() != histograms_->channels())
    throw std::invalid_argument("region modality of '" + body().name + "': camera '" + params_.color_camera +
                                "' changed between grey and colour images; restart tracking");
  intrinsics_ = image.intrinsics;
  camera_T_reference_ = image.camera_T_reference.cast<float>();
  const Posef pose = camera_T_body(image);
  const int view = view_selector_.select(*model_, pose.inverse().translation().normalized());
  const int scale = iteration_value(params_.scales, corr_iter);
  n_considered_ = std::min(model_->view_point_count(view), params_.n_lines_max);
  const ModelPoint* points = model_->points(view);

  if (corr_iter == 0)
    scene_ = crop_.find(renders, image.intrinsics, image.camera_T_reference);
  occlusions_.update(corr_iter, view, n_considered_,
                     [&](int i) { return hidden(frame, points[i].position, model_->depth_offsets(view, i)); });
  ruled_out_.update(corr_iter, view, n_considered_,
                    [&](int i) { return ruled_out_by_scene(points[i], pose, model_->depth_offsets(view, i)); });
  auto collect = [&](bool test_occlusions) {
    lines_.clear();
    n_measurable_ = 0;
    ProjectedPoint p;
    for (int i = 0; i < n_considered_; ++i) {
      // What the scene's render rules out is known to be unmeasurable, unlike what an
      // unknown occluder hides: it does not count against the cue's quality.
      if (ruled_out_.occluded(i) || !project(points[i], pose, intrinsics_, p)) continue;
      if (std::min(p.foreground_px, p.background_px) / scale < params_.min_continuous_distance) continue;
      // Nor does what the camera cannot see: a line outside the image or the mask.
      if (!image.mask.usable(p.centre)) continue;
      Line line;
      line.body_point = points[i].position;
      line.centre = p.centre;
      line.normal = p.normal;
      if (!sample_segments(image.image, p, scale, line)) continue;
      ++n_measurable_;
      if (test_occlusions && occlusions_.occluded(i)) continue;
      // The global iterations read only the distribution's mean and variance.
      const std::size_t offset = lines_.size() * params_.distribution_length;
      compute_distribution(line, distributions_.data() + offset,
                           corr_iter < params_.n_global_iterations ? nullptr : log_distributions_.data() + offset);
      lines_.push_back(line);
    }
  };
  if (!histograms_learnt_) {
    // Without colour statistics no line has a posterior: nothing is measurable.
    lines_.clear();
    n_measurable_ = 0;
  } else {
    collect(true);
    if (static_cast<int>(lines_.size()) < params_.min_n_unoccluded_lines) collect(false);
  }
  weigh_lines(pose, corr_iter);
  last_corr_iter_ = corr_iter;
}

float RegionModality::normalised_residual(const Line& line, const Posef& camera_T_body) const {
  const float pixels = (line_position(line, camera_T_body, intrinsics_) - line.mean) / line.normal_factor;
  return pixels * std::sqrt(min_variance_ / line.variance);
}

void RegionModality::weigh_lines(const Posef& camera_T_body, int corr_iter) {
  noise_.estimate([&](auto add) {
    for (Line& line : lines_) add(line.residual = normalised_residual(line, camera_T_body));
  });
  // Robust weights, fixed for this pass's updates (iteratively reweighted): a line whose
  // contour lies far beyond the others' scatter, such as a background of the object's
  // colour, must not pull the pose. Without them (no residuals collected) weight() is 1.
  const double scale = noise_.scale(iteration_value(params_.standard_deviations, corr_iter));
  for (Line& line : lines_) line.weight = noise_.weight(line.residual, scale);
}

double RegionModality::sigma(int corr_iter) const {
  return noise_.sigma(iteration_value(params_.standard_deviations, corr_iter));
}

float RegionModality::line_position(const Line& line, const Posef& camera_T_body, const Intrinsics& k) const {
  const Eigen::Vector2f x = k.project<float>(camera_T_body * line.body_point);
  return line.normal_factor * (line.normal.dot(x - line.centre) - line.delta_r);
}

CueTerms RegionModality::gradient_hessian(int corr_iter, int) {
  const Posef pose = camera_T_reference_ * body().reference_T_body.cast<float>();
  const Eigen::Matrix3f R_t = pose.rotation().transpose();
  const float sigma_r = static_cast<float>(sigma(corr_iter));
  const bool gaussian = corr_iter < params_.n_global_iterations;
  const int n_dist = params_.distribution_length;
  const float centre = (n_dist - 1) / 2.f;
  const float learning_rate = static_cast<float>(params_.learning_rate);

  Eigen::Matrix<float, 6, 1> g_sum = Eigen::Matrix<float, 6, 1>::Zero();
  Eigen::Matrix<float, 6, 6> H_sum = Eigen::Matrix<float, 6, 6>::Zero();
  for (std::size_t l = 0; l < lines_.size(); ++l) {
    const Line& line = lines_[l];
    const Eigen::Vector3f X = pose * line.body_point;
    if (X.z() <= 0.f) continue;
    const Eigen::Vector2f x = intrinsics_.project<float>(X);
    const float delta = line.normal_factor * (line.normal.dot(x - line.centre) - line.delta_r);

    float dloglikelihood;
    if (gaussian) {
      dloglikelihood = (line.mean - delta) / line.variance;
    } else {
      const float x = delta + centre;
      if (x < 0.f || x >= n_dist - 1) continue;
      const ContourPosterior posterior(log_distributions_.data() + l * n_dist, n_dist, params_.subpixel_posterior);
      dloglikelihood = learning_rate * posterior.slope(x) / line.variance;
    }

    // J = n̄ nᵀ ∂π/∂X R [−[X_M]×, I]: with v = Rᵀ (n̄ ∂π/∂Xᵀ n), J = [X_M × v; v].
    const Eigen::Vector3f a =
        line.normal_factor * (intrinsics_.projection_jacobian<float>(X).transpose() * line.normal);
    const Eigen::Vector3f v = R_t * a;
    Eigen::Matrix<float, 6, 1> J;
    J << line.body_point.cross(v), v;
    const float weight = line.weight * min_variance_ / (line.normal_factor * line.normal_factor * sigma_r * sigma_r);
    g_sum += (weight * dloglikelihood) * J;
    H_sum.noalias() -= (weight / line.variance) * J * J.transpose();
  }
  return {g_sum.cast<double>(), H_sum.cast<double>(), static_cast<int>(lines_.size())};
}

double RegionModality::log_likelihood(int corr_iter) const {
  // The integral of the derivative add_gradient_hessian uses: a Gaussian around μ in the
  // global iterations, afterwards ln p(d) between its positions (ContourPosterior, scaled alike).
  const Pose pose = camera_T_reference_.cast<double>() * body().reference_T_body;
  const double sigma_r = sigma(corr_iter);
  const int n_dist = params_.distribution_length;
  const double centre = (n_dist - 1) / 2.0;
  double sum = 0.0;
  for (std::size_t l = 0; l < lines_.size(); ++l) {
    const Line& line = lines_[l];
    const Eigen::Vector2d x = intrinsics_.project<double>(pose * line.body_point.cast<double>());
    const double delta = line.normal_factor * (line.normal.cast<double>().dot(x - line.centre.cast<double>()) - line.delta_r);
    const double weight = line.weight * min_variance_ / (line.normal_factor * line.normal_factor * sigma_r * sigma_r);
    if (corr_iter < params_.n_global_iterations) {
      sum -= weight * 0.5 * (delta - line.mean) * (delta - line.mean) / line.variance;
      continue;
    }
    const double position = delta + centre;
    if (position < 0.0 || position >= n_dist - 1) continue;
    const double log_p =
        ContourPosterior(log_distributions_.data() + l * n_dist, n_dist, params_.subpixel_posterior).log(position);
    sum += weight * params_.learning_rate * log_p / line.variance;
  }
  return sum;
}

void RegionModality::append_residuals(std::vector<double>& residuals, std::vector<double>& weights) const {
  // Distance of the projected contour from the most likely contour location along the
  // line, in pixels; the weight is the line's confidence σ_min² / σ_d² times its robust weight.
  const Pose pose = camera_T_reference_.cast<double>() * body().reference_T_body;
  for (const Line& line : lines_) {
    const Eigen::Vector2d x = intrinsics_.project<double>(pose * line.body_point.cast<double>());
    const double delta = line.normal_factor * (line.normal.cast<double>().dot(x - line.centre.cast<double>()) - line.delta_r);
    residuals.push_back((delta - line.mean) / line.normal_factor);
    weights.push_back(line.weight * min_variance_ / line.variance);
  }
}

void RegionModality::append_image_features(std::vector<ImageFeature>& features) const {
  // The most likely contour location: where the line's position, n̄ (n·(x − c) − Δr),
  // equals the distribution's mean.
  for (const Line& line : lines_) {
    const float along_normal = line.mean / line.normal_factor + line.delta_r;
    features.push_back({(line.centre + along_normal * line.normal).cast<double>(),
                        static_cast<double>(line.weight)});
  }
}

void RegionModality::finish(const Frame& frame, const Renders&) {
  update_quality();
  ++frames_since_start_;
  count_line_pixels(frame);
  if (histograms_learnt_)
    histograms_->blend_counts(params_.learning_rate_f, params_.learning_rate_b);
  else
    histograms_learnt_ = histograms_->set_from_counts();
}

void RegionModality::update_quality() {
  // A line agrees with the pose when its contour-location distribution holds its mass
  // within ±1.5 segments of where the model's contour now projects, with the whole contour
  // moved by the image shift (up to kRegistrationTolerancePx) that agrees best. Lines an
  // unknown occluder hides count as disagreeing, since a wrong pose looks the same; lines
  // the camera cannot see (outside the image or the mask) and lines the model's own
  // geometry rules out at this pose (a region too thin to measure) do not count, and a
  // region with none left has nothing to say: it abstains.
  const Posef pose = camera_T_reference_ * body().reference_T_body.cast<float>();
  const int n_dist = params_.distribution_length;
  const float centre = (n_dist - 1) / 2.f;
  // Per line: its mass up to each segment (for any window in constant time), where the
  // contour projects, and how a shift of the image moves that (segments per pixel).
  cumulative_mass_.resize(lines_.size() * (n_dist + 1));
  contour_positions_.resize(lines_.size());
  segments_per_pixel_.resize(lines_.size());
  for (std::size_t l = 0; l < lines_.size(); ++l) {
    const float* distribution = distributions_.data() + l * n_dist;
    float* sum = cumulative_mass_.data() + l * (n_dist + 1);
    sum[0] = 0.f;
    for (int d = 0; d < n_dist; ++d) sum[d + 1] = sum[d] + distribution[d];
    contour_positions_[l] = centre + line_position(lines_[l], pose, intrinsics_);
    segments_per_pixel_[l] = lines_[l].normal_factor * lines_[l].normal;
  }
  const auto agreement_at = [&](const Eigen::Vector2f& shift) {
    double agreement = 0.0;
    for (std::size_t l = 0; l < lines_.size(); ++l) {
      const float position = contour_positions_[l] + segments_per_pixel_[l].dot(shift);
      const int first = std::clamp(static_cast<int>(std::ceil(position - kAgreementSegments)), 0, n_dist);
      const int last = std::clamp(static_cast<int>(std::floor(position + kAgreementSegments)) + 1, first, n_dist);
      const float* sum = cumulative_mass_.data() + l * (n_dist + 1);
      agreement += sum[last] - sum[first];
    }
    return agreement;
  };
  double agreement = 0.0;
  for (int dv = -kRegistrationTolerancePx; dv <= kRegistrationTolerancePx; ++dv)
    for (int du = -kRegistrationTolerancePx; du <= kRegistrationTolerancePx; ++du)
      agreement = std::max(agreement, agreement_at(Eigen::Vector2f(static_cast<float>(du), static_cast<float>(dv))));
  quality_.n_valid = static_cast<int>(lines_.size());
  quality_.valid_fraction = n_measurable_ > 0 ? static_cast<double>(lines_.size()) / n_measurable_ : 0.0;
  quality_.score = n_measurable_ > 0 ? agreement / n_measurable_ : 0.0;
  quality_.abstained = n_measurable_ == 0;
  quality_.sigma = sigma(last_corr_iter_);
}

}  // namespace icgp
