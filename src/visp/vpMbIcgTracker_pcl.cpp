// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker's PCL overloads, alone in this file: PCL's headers take long to compile.
// Only PCL's header-only point-cloud templates are used, so nothing links against PCL.
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <visp3/core/vpException.h>

#include "vpMbIcgTracker_impl.h"

namespace {

template <typename Point>
void require_organised(const pcl::PointCloud<Point>& cloud, const std::string& camera) {
  if (cloud.height <= 1 || cloud.points.size() != static_cast<std::size_t>(cloud.width) * cloud.height)
    throw vpException(vpException::badValue, "vpMbIcgTracker::track: the point cloud of \"" + camera +
                                                 "\" must be organised (one point per pixel), got " +
                                                 std::to_string(cloud.points.size()) + " points as " +
                                                 std::to_string(cloud.width) + " x " + std::to_string(cloud.height));
}

/// The point of an organised cloud's pixel.
template <typename Point>
Eigen::Vector3f cloud_point(const pcl::PointCloud<Point>& cloud, int row, int col) {
  const Point& p = cloud.points[static_cast<std::size_t>(row) * cloud.width + col];
  return {p.x, p.y, p.z};
}

/// The cloud as a camera's depth (icgp::visp_detail::read_cloud).
template <typename Point>
icgp::visp_detail::DepthInput depth_of_cloud(const std::string& camera, const std::shared_ptr<const pcl::PointCloud<Point>>& cloud,
                                             const vpCameraParameters& parameters) {
  if (!cloud) throw vpException(vpException::badValue, "vpMbIcgTracker::track: the point cloud of camera '" + camera + "' is null");
  icgp::visp_detail::DepthInput depth{camera, cloud->width, cloud->height};
  icgp::visp_detail::require_depth_size("track", depth);
  require_organised(*cloud, camera);
  icgp::visp_detail::read_cloud(
      depth, [cloud](int row, int col) { return cloud_point(*cloud, row, col); }, parameters);
  return depth;
}

}  // namespace

void vpMbIcgTracker::track(std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                           std::map<std::string, std::shared_ptr<const pcl::PointCloud<pcl::PointXYZ>>>& mapOfPointClouds) {
  std::vector<DepthInput> depths;
  for (const auto& [camera, cloud] : mapOfPointClouds) depths.push_back(depth_of_cloud(camera, cloud, impl_->rig.at(camera, "track").parameters));
  track_frame(mapOfImages, depths, "track");
}

void vpMbIcgTracker::track(std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
                           std::map<std::string, std::shared_ptr<const pcl::PointCloud<pcl::PointXYZ>>>& mapOfPointClouds) {
  std::vector<DepthInput> depths;
  for (const auto& [camera, cloud] : mapOfPointClouds) depths.push_back(depth_of_cloud(camera, cloud, impl_->rig.at(camera, "track").parameters));
  track_frame(mapOfColorImages, depths, "track");
}

void vpMbIcgTracker::track(const std::shared_ptr<const pcl::PointCloud<pcl::PointXYZRGBA>>& cloud) {
  const std::string& camera = impl_->rig.reference();
  if (!impl_->rig.is_depth_camera(camera))
    throw vpException(vpException::badValue, "vpMbIcgTracker::track(cloud): a registered cloud is the reference camera's "
                                             "colour and depth, but camera '" + camera + "' has no depth tracker type");
  DepthInput depth = depth_of_cloud(camera, cloud, impl_->rig.reference_camera().parameters);
  vpImage<vpRGBa> color(cloud->height, cloud->width);
  for (std::size_t i = 0; i < cloud->points.size(); ++i) {
    const pcl::PointXYZRGBA& p = cloud->points[i];
    color.bitmap[i] = vpRGBa(p.r, p.g, p.b, p.a);
  }
  track_frame(std::map<std::string, const vpImage<vpRGBa>*>{{camera, &color}}, {depth}, "track(cloud)");
}
