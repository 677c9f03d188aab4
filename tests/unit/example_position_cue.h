// SPDX-License-Identifier: GPL-2.0-or-later
// The smallest complete cue (docs/architecture.md): a measured position of the body's
// origin in the reference camera, with a standard deviation, as a fiducial marker or an
// external sensor would give it. It shows the measurement in the reference camera's image.
#pragma once

#include <cmath>
#include <optional>

#include "icgp/modality/modality.h"

namespace icgp::example {

class PositionCue final : public Modality {
 public:
  PositionCue(Body& body, const Eigen::Vector3d& measured, double sigma)
      : Modality(body), measured_(measured), sigma_(sigma) {}

  std::string name() const override { return "position"; }
  const std::string& camera() const override { return no_camera_; }  // it reads no image
  void start(const Frame&, const Renders&) override {}
  void correspondences(const Frame& frame, const Renders&, int) override {
    if (!frame.colors.empty()) image_ = frame.colors.front().intrinsics;
  }

  // ℓ = −‖t − p‖² / (2σ²). A body-frame variation θ moves the origin t by R θ_t.
  CueTerms gradient_hessian(int, int) override {
    const Eigen::Matrix3d R = body().reference_T_body.rotation();
    CueTerms terms;
    terms.gradient.tail<3>() = -R.transpose() * error() / (sigma_ * sigma_);
    terms.hessian.bottomRightCorner<3, 3>() = -Eigen::Matrix3d::Identity() / (sigma_ * sigma_);
    terms.n_correspondences = 1;
    return terms;
  }
  double log_likelihood(int) const override { return -error().squaredNorm() / (2.0 * sigma_ * sigma_); }

  void finish(const Frame&, const Renders&) override {}
  ModalityQuality quality() const override {
    ModalityQuality q;
    q.score = std::exp(-error().squaredNorm() / (2.0 * sigma_ * sigma_));  // 1 on the measurement
    q.valid_fraction = 1.0;
    q.n_valid = 1;
    q.sigma = sigma_;
    return q;
  }
  void append_image_features(std::vector<ImageFeature>& features) const override {
    if (image_ && measured_.z() > 0.0) features.push_back({image_->project(measured_), 1.0});
  }
  void append_residuals(std::vector<double>& residuals, std::vector<double>& weights) const override {
    for (int i = 0; i < 3; ++i) {
      residuals.push_back(error()[i]);
      weights.push_back(1.0);
    }
  }

 private:
  Eigen::Vector3d error() const { return body().reference_T_body.translation() - measured_; }

  Eigen::Vector3d measured_;
  double sigma_;
  std::string no_camera_;
  std::optional<Intrinsics> image_;  ///< the reference camera's, once a frame had one
};

}  // namespace icgp::example
