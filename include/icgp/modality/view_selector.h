// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>

#include "icgp/model/viewpoint_model.h"

namespace icgp {

/// Picks the model view for a camera direction, skipping the search over all views while
/// the direction stays within a hundredth of a degree of the last one searched (views are
/// degrees apart; the optimiser's last steps move far less).
class ViewSelector {
 public:
  int select(const ViewpointModel& model, const Eigen::Vector3f& direction) {
    constexpr float kCosTolerance = 0.99999998f;  // cos(0.0115 deg)
    if (view_ < 0 || direction.dot(direction_) < kCosTolerance) {
      view_ = model.closest_view(direction);
      direction_ = direction;
    }
    return view_;
  }
  void reset() { view_ = -1; }

 private:
  int view_ = -1;
  Eigen::Vector3f direction_ = Eigen::Vector3f::Zero();
};

}  // namespace icgp
