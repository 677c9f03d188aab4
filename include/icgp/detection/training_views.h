// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "icgp/base/body.h"
#include "icgp/base/intrinsics.h"
#include "icgp/render/scene_renderer.h"

namespace icgp {

/// A render of a body from a known pose: what a keypoint detector learns its appearance
/// from, with the depth that lifts every pixel of it onto the model.
struct TrainingView {
  Pose camera_T_body;
  Intrinsics intrinsics;  ///< of `grey`, `depth` and `mask`
  cv::Mat grey;           ///< CV_8UC1 shaded render, the texture included
  cv::Mat depth;          ///< CV_32FC1 metric Z, 0 off the body
  cv::Mat mask;           ///< CV_8UC1 255 on the body, away from its outline

  /// The body-frame point seen at pixel (u, v), or false off the body.
  bool lift(float u, float v, Eigen::Vector3f& body_point) const;
};

/// `body` rendered from the 42 directions of a once-subdivided icosphere about its bounding
/// sphere (about 30 degrees apart: ORB's descriptors hold over about that much turn out of
/// the image plane), from four sphere radii away (a perspective like a camera's at arm's
/// length), each at 320² and 100² pixels: ORB's eight levels 1.2 apart reach from each size
/// to 3.6 times smaller, so together a body from about 36 to 1100 pixels across is
/// matched. What icgp's KeypointModel and the vpKeyPoint baseline learn from.
std::vector<TrainingView> render_training_views(SceneRenderer& renderer, const Body& body);

}  // namespace icgp
