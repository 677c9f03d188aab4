// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/detection/training_views.h"

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "icgp/model/icosphere.h"

namespace icgp {
namespace {

/// The training camera's distance in sphere radii, its directions (icosphere
/// subdivisions) and image sizes: render_training_views.
constexpr double kDistanceRadii = 4.0;
constexpr int kViewDivides = 1;
constexpr int kViewSizes[] = {320, 100};
/// Pixels of the body next to its outline are left out of the mask: keypoints there
/// describe the render's background as much as the body.
constexpr int kOutlineMarginPx = 3;

}  // namespace

bool TrainingView::lift(float u, float v, Eigen::Vector3f& body_point) const {
  const int col = static_cast<int>(std::lround(u)), row = static_cast<int>(std::lround(v));
  if (col < 0 || row < 0 || col >= depth.cols || row >= depth.rows) return false;
  const float z = depth.at<float>(row, col);
  if (!(z > 0.f)) return false;
  const Eigen::Vector3d camera_point = intrinsics.back_project<double>(u, v, z);
  body_point = (camera_T_body.inverse() * camera_point).cast<float>();
  return true;
}

std::vector<TrainingView> render_training_views(SceneRenderer& renderer, const Body& body) {
  const Sphere sphere = bounding_sphere(body.mesh);
  const double distance = kDistanceRadii * sphere.radius;
  const cv::Mat outline_margin =
      cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * kOutlineMarginPx + 1, 2 * kOutlineMarginPx + 1});
  std::vector<TrainingView> views;
  Body shown = body;
  for (const int size : kViewSizes) {
    // A camera whose image the sphere just fills; the focused render then is that image.
    const Intrinsics camera = Intrinsics::centred(size, size, 0.5 * size * distance / sphere.radius);
    for (const Eigen::Vector3f& d : icosphere_directions(kViewDivides)) {
      const Eigen::Vector3d direction = d.cast<double>();
      const Eigen::Vector3d up = std::abs(direction.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
      shown.reference_T_body = look_at<double>(sphere.centre + distance * direction, sphere.centre, up);
      std::optional<RenderRequest> request =
          focused_render_request("training", camera, Pose(), shown.reference_T_body, sphere, size);
      if (!request) continue;
      request->targets = kRenderDepth | kRenderColor | kRenderIds;
      Renders renders;
      renderer.render({&shown}, {*request}, renders);
      const FocusedRender& render = renders.at(*request);
      TrainingView view;
      view.camera_T_body = shown.reference_T_body;
      view.intrinsics = render.intrinsics;
      cv::cvtColor(render.color, view.grey, cv::COLOR_BGR2GRAY);
      view.depth = render.depth.clone();
      cv::erode(render.ids == renders.id(body.name), view.mask, outline_margin);
      views.push_back(std::move(view));
    }
  }
  return views;
}

}  // namespace icgp
