// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "icgp/model/viewpoint_model.h"

namespace icgp {

/// Picks the model view for a camera direction, skipping the search over all views while
/// the direction stays within a hundredth of a degree of the last one searched (views are
/// degrees apart; the optimiser's last steps move far less). Near the boundary between two
/// views the last view is kept until another is closer by a margin: otherwise a camera
/// resting there makes the estimate flip between two point sets from frame to frame, which
/// a visual servo turns into a limit cycle. The view returned can be read: a model still
/// being generated makes it first (ViewpointModel::require_view).
class ViewSelector {
 public:
  static constexpr float kHysteresisDegrees = 1.f;

  int select(const ViewpointModel& model, const Eigen::Vector3f& direction) {
    constexpr float kCosTolerance = 0.99999998f;  // cos(0.0115 deg)
    if (view_ >= 0 && direction.dot(direction_) >= kCosTolerance) return view_;
    direction_ = direction;
    const int closest = model.closest_view(direction);
    if (view_ < 0 || angle(model, view_, direction) > angle(model, closest, direction) + kHysteresis) view_ = closest;
    model.require_view(view_);
    return view_;
  }
  void reset() { view_ = -1; }

 private:
  static constexpr float kHysteresis = kHysteresisDegrees * 3.14159265f / 180.f;

  static float angle(const ViewpointModel& model, int view, const Eigen::Vector3f& direction) {
    return std::acos(std::clamp(model.view(view).direction.dot(direction), -1.f, 1.f));
  }

  int view_ = -1;
  Eigen::Vector3f direction_ = Eigen::Vector3f::Zero();
};

}  // namespace icgp
