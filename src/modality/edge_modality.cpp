// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/modality/edge_modality.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "icgp/modality/cue_images.h"
#include "icgp/modality/iteration_value.h"
#include "icgp/render/renderer.h"

namespace icgp {
namespace {

/// Gaussian smoothing (3 x 3) of the image before its gradient: a sample's step of brightness
/// is then a smooth peak whose sub-pixel place a parabola finds.
constexpr double kSmoothingSigma = 0.8;
/// A step of brightness counts for a crease when its gradient is within about 25° of the
/// crease's normal (cos² 25°).
constexpr float kMinAlignment2 = 0.82f;
/// Pixels searched either side of a sample on the start frame, at the pose given as right:
/// the antialiased or blurred width of a step.
constexpr int kStartRange = 2;
/// 1 / (2 s²) for the spread s of the log of a step's size between frames: s = 0.5 allows a
/// factor of about 1.6 per standard deviation (shading changes as the object turns).
constexpr float kInverseContrastSpread = 2.f;
/// The visible samples are chosen anew when the camera came this much nearer or farther
/// (in log of the distance) since they were chosen: their spacing in the image then changed.
constexpr double kResampleDistanceChange = 0.1;

Eigen::Vector2f perpendicular(const Eigen::Vector2f& d) { return {-d.y(), d.x()}; }

}  // namespace

EdgeModality::EdgeModality(Body& body, EdgeParams params, std::string color_camera)
    : Modality(body),
      params_(std::move(params)),
      color_camera_(std::move(color_camera)),
      convex_(is_convex(body.mesh)),
      sphere_(bounding_sphere(body.mesh)),
      noise_(params_.noise) {
  if (!(params_.sample_step > 0.0) || params_.n_points_max < 1 || params_.search_ranges.empty() ||
      params_.standard_deviations.empty())
    throw std::invalid_argument("edge modality of '" + body.name +
                                "': sample_step and n_points_max must be positive, search_ranges and "
                                "standard_deviations non-empty");
  for (const MeshEdge& e : mesh_edges(body.mesh, params_.crease_angle_deg))
    if (e.crease) creases_.push_back(e);
  polarity_.assign(creases_.size(), 0.f);
}

const ColorImage& EdgeModality::color_image(const Frame& frame) const {
  return cue_color_image(frame, color_camera_, name(), body());
}

Pose EdgeModality::camera_T_body() const { return camera_T_reference_ * body().reference_T_body; }

std::optional<RenderRequest> EdgeModality::visibility_render(const ColorImage& color) const {
  return focused_render_request(color_camera_, color.intrinsics, color.camera_T_reference, body().reference_T_body,
                                sphere_, params_.render_size);
}

bool EdgeModality::resampling_due(const Pose& camera_T_body) const {
  if (!sampled_) return true;
  const Eigen::Vector3d from = camera_T_body.inverse().translation() - sphere_.centre;
  const Eigen::Vector3d before = sampled_from_ - sphere_.centre;
  const double cos_turned = from.normalized().dot(before.normalized());
  return cos_turned < std::cos(deg_to_rad(params_.resample_angle_deg)) ||
         std::abs(std::log(from.norm() / before.norm())) > kResampleDistanceChange;
}

std::vector<RenderRequest> EdgeModality::render_requests(const Frame& frame, Stage stage) const {
  const bool samples = stage.kind == Stage::kStart || (stage.kind == Stage::kCorrespondences && stage.corr_iter == 0);
  if (!samples) return {};
  bool others = false;
  if (stage.scene)
    for (const BodyExtent& b : *stage.scene) others = others || b.name != body().name;
  // Another body may have moved over this one whatever this one did: render every frame.
  const ColorImage& color = color_image(frame);
  const bool render = others || (!convex_ && (stage.kind == Stage::kStart ||
                                             resampling_due(color.camera_T_reference * body().reference_T_body)));
  if (!render) return {};
  if (std::optional<RenderRequest> request = visibility_render(color)) return {*request};
  return {};
}

void EdgeModality::start(const Frame& frame, const Renders& renders) {
  noise_.reset();
  quality_ = {};
  std::fill(polarity_.begin(), polarity_.end(), 0.f);
  // The given pose is taken as right, as the texture and flow cues take it when they lift
  // their points: each sample learns the step its crease shows there, so that the first
  // tracked frame already looks for steps like its creases' and not the strongest nearby.
  const ColorImage& color = color_image(frame);
  intrinsics_ = color.intrinsics;
  camera_T_reference_ = color.camera_T_reference;
  compute_gradient(color);
  const std::optional<RenderRequest> request = visibility_render(color);
  sample_creases(request ? renders.find(*request) : nullptr);
  match(color.mask, kStartRange, 1.0);
  learn_contrasts();
}

void EdgeModality::compute_gradient(const ColorImage& color) {
  const Eigen::Vector3d centre = camera_T_body() * sphere_.centre;
  // Without a region this frame, no gradient of an earlier frame may be read (gradient_at
  // reads nothing outside the region; the buffers are kept for the next frame).
  gradient_region_ = {};
  if (!(centre.z() > sphere_.radius)) return;
  const ImageSquare square = square_around_sphere(intrinsics_, centre, sphere_.radius);
  const int margin = *std::max_element(params_.search_ranges.begin(), params_.search_ranges.end()) + 4;
  const int side = static_cast<int>(std::ceil(square.size)) + 1 + 2 * margin;
  gradient_region_ = cv::Rect(static_cast<int>(std::floor(square.u_min)) - margin,
                              static_cast<int>(std::floor(square.v_min)) - margin, side, side) &
                     cv::Rect(0, 0, color.image.cols, color.image.rows);
  if (gradient_region_.empty()) return;
  const cv::Mat roi = color.image(gradient_region_);
  if (roi.channels() == 3)
    cv::cvtColor(roi, scratch_grey_, cv::COLOR_BGR2GRAY);
  else
    roi.copyTo(scratch_grey_);
  cv::GaussianBlur(scratch_grey_, scratch_grey_, cv::Size(3, 3), kSmoothingSigma);
  // Both Sobel derivatives in one pass, in integers: a third of two float passes' time.
  cv::spatialGradient(scratch_grey_, gradient_u_, gradient_v_, 3);
}

std::optional<Eigen::Vector2f> EdgeModality::gradient_at(const Eigen::Vector2f& x) const {
  if (!x.allFinite()) return std::nullopt;
  const float u = x.x() - static_cast<float>(gradient_region_.x);
  const float v = x.y() - static_cast<float>(gradient_region_.y);
  const int c = static_cast<int>(std::floor(u)), r = static_cast<int>(std::floor(v));
  if (c < 0 || r < 0 || c + 1 >= gradient_region_.width || r + 1 >= gradient_region_.height) return std::nullopt;
  const float a = u - static_cast<float>(c), b = v - static_cast<float>(r);
  auto bilinear = [&](const cv::Mat& m) {
    const std::int16_t* row0 = m.ptr<std::int16_t>(r);
    const std::int16_t* row1 = m.ptr<std::int16_t>(r + 1);
    return (1.f - b) * ((1.f - a) * row0[c] + a * row0[c + 1]) + b * ((1.f - a) * row1[c] + a * row1[c + 1]);
  };
  // Sobel's 3 x 3 kernels sum to 8 times the central difference: /8 gives grey levels per pixel.
  return Eigen::Vector2f(bilinear(gradient_u_), bilinear(gradient_v_)) * 0.125f;
}

void EdgeModality::sample_creases(const FocusedRender* render) {
  samples_.clear();
  const Pose T = camera_T_body();
  sampled_ = true;
  sampled_from_ = T.inverse().translation();
  const Eigen::Vector3d camera_in_body = T.inverse().translation();
  const double min_view_cosine = std::cos(deg_to_rad(params_.max_view_angle_deg));
  struct Visible {
    int edge;
    Eigen::Vector3d a, b;  ///< camera frame
    double length;         ///< pixels
  };
  std::vector<Visible> visible;
  double total_length = 0.0;
  for (std::size_t i = 0; i < creases_.size(); ++i) {
    const MeshEdge& e = creases_[i];
    const Eigen::Vector3d to_camera = (camera_in_body - 0.5 * (e.a + e.b)).normalized();
    if (e.normal_1.dot(to_camera) < min_view_cosine && e.normal_2.dot(to_camera) < min_view_cosine) continue;
    const Eigen::Vector3d a = T * e.a, b = T * e.b;
    if (a.z() <= 0.0 || b.z() <= 0.0) continue;
    const double length = (intrinsics_.project<double>(a) - intrinsics_.project<double>(b)).norm();
    if (!(length > 1.0)) continue;
    visible.push_back({static_cast<int>(i), a, b, length});
    total_length += length;
  }
  const double step = std::max(params_.sample_step, total_length / params_.n_points_max);
  const Eigen::Matrix3d body_R_camera = T.rotation().transpose();
  for (const Visible& v : visible) {
    const int n = static_cast<int>(std::floor(v.length / step));
    const MeshEdge& e = creases_[static_cast<std::size_t>(v.edge)];
    const Eigen::Vector3f direction = (e.b - e.a).normalized().cast<float>();
    for (int k = 0; k < n; ++k) {
      const double s = (k + 0.5) / n;
      const Eigen::Vector3d X = (1.0 - s) * v.a + s * v.b;
      if (render) {
        // Hidden when a surface is clearly in front of the sample anywhere in its 3 x 3
        // render neighbourhood (the faces that meet at the crease are at its depth).
        const Eigen::Vector2d y = render->intrinsics.project<double>(X);
        const int u = static_cast<int>(std::lround(y.x())), w = static_cast<int>(std::lround(y.y()));
        const float tolerance = static_cast<float>(0.002 + 0.01 * X.z());
        bool hidden = false;
        for (int dv = -1; dv <= 1 && !hidden; ++dv)
          for (int du = -1; du <= 1 && !hidden; ++du) {
            const int uu = std::clamp(u + du, 0, render->depth.cols - 1);
            const int vv = std::clamp(w + dv, 0, render->depth.rows - 1);
            const float d = render->depth.ptr<float>(vv)[uu];
            hidden = d > 0.f && d < static_cast<float>(X.z()) - tolerance;
          }
        if (hidden) continue;
      }
      Sample sample;
      sample.body_point = (body_R_camera * (X - T.translation())).cast<float>();
      sample.body_direction = direction;
      sample.edge = v.edge;
      samples_.push_back(sample);
    }
  }
}

void EdgeModality::match(const PixelMask& mask, int range, double prior_sigma) {
  const Posef T = camera_T_body().cast<float>();
  const float inverse_prior = static_cast<float>(0.5 / (prior_sigma * prior_sigma));
  const float min_contrast = static_cast<float>(params_.min_contrast);
  std::vector<float>& along = scratch_along_;  // kept from call to call: no allocation per frame
  along.resize(static_cast<std::size_t>(2 * range + 1));
  for (Sample& s : samples_) {
    s.polarity = 0.f;
    s.weight = 0.f;
    s.seen = false;
    const Eigen::Vector3f X = T * s.body_point;
    const Eigen::Vector3f D = T.rotation() * s.body_direction;
    if (X.z() <= 0.f) continue;
    const Eigen::Vector2f x = intrinsics_.project<float>(X);
    if (!mask.usable(x)) continue;
    const Eigen::Vector2f tangent = intrinsics_.projection_jacobian<float>(X) * D;
    if (!(tangent.norm() > 0.f)) continue;
    s.normal = perpendicular(tangent.normalized());
    bool inside = true;
    for (int k = -range; k <= range && inside; ++k) {
      const std::optional<Eigen::Vector2f> g = gradient_at(x + static_cast<float>(k) * s.normal);
      inside = g.has_value();
      if (!inside) break;
      // A step across the crease: the gradient points along its normal. Texture and clutter
      // edges at other angles do not count (moving edges' oriented masks do the same).
      const float across = g->dot(s.normal);
      along[static_cast<std::size_t>(k + range)] = across * across >= kMinAlignment2 * g->squaredNorm() ? across : 0.f;
    }
    if (!inside) continue;
    s.seen = true;
    const float known = s.contrast != 0.f ? s.contrast : polarity_[static_cast<std::size_t>(s.edge)];
    int best = -1;
    float best_score = 0.f;
    for (int i = 1; i + 1 < static_cast<int>(along.size()); ++i) {
      const float g = along[static_cast<std::size_t>(i)];
      const float magnitude = std::abs(g);
      if (magnitude < min_contrast || magnitude < std::abs(along[i - 1]) || magnitude < std::abs(along[i + 1])) continue;
      if (known != 0.f && g * known < 0.f) continue;
      const float d = static_cast<float>(i - range);
      // With the step the sample matched last, the likeliest candidate has a step of that
      // size (as moving edges compare contrasts); without, the strongest.
      float likelihood = magnitude;
      if (s.contrast != 0.f) {
        const float log_ratio = std::log(magnitude / std::abs(s.contrast));
        likelihood = std::exp(-log_ratio * log_ratio * kInverseContrastSpread);
      }
      const float score = likelihood * std::exp(-d * d * inverse_prior);
      if (score > best_score) {
        best_score = score;
        best = i;
      }
    }
    if (best < 0) continue;
    // The peak of |g| between its neighbours, by a parabola through the three.
    const float l = std::abs(along[best - 1]), c = std::abs(along[best]), r = std::abs(along[best + 1]);
    const float curvature = l - 2.f * c + r;
    const float offset = curvature < 0.f ? std::clamp(0.5f * (l - r) / curvature, -0.5f, 0.5f) : 0.f;
    s.found = x + (static_cast<float>(best - range) + offset) * s.normal;
    s.polarity = along[best] > 0.f ? 1.f : -1.f;
    s.step = along[best];
    s.weight = 1.f;
  }
}

float EdgeModality::residual(const Sample& s, const Posef& T) const {
  return s.normal.dot(intrinsics_.project<float>(T * s.body_point) - s.found);
}

void EdgeModality::correspondences(const Frame& frame, const Renders& renders, int corr_iter) {
  const ColorImage& color = color_image(frame);
  intrinsics_ = color.intrinsics;
  camera_T_reference_ = color.camera_T_reference;
  if (corr_iter == 0) {
    compute_gradient(color);
    const std::optional<RenderRequest> request = visibility_render(color);
    const FocusedRender* render = request ? renders.find(*request) : nullptr;
    if (render || resampling_due(camera_T_body())) sample_creases(render);
  }
  match(color.mask, iteration_value(params_.search_ranges, corr_iter),
        iteration_value(params_.standard_deviations, corr_iter));
  const Posef T = camera_T_body().cast<float>();
  noise_.estimate([&](auto add) {
    for (const Sample& s : samples_)
      if (s.polarity != 0.f) add(residual(s, T));
  });
  update_weights(corr_iter);
  last_corr_iter_ = corr_iter;
}

double EdgeModality::sigma(int corr_iter) const {
  return noise_.sigma(iteration_value(params_.standard_deviations, corr_iter));
}

void EdgeModality::update_weights(int corr_iter) {
  const Posef T = camera_T_body().cast<float>();
  const double scale = noise_.scale(iteration_value(params_.standard_deviations, corr_iter));
  for (Sample& s : samples_)
    s.weight = s.polarity != 0.f ? noise_.weight(residual(s, T), scale) : 0.f;
}

CueTerms EdgeModality::gradient_hessian(int corr_iter, int) {
  update_weights(corr_iter);
  const Posef T = camera_T_body().cast<float>();
  const float inverse_variance = static_cast<float>(1.0 / (sigma(corr_iter) * sigma(corr_iter)));
  Eigen::Matrix<float, 6, 1> g = Eigen::Matrix<float, 6, 1>::Zero();
  Eigen::Matrix<float, 6, 6> H = Eigen::Matrix<float, 6, 6>::Zero();
  int n = 0;
  for (const Sample& s : samples_) {
    if (s.weight <= 0.f) continue;
    const Eigen::Vector3f X = T * s.body_point;
    if (X.z() <= 0.f) continue;
    const Eigen::Matrix<float, 1, 6> J = s.normal.transpose() * intrinsics_.projection_jacobian<float>(X) *
                                         point_jacobian_body_variation<float>(T.rotation(), s.body_point);
    const float w = s.weight * inverse_variance;
    g.noalias() -= w * J.transpose() * residual(s, T);
    H.noalias() -= w * J.transpose() * J;
    ++n;
  }
  return {g.cast<double>(), H.cast<double>(), n};
}

double EdgeModality::log_likelihood(int corr_iter) const {
  const Pose T = camera_T_body();
  const double s = sigma(corr_iter);
  double sum = 0.0;
  for (const Sample& sample : samples_) {
    if (sample.weight <= 0.f) continue;
    const Eigen::Vector2d x = intrinsics_.project<double>(T * sample.body_point.cast<double>());
    const double r = sample.normal.cast<double>().dot(x - sample.found.cast<double>());
    sum -= 0.5 * sample.weight * r * r / (s * s);
  }
  return sum;
}

void EdgeModality::append_residuals(std::vector<double>& residuals, std::vector<double>& weights) const {
  const Posef T = camera_T_body().cast<float>();
  for (const Sample& s : samples_) {
    if (s.polarity == 0.f) continue;
    residuals.push_back(residual(s, T));
    weights.push_back(s.weight);
  }
}

void EdgeModality::append_image_features(std::vector<ImageFeature>& features) const {
  for (const Sample& s : samples_)
    if (s.polarity != 0.f) features.push_back({s.found.cast<double>(), s.weight});
}

void EdgeModality::learn_contrasts() {
  // The samples' weighted votes are summed in polarity_ itself, then reduced to their sign.
  std::fill(polarity_.begin(), polarity_.end(), 0.f);
  for (Sample& s : samples_) {
    if (s.polarity == 0.f || s.weight <= 0.f) continue;
    s.contrast = s.step;
    polarity_[static_cast<std::size_t>(s.edge)] += s.weight * s.polarity;
  }
  for (float& p : polarity_) p = p > 0.f ? 1.f : p < 0.f ? -1.f : 0.f;
}

void EdgeModality::finish(const Frame&, const Renders&) {
  // Each sample keeps the step it matched with trust; each crease the sign its samples agreed
  // on, for samples chosen later. A crease that found nothing forgets its sign (it was
  // hidden, or its faces' brightness changed).
  learn_contrasts();
  // Samples the camera could not see (outside the image or the mask) say nothing of the pose.
  int n = 0, n_matched = 0, n_inliers = 0;
  for (const Sample& s : samples_) {
    n += s.seen;
    if (s.polarity == 0.f) continue;
    ++n_matched;
    if (s.weight > 0.f) ++n_inliers;
  }
  quality_.n_valid = n_inliers;
  quality_.valid_fraction = n > 0 ? static_cast<double>(n_matched) / n : 0.0;
  quality_.score = n > 0 ? static_cast<double>(n_inliers) / n : 0.0;
  quality_.abstained = n < params_.min_points;
  quality_.sigma = sigma(last_corr_iter_);
}

}  // namespace icgp
