// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/detection/texture_alignment.h"

#include <cmath>

#include <Eigen/Geometry>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "point_correspondences.h"

namespace icgp {
namespace {

/// Side of the render the corners are taken from: the body's detail at about the image's
/// own scale for a body up to this many pixels across.
constexpr int kRenderSize = 256;
/// Shi-Tomasi corners of the render: at most this many, this far apart (pixels), above
/// this share of the strongest corner's response.
constexpr int kCorners = 300;
constexpr double kCornerQuality = 0.01;
constexpr double kCornerSpacingPx = 4.0;
/// Lucas-Kanade: window and pyramid levels (follows up to about 20 pixels of offset).
constexpr int kFlowWindow = 21;
constexpr int kFlowLevels = 3;
/// PnP over the followed corners: the reprojection error of an inlier, and the fewest
/// inliers a pose is taken from.
constexpr float kInlierPx = 2.0f;
constexpr int kMinInliers = 20;
constexpr int kRansacIterations = 100;
constexpr double kRansacConfidence = 0.99;
constexpr int kRounds = 2;

}  // namespace

TextureAlignment::TextureAlignment(SceneRenderer& renderer, const Body& body)
    : renderer_(renderer), body_(body), sphere_(bounding_sphere(body.mesh)) {}

std::optional<Pose> TextureAlignment::align(const cv::Mat& grey, const Intrinsics& K, const Pose& camera_T_reference,
                                            const Pose& reference_T_body, const std::vector<Body*>& occluders) {
  std::optional<Pose> pose;
  Pose current = reference_T_body;
  for (int r = 0; r < kRounds; ++r) {
    const std::optional<Pose> next = round(grey, K, camera_T_reference, current, occluders);
    if (!next) break;
    pose = current = *next;
  }
  return pose;
}

std::optional<Pose> TextureAlignment::round(const cv::Mat& grey, const Intrinsics& K, const Pose& camera_T_reference,
                                            const Pose& reference_T_body, const std::vector<Body*>& occluders) {
  std::optional<RenderRequest> request =
      focused_render_request("alignment", K, camera_T_reference, reference_T_body, sphere_, kRenderSize);
  if (!request) return std::nullopt;
  request->targets = kRenderDepth | kRenderColor | kRenderIds;
  body_.reference_T_body = reference_T_body;
  std::vector<const Body*> shown{&body_};
  shown.insert(shown.end(), occluders.begin(), occluders.end());
  Renders renders;
  renderer_.render(shown, {*request}, renders);
  const FocusedRender& render = renders.at(*request);
  cv::Mat rendered;
  cv::cvtColor(render.color, rendered, cv::COLOR_BGR2GRAY);
  const cv::Mat on_body = render.ids == renders.id(body_.name);
  cv::Mat inside;
  cv::erode(on_body, inside, cv::Mat(), cv::Point(-1, -1), 2);  // corners on the outline see the background too

  // The image resampled onto the render's pixel grid: crop pixel (x, y) is image pixel
  // ((x - pu_c) fu / fu_c + pu, ...), so that flow starts at zero offset.
  const Intrinsics& crop = render.intrinsics;
  const double su = K.fu / crop.fu, sv = K.fv / crop.fv;
  const cv::Matx23d crop_to_image(su, 0.0, K.pu - crop.pu * su, 0.0, sv, K.pv - crop.pv * sv);
  cv::Mat patch;
  cv::warpAffine(grey, patch, crop_to_image, rendered.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                 cv::BORDER_REPLICATE);

  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(rendered, corners, kCorners, kCornerQuality, kCornerSpacingPx, inside);
  if (static_cast<int>(corners.size()) < kMinInliers) return std::nullopt;
  std::vector<cv::Point2f> followed;
  std::vector<std::uint8_t> status;
  std::vector<float> error;
  cv::calcOpticalFlowPyrLK(rendered, patch, corners, followed, status, error, cv::Size(kFlowWindow, kFlowWindow),
                           kFlowLevels);
  const Pose camera_T_body = camera_T_reference * reference_T_body;
  const Pose body_T_camera = camera_T_body.inverse();
  PointCorrespondences followed_points;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    if (!status[i]) continue;
    const int col = static_cast<int>(std::lround(corners[i].x)), row = static_cast<int>(std::lround(corners[i].y));
    const float z = render.depth.at<float>(row, col);
    if (!(z > 0.f)) continue;
    const Eigen::Vector3d X = body_T_camera * crop.back_project<double>(corners[i].x, corners[i].y, z);
    const cv::Vec2d p = crop_to_image * cv::Vec3d(followed[i].x, followed[i].y, 1.0);
    followed_points.add(X.cast<float>(), cv::Point2f(static_cast<float>(p[0]), static_cast<float>(p[1])));
  }
  if (static_cast<int>(followed_points.size()) < kMinInliers) return std::nullopt;
  // RANSAC from the pose the render was made at.
  const Eigen::AngleAxisd turn(camera_T_body.rotation());
  const Eigen::Vector3d rotation_vector = turn.angle() * turn.axis();
  cv::Mat rvec = (cv::Mat_<double>(3, 1) << rotation_vector.x(), rotation_vector.y(), rotation_vector.z());
  cv::Mat tvec = (cv::Mat_<double>(3, 1) << camera_T_body.translation().x(), camera_T_body.translation().y(),
                  camera_T_body.translation().z());
  std::vector<int> inliers;
  if (!cv::solvePnPRansac(followed_points.model, followed_points.image, camera_matrix(K), cv::noArray(), rvec, tvec,
                          true, kRansacIterations, kInlierPx, kRansacConfidence, inliers, cv::SOLVEPNP_ITERATIVE) ||
      static_cast<int>(inliers.size()) < kMinInliers)
    return std::nullopt;
  const std::optional<Pose> aligned = refined_pose(followed_points.subset(inliers), K, rvec, tvec);
  if (!aligned) return std::nullopt;
  return camera_T_reference.inverse() * *aligned;
}

}  // namespace icgp
