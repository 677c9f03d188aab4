// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/modality/flow_modality.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <stdexcept>

#include "icgp/geometry/rounding.h"
#include "icgp/modality/cue_images.h"
#include "icgp/modality/iteration_value.h"
#include "icgp/modality/reprojection_terms.h"
#include "icgp/render/renderer.h"

namespace icgp {
namespace {

/// Lucas–Kanade's iterations per level: vpKltOpencv's termination criteria.
const cv::TermCriteria kFlowTermination(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 0.03);
/// vpKltOpencv's minimum eigenvalue of the window's gradient matrix, below which a point
/// has no texture to follow.
constexpr double kMinEigenvalue = 1e-4;
/// A surface seen at more than about 85° from its normal shows its corners too obliquely to
/// follow them.
constexpr float kMinViewCosine = 0.087f;
/// Side of the focused render corners are lifted in and masked by. A corner is lifted along
/// its own ray, so a coarser render only misplaces it in depth by the surface's slope over a
/// render pixel; one size for every renewal spares the renderer new buffers.
constexpr int kCornerRenderSize = 256;

}  // namespace

FlowModality::FlowModality(Body& body, FlowParams params, std::string color_camera, std::string depth_camera)
    : Modality(body),
      params_(std::move(params)),
      color_camera_(std::move(color_camera)),
      depth_camera_(std::move(depth_camera)),
      lifter_(MeasuredOcclusion{params_.occlusion.radius, params_.occlusion.threshold}),
      sphere_(bounding_sphere(body.mesh)),
      frames_(params_.window_size, params_.pyramid_levels),
      noise_(params_.noise) {}

const ColorImage& FlowModality::color_image(const Frame& frame) const {
  return cue_color_image(frame, color_camera_, name(), body());
}

Pose FlowModality::camera_T_body() const { return camera_T_reference_ * body().reference_T_body; }

bool FlowModality::load_image(const ColorImage& color) {
  intrinsics_ = color.intrinsics;
  camera_T_reference_ = color.camera_T_reference;
  return frames_.load(color.image);
}

cv::Rect FlowModality::body_region() const {
  const Eigen::Vector3d centre = camera_T_body() * sphere_.centre;
  if (!(centre.z() > sphere_.radius)) return {};
  const ImageSquare square = square_around_sphere(intrinsics_, centre, sphere_.radius);
  const int side = static_cast<int>(std::ceil(square.size)) + 1;
  return {static_cast<int>(std::floor(square.u_min)), static_cast<int>(std::floor(square.v_min)), side, side};
}

void FlowModality::track_points(const PixelMask& mask) {
  frames_.focus(body_region());
  if (matches_.empty() || !frames_.ready()) {
    matches_.clear();
    return;
  }
  // The pyramids cover region(): points are followed in its coordinates.
  const cv::Point2f origin(static_cast<float>(frames_.region().x), static_cast<float>(frames_.region().y));
  scratch_from_.clear();
  for (const Match& m : matches_) scratch_from_.push_back(cv::Point2f(m.image_point.x(), m.image_point.y()) - origin);
  cv::calcOpticalFlowPyrLK(frames_.previous(), frames_.current(), scratch_from_, scratch_to_, scratch_status_,
                           scratch_error_, frames_.window(), frames_.levels(), kFlowTermination, 0, kMinEigenvalue);
  // Back from where each point went: a point the flow lost (to a look-alike, an occluder, a
  // highlight) rarely comes back to where it was.
  cv::calcOpticalFlowPyrLK(frames_.current(), frames_.previous(), scratch_to_, scratch_back_, scratch_back_status_,
                           scratch_error_, frames_.window(), frames_.levels(), kFlowTermination, 0, kMinEigenvalue);
  const float max_return = static_cast<float>(params_.forward_backward_threshold);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < matches_.size(); ++i) {
    const cv::Point2f to = scratch_to_[i] + origin;
    const cv::Point2f back = scratch_back_[i] - scratch_from_[i];
    if (!scratch_status_[i] || !scratch_back_status_[i] || !(std::hypot(back.x, back.y) <= max_return)) continue;
    const Eigen::Vector2f pixel(to.x, to.y);
    if (!intrinsics_.contains(pixel.x(), pixel.y()) || !mask.usable(pixel)) {
      ++n_out_of_view_;
      continue;
    }
    matches_[kept] = matches_[i];
    matches_[kept++].image_point = pixel;
  }
  matches_.resize(kept);
}

void FlowModality::drop_turned_away_points() {
  const Posef T = camera_T_body().cast<float>();
  const auto turned_away = [&](const Match& m) {
    if (m.body_normal.isZero()) return false;
    const Eigen::Vector3f X = T * m.body_point;
    return (T.rotation() * m.body_normal).dot(-X) <= kMinViewCosine * X.norm();
  };
  const auto first_turned_away = std::remove_if(matches_.begin(), matches_.end(), turned_away);
  n_out_of_view_ += static_cast<int>(matches_.end() - first_turned_away);
  matches_.erase(first_turned_away, matches_.end());
}

void FlowModality::start(const Frame& frame, const Renders& renders) {
  load_image(color_image(frame));
  frames_.forget_previous();
  noise_.reset();
  quality_ = {};
  frames_since_start_ = 0;
  renew_points(frame, renders);
}

void FlowModality::correspondences(const Frame& frame, const Renders&, int corr_iter) {
  // The flow does not depend on the pose: once per frame is enough.
  if (corr_iter == 0) {
    const ColorImage& color = color_image(frame);
    if (load_image(color)) {
      track_points(color.mask);
    } else {
      matches_.clear();
      size_changed_ = true;
    }
    drop_turned_away_points();
  }
  estimate_reprojection_noise(noise_, matches_, camera_T_body().cast<float>(), intrinsics_);
  update_weights(corr_iter);
  last_corr_iter_ = corr_iter;
}

double FlowModality::sigma(int corr_iter) const {
  return noise_.sigma(iteration_value(params_.standard_deviations, corr_iter));
}

double FlowModality::scale(int corr_iter) const {
  return noise_.scale(iteration_value(params_.standard_deviations, corr_iter));
}

void FlowModality::update_weights(int corr_iter) {
  const Posef T = camera_T_body().cast<float>();
  const double s = scale(corr_iter);
  for (Match& m : matches_) {
    const Eigen::Vector3f X = T * m.body_point;
    m.weight = X.z() > 0.f ? noise_.weight((intrinsics_.project<float>(X) - m.image_point).norm(), s) : 0.f;
  }
}

CueTerms FlowModality::gradient_hessian(int corr_iter, int) {
  update_weights(corr_iter);
  return reprojection_terms(matches_, camera_T_body().cast<float>(), intrinsics_, static_cast<float>(sigma(corr_iter)));
}

double FlowModality::log_likelihood(int corr_iter) const {
  return reprojection_log_likelihood(matches_, camera_T_body(), intrinsics_, sigma(corr_iter));
}

void FlowModality::append_residuals(std::vector<double>& residuals, std::vector<double>& weights) const {
  append_reprojection_residuals(matches_, camera_T_body(), intrinsics_, residuals, weights);
}

void FlowModality::append_image_features(std::vector<ImageFeature>& features) const {
  for (const Match& m : matches_) features.push_back({m.image_point.cast<double>(), m.weight});
}

bool FlowModality::renewal_due() const {
  if (size_changed_ || n_lifted_ < 0) return true;
  const double turned = rotation_angle_between(camera_R_body_at_renewal_, camera_T_body().rotation()) * 180.0 / M_PI;
  return static_cast<double>(matches_.size()) < params_.renew_fraction * n_lifted_ ||
         turned > params_.renew_rotation_deg;
}

std::optional<RenderRequest> FlowModality::corner_render(const Frame& frame) const {
  const ColorImage& color = color_image(frame);
  return focused_render_request(color_camera_, color.intrinsics, color.camera_T_reference, body().reference_T_body,
                                sphere_, kCornerRenderSize);
}

std::vector<RenderRequest> FlowModality::render_requests(const Frame& frame, Stage stage) const {
  const bool corners = stage.kind == Stage::kStart || (stage.kind == Stage::kFinish && renewal_due());
  if (!corners) return {};
  if (std::optional<RenderRequest> request = corner_render(frame)) return {*request};
  return {};
}

cv::Mat FlowModality::body_mask(const FocusedRender& render, std::uint8_t body_id, const cv::Rect& roi) const {
  const Intrinsics& crop_k = render.intrinsics;
  const double su = crop_k.fu / intrinsics_.fu, sv = crop_k.fv / intrinsics_.fv;
  cv::Mat mask(roi.size(), CV_8UC1, cv::Scalar(0));
  for (int r = 0; r < roi.height; ++r) {
    const int row = round_to_int(static_cast<float>(crop_k.pv + (roi.y + r - intrinsics_.pv) * sv));
    if (row < 0 || row >= render.ids.rows) continue;
    const std::uint8_t* ids = render.ids.ptr<std::uint8_t>(row);
    std::uint8_t* out = mask.ptr<std::uint8_t>(r);
    for (int c = 0; c < roi.width; ++c) {
      const int col = round_to_int(static_cast<float>(crop_k.pu + (roi.x + c - intrinsics_.pu) * su));
      if (col >= 0 && col < render.ids.cols && ids[col] == body_id) out[c] = 255;
    }
  }
  if (params_.mask_border > 0) {
    const int side = 2 * params_.mask_border + 1;
    cv::erode(mask, mask, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(side, side)));
  }
  return mask;
}

void FlowModality::renew_points(const Frame& frame, const Renders& renders) {
  matches_.clear();
  n_lifted_ = kNeverLifted;
  n_out_of_view_ = 0;
  size_changed_ = false;
  const std::optional<RenderRequest> request = corner_render(frame);
  if (!request) return;
  const ColorImage& color = color_image(frame);
  const cv::Rect roi = cv::Rect(static_cast<int>(std::floor(request->square.u_min)),
                                static_cast<int>(std::floor(request->square.v_min)),
                                static_cast<int>(std::ceil(request->square.size)) + 1,
                                static_cast<int>(std::ceil(request->square.size)) + 1) &
                       cv::Rect(0, 0, frames_.grey().cols, frames_.grey().rows);
  if (roi.empty()) return;
  const FocusedRender& render = renders.at(*request);
  const std::uint8_t body_id = renders.id(body().name);
  cv::Mat mask = body_mask(render, body_id, roi);
  if (!color.mask.all_pixels()) mask &= color.mask.mask(roi) != 0;
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(frames_.grey()(roi), corners, params_.max_features, params_.quality, params_.min_distance,
                          mask, params_.block_size, params_.use_harris, params_.harris_k);
  for (cv::Point2f& p : corners) p += cv::Point2f(static_cast<float>(roi.x), static_cast<float>(roi.y));

  const bool measure = params_.occlusion.measure && !depth_camera_.empty();
  const DepthImage* depth = measure ? frame.find_depth(depth_camera_) : nullptr;
  if (depth && !depth->delivered()) depth = nullptr;
  if (depth && depth->depth.type() != CV_32FC1)
    throw std::invalid_argument("flow modality of '" + body().name + "': camera '" + depth_camera_ +
                                "' must give a CV_32FC1 depth image");
  const Pose depth_T_camera = depth ? depth->camera_T_reference * camera_T_reference_.inverse() : Pose();
  for (const SurfacePoint& p : lifter_.lift(intrinsics_, camera_T_body(), render, body_id, corners, depth,
                                            depth_T_camera))
    matches_.push_back({p.body_point, p.body_normal, Eigen::Vector2f(corners[p.index].x, corners[p.index].y), 1.f});
  n_lifted_ = static_cast<int>(matches_.size());
  camera_R_body_at_renewal_ = camera_T_body().rotation();
}

void FlowModality::finish(const Frame& frame, const Renders& renders) {
  int n_inliers = 0;
  for (const Match& m : matches_)
    if (m.weight > 0.f) ++n_inliers;
  const int n_expected = n_lifted_ - n_out_of_view_;
  quality_.n_valid = n_inliers;
  quality_.valid_fraction = n_expected > 0 ? static_cast<double>(matches_.size()) / n_expected : 0.0;
  quality_.score = n_expected > 0 ? static_cast<double>(n_inliers) / n_expected : 0.0;
  // Like the texture cue's keyframes, corners lifted at the start pose would confirm it on
  // the first frame whatever it is: the flow vouches once the other cues had a frame to
  // confirm that pose. Too few corners are chance, not evidence.
  quality_.just_started = frames_since_start_ == 0;
  quality_.abstained = n_expected < params_.min_points || quality_.just_started;
  ++frames_since_start_;
  quality_.sigma = sigma(last_corr_iter_);
  if (renewal_due()) renew_points(frame, renders);
}

}  // namespace icgp
