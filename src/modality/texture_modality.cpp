// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/modality/texture_modality.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "icgp/features/daisy.h"
#include "icgp/features/freak.h"
#include "icgp/features/hamming_matching.h"
#include "icgp/features/oriented_brief.h"
#include "icgp/geometry/rounding.h"
#include "icgp/modality/cue_images.h"
#include "icgp/modality/iteration_value.h"
#include "icgp/modality/reprojection_terms.h"

namespace icgp {
namespace {

bool uses_orb_detector(Descriptor descriptor) {
  return descriptor == Descriptor::kFreak || descriptor == Descriptor::kDaisy;
}

cv::Ptr<cv::Feature2D> make_orb(const TextureParams& p) {
  return cv::ORB::create(p.orb_n_features, static_cast<float>(p.orb_scale_factor), p.orb_n_levels);
}

/// Affine map from full-image to crop coordinates (pixel-centre convention, as
/// Intrinsics::cropped): u_crop = s (u − u_min + 0.5) − 0.5.
struct CropMap {
  double scale, u_min, v_min;
  cv::Point2f to_image(const cv::Point2f& c) const {
    return {static_cast<float>((c.x + 0.5) / scale + u_min - 0.5), static_cast<float>((c.y + 0.5) / scale + v_min - 0.5)};
  }
};

}  // namespace

cv::Ptr<cv::Feature2D> make_descriptor(Descriptor descriptor, const TextureParams& p) {
  switch (descriptor) {
    case Descriptor::kOrb: return make_orb(p);
    case Descriptor::kBrisk: return cv::BRISK::create();
    case Descriptor::kAkaze: return cv::AKAZE::create();
    case Descriptor::kSift:
      return cv::SIFT::create(0, p.sift_n_octave_layers, p.sift_contrast_threshold, p.sift_edge_threshold, p.sift_sigma);
    case Descriptor::kFreak: return Freak::create();
    case Descriptor::kDaisy: return Daisy::create();
    case Descriptor::kOrientedBrief: return OrientedBrief::create(p.orb_n_features);
  }
  throw std::invalid_argument("texture descriptor " + std::to_string(static_cast<int>(descriptor)) +
                              " is not a Descriptor");
}

FeatureExtractor::FeatureExtractor(const TextureParams& params)
    : descriptor_(make_descriptor(params.descriptor, params)), size_(params.focused_image_size) {
  detector_ = uses_orb_detector(params.descriptor) ? make_orb(params) : descriptor_;
}

void FeatureExtractor::extract(const cv::Mat& image, const ImageSquare& square, std::vector<cv::Point2f>& points,
                               cv::Mat& descriptors) {
  points.clear();
  descriptors.release();
  keypoints_.clear();
  const bool overlaps = square.size > 0.0 && square.u_min < image.cols && square.v_min < image.rows &&
                        square.u_min + square.size > 0.0 && square.v_min + square.size > 0.0;
  if (!overlaps) return;
  // A square snapped to whole pixels that lies inside the image is cut out, made grey and
  // resized (cv::resize is SIMD and 2.4x faster than a general warp, and one channel costs
  // half of three); otherwise the exact square is warped with replicated borders (a
  // constant border would add corners where the crop leaves the image). Both follow the
  // pixel-centre convention of CropMap.
  const cv::Rect snapped(cvRound(square.u_min), cvRound(square.v_min), std::max(1, cvRound(square.size)),
                         std::max(1, cvRound(square.size)));
  CropMap map{0.0, 0.0, 0.0};
  if ((snapped & cv::Rect(0, 0, image.cols, image.rows)) == snapped) {
    map = {static_cast<double>(size_) / snapped.width, static_cast<double>(snapped.x), static_cast<double>(snapped.y)};
    cv::Mat cut = image(snapped);
    if (cut.channels() == 3) {
      cv::cvtColor(cut, crop_, cv::COLOR_BGR2GRAY);
      cut = crop_;
    }
    cv::resize(cut, grey_, cv::Size(size_, size_), 0.0, 0.0, cv::INTER_LINEAR);
  } else {
    map = {size_ / square.size, square.u_min, square.v_min};
    const cv::Matx23d to_crop(map.scale, 0.0, map.scale * (0.5 - map.u_min) - 0.5,  //
                              0.0, map.scale, map.scale * (0.5 - map.v_min) - 0.5);
    const bool colour = image.channels() == 3;
    cv::warpAffine(image, colour ? crop_ : grey_, to_crop, cv::Size(size_, size_), cv::INTER_LINEAR,
                   cv::BORDER_REPLICATE);
    if (colour) cv::cvtColor(crop_, grey_, cv::COLOR_BGR2GRAY);
  }
  if (detector_ == descriptor_) {
    descriptor_->detectAndCompute(grey_, cv::noArray(), keypoints_, descriptors);
  } else {
    detector_->detect(grey_, keypoints_);
    descriptor_->compute(grey_, keypoints_, descriptors);
  }
  points.reserve(keypoints_.size());
  for (const cv::KeyPoint& kp : keypoints_) points.push_back(map.to_image(kp.pt));
}

TextureModality::TextureModality(Body& body, TextureParams params)
    : Modality(body),
      params_(std::move(params)),
      extractor_(params_),
      lifter_(MeasuredOcclusion{params_.occlusion.radius, params_.occlusion.threshold}),
      matcher_(extractor_.norm()),
      crop_(body, params_.color_camera, params_.occlusion.render_size),
      noise_(params_.noise) {}

const ColorImage& TextureModality::color_image(const Frame& frame) const {
  return cue_color_image(frame, params_.color_camera, name(), body());
}

Pose TextureModality::camera_T_body() const { return camera_T_reference_ * body().reference_T_body; }

void TextureModality::detect(const Frame& frame) {
  const ColorImage& color = color_image(frame);
  intrinsics_ = color.intrinsics;
  camera_T_reference_ = color.camera_T_reference;
  const Eigen::Vector3d centre = camera_T_body() * crop_.sphere().centre;
  if (!(centre.z() > crop_.sphere().radius)) {
    points_.clear();
    descriptors_.release();
    return;
  }
  extractor_.extract(color.image, square_around_sphere(intrinsics_, centre, crop_.sphere().radius), points_, descriptors_);
  if (!color.mask.all_pixels()) drop_masked_points(color.mask);
}

void TextureModality::drop_masked_points(const PixelMask& mask) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    if (!mask.usable(Eigen::Vector2f(points_[i].x, points_[i].y))) continue;
    if (kept != i) descriptors_.row(static_cast<int>(i)).copyTo(descriptors_.row(static_cast<int>(kept)));
    points_[kept++] = points_[i];
  }
  points_.resize(kept);
  descriptors_ = descriptors_.rowRange(0, static_cast<int>(kept));
}

std::optional<RenderRequest> TextureModality::keyframe_render(const Frame& frame) const {
  const ColorImage& color = color_image(frame);
  return focused_render_request(params_.color_camera, color.intrinsics, color.camera_T_reference,
                                body().reference_T_body, crop_.sphere(), params_.focused_image_size);
}

bool TextureModality::keyframe_due(const Pose& camera_T_body, int age) const {
  const double angle = rotation_angle_between(keyframe_.camera_R_body, camera_T_body.rotation()) * 180.0 / M_PI;
  const bool old = params_.keyframe_max_age > 0 && age >= params_.keyframe_max_age;
  return angle > params_.keyframe_orientation_threshold_deg || old;
}

std::vector<RenderRequest> TextureModality::render_requests(const Frame& frame, Stage stage) const {
  if (stage.kind == Stage::kCorrespondences) {
    const ColorImage& color = color_image(frame);
    std::optional<RenderRequest> request;
    if (params_.occlusion.model)
      request = crop_.request(stage, color.intrinsics, color.camera_T_reference);
    return request ? std::vector<RenderRequest>{*request} : std::vector<RenderRequest>{};
  }
  const bool keyframe = stage.kind == Stage::kStart ||
                        (stage.kind == Stage::kFinish &&
                         keyframe_due(color_image(frame).camera_T_reference * body().reference_T_body, keyframe_.age + 1));
  if (!keyframe) return {};
  if (auto request = keyframe_render(frame)) return {*request};
  return {};
}

void TextureModality::make_keyframe(const Frame& frame, const Renders& renders) {
  const std::optional<RenderRequest> request = keyframe_render(frame);
  if (!request) {
    keyframe_ = Keyframe{};
    return;
  }
  // Measured occlusions need depth; a frame without it (a colour-only camera) keeps every
  // keypoint on the rendered silhouette, as the region modality keeps its lines.
  const bool measure = params_.occlusion.measure && !params_.depth_camera.empty();
  const DepthImage* depth = measure ? frame.find_depth(params_.depth_camera) : nullptr;
  if (depth && !depth->delivered()) depth = nullptr;
  if (depth) {
    if (depth->depth.type() != CV_32FC1)
      throw std::invalid_argument("texture modality of '" + body().name + "': camera '" + params_.depth_camera +
                                  "' must give a CV_32FC1 depth image");
  }
  const Pose depth_T_camera = depth ? depth->camera_T_reference * camera_T_reference_.inverse() : Pose();
  const std::vector<SurfacePoint> lifted =
      lifter_.lift(intrinsics_, camera_T_body(), renders.at(*request), renders.id(body().name), points_, depth,
                   depth_T_camera);
  keyframe_ = Keyframe{};
  keyframe_.camera_R_body = camera_T_body().rotation();
  if (lifted.empty()) return;
  keyframe_.descriptors.create(static_cast<int>(lifted.size()), descriptors_.cols, descriptors_.type());
  for (std::size_t j = 0; j < lifted.size(); ++j) {
    keyframe_.body_points.push_back(lifted[j].body_point);
    keyframe_.image_points.push_back(points_[lifted[j].index]);
    descriptors_.row(lifted[j].index).copyTo(keyframe_.descriptors.row(static_cast<int>(j)));
  }
}

void TextureModality::start(const Frame& frame, const Renders& renders) {
  detect(frame);
  make_keyframe(frame, renders);
  matches_.clear();
  noise_.reset();
  others_step_.setZero();
  others_covariance_.setZero();
  quality_ = {};
  frames_since_start_ = 0;
}

void TextureModality::match() {
  matches_.clear();
  if (descriptors_.empty() || keyframe_.descriptors.rows < 2) return;
  nearest_.clear();
  if (extractor_.norm() == cv::NORM_HAMMING) {
    two_nearest_hamming(descriptors_, keyframe_.descriptors, nearest_);
  } else {
    knn_.clear();  // knnMatch appends
    matcher_.knnMatch(descriptors_, keyframe_.descriptors, knn_, 2);
    for (const std::vector<cv::DMatch>& m : knn_)
      nearest_.push_back(m.size() == 2 ? TwoNearest{m[0].trainIdx, m[0].distance, m[1].distance} : TwoNearest{-1, 0.f, 0.f});
  }
  const float ratio = static_cast<float>(params_.ratio_test);
  for (std::size_t q = 0; q < nearest_.size(); ++q) {
    const TwoNearest& n = nearest_[q];
    if (n.train_index < 0 || n.best >= ratio * n.second) continue;
    matches_.push_back({keyframe_.body_points[n.train_index], Eigen::Vector2f(points_[q].x, points_[q].y),
                        n.train_index, 1.f});
  }
}

void TextureModality::correspondences(const Frame& frame, const Renders& renders, int corr_iter) {
  // Keypoints and matches do not depend on the pose: once per frame is enough.
  if (corr_iter == 0) {
    detect(frame);
    match();
    const ColorImage& color = color_image(frame);
    scene_ = crop_.find(renders, color.intrinsics, color.camera_T_reference);
  }
  update_weights();
  estimate_noise();
  last_corr_iter_ = corr_iter;
}

void TextureModality::estimate_noise() {
  const Pose camera_T_body = this->camera_T_body();
  estimate_reprojection_noise(noise_, matches_, camera_T_body.cast<float>(), intrinsics_);
  const double own_fit = noise_.estimated();
  const Posef at_others = camera_T_body.updated_in_body_frame(others_step_).cast<float>();
  estimate_reprojection_noise(noise_, matches_, at_others, intrinsics_);
  // The others' pose is uncertain too: that spread of the residuals there is not this cue's
  // noise, and only a significant excess over its own fit shows a bias.
  noise_.discount(reprojection_spread(matches_, at_others, intrinsics_, others_covariance_.cast<float>()), own_fit);
}

double TextureModality::sigma(int corr_iter) const {
  return noise_.sigma(iteration_value(params_.standard_deviations, corr_iter));
}

void TextureModality::update_weights() {
  const Posef T = camera_T_body().cast<float>();
  const float inverse_c2 = static_cast<float>(1.0 / (params_.tukey_norm_constant * params_.tukey_norm_constant));
  for (Match& m : matches_) {
    const Eigen::Vector3f X = T * m.body_point;
    if (X.z() <= 0.f) {
      m.weight = 0.f;
      continue;
    }
    const float u = (intrinsics_.project<float>(X) - m.image_point).squaredNorm() * inverse_c2;
    m.weight = u <= 1.f ? 1.f - u + u * u / 3.f : 1.f / (3.f * u);
  }
}

CueTerms TextureModality::gradient_hessian(int corr_iter, int) {
  update_weights();
  return reprojection_terms(matches_, camera_T_body().cast<float>(), intrinsics_,
                            static_cast<float>(this->sigma(corr_iter)));
}

double TextureModality::log_likelihood(int corr_iter) const {
  return reprojection_log_likelihood(matches_, camera_T_body(), intrinsics_, sigma(corr_iter));
}

void TextureModality::append_residuals(std::vector<double>& residuals, std::vector<double>& weights) const {
  append_reprojection_residuals(matches_, camera_T_body(), intrinsics_, residuals, weights);  // Tukey weights
}

void TextureModality::append_image_features(std::vector<ImageFeature>& features) const {
  for (const Match& m : matches_) features.push_back({m.image_point.cast<double>(), m.weight});
}

void TextureModality::finish(const Frame& frame, const Renders& renders) {
  update_quality(color_image(frame).mask);
  ++frames_since_start_;
  ++keyframe_.age;
  if (keyframe_due(camera_T_body(), keyframe_.age)) make_keyframe(frame, renders);
}

void TextureModality::update_quality(const PixelMask& mask) {
  const Posef T = camera_T_body().cast<float>();
  const float inlier = 0.5f * static_cast<float>(params_.tukey_norm_constant);
  int n_inliers = 0;
  for (const Match& m : matches_) {
    const Eigen::Vector3f X = T * m.body_point;
    if (X.z() > 0.f && (intrinsics_.project<float>(X) - m.image_point).norm() < inlier) ++n_inliers;
  }
  // Fewer inliers than a pose needs to be determined (4, as for PnP) confirm nothing:
  // that many agree by chance on a frame without the object.
  if (n_inliers < 4) n_inliers = 0;
  // Keyframe points the camera cannot see now (outside the image or the mask) or another
  // body hides cannot match: they are not expected to.
  int n_unseen = 0;
  for (const Eigen::Vector3f& p : keyframe_.body_points) {
    const Eigen::Vector3f X = T * p;
    const Eigen::Vector2f pixel = intrinsics_.project<float>(X);
    const bool seen = X.z() > 0.f && intrinsics_.contains(pixel.x(), pixel.y()) && mask.usable(pixel) &&
                      (scene_.empty() || !scene_.hidden(X, 0.f, params_.occlusion.modeled_radius,
                                                        params_.occlusion.modeled_threshold));
    n_unseen += !seen;
  }
  const int n_points = static_cast<int>(keyframe_.body_points.size()) - n_unseen;
  quality_.n_valid = static_cast<int>(matches_.size());
  quality_.valid_fraction = n_points > 0 ? std::min(1.0, static_cast<double>(matches_.size()) / n_points) : 0.0;
  quality_.score = n_points > 0 ? std::min(1.0, static_cast<double>(n_inliers) / n_points) : 0.0;
  // The first frame after a (re)start is matched to the keyframe lifted at the start pose,
  // which nothing has confirmed: a wrong start pose would match itself perfectly. Texture
  // tells how the object moved since its keyframe, not where it is, so it only vouches once
  // the other cues have had a frame to confirm that pose.
  quality_.just_started = frames_since_start_ == 0;
  quality_.abstained = n_points < params_.min_keyframe_points || quality_.just_started;
  quality_.sigma = sigma(last_corr_iter_);
}

}  // namespace icgp
