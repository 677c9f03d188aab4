// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker's PCL overloads, alone in this file: PCL's headers take long to compile.
// Only PCL's header-only point-cloud templates are used, so nothing links against PCL.
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <visp3/core/vpException.h>

#include "icgp/visp/vpMbIcgTracker.h"

namespace {

template <typename Point>
void require_organised(const pcl::PointCloud<Point>& cloud, const std::string& camera) {
  if (cloud.height <= 1 || cloud.points.size() != static_cast<std::size_t>(cloud.width) * cloud.height)
    throw vpException(vpException::badValue, "vpMbIcgTracker::track: the point cloud of \"" + camera +
                                                 "\" must be organised (one point per pixel), got " +
                                                 std::to_string(cloud.points.size()) + " points as " +
                                                 std::to_string(cloud.width) + " x " + std::to_string(cloud.height));
}

/// The organised cloud of "Camera2" from the map.
const pcl::PointCloud<pcl::PointXYZ>& depth_camera_cloud(
    std::map<std::string, std::shared_ptr<const pcl::PointCloud<pcl::PointXYZ>>>& clouds) {
  const pcl::PointCloud<pcl::PointXYZ>* cloud = nullptr;
  for (const auto& [name, c] : clouds) {
    if (name != "Camera2")
      throw vpException(vpException::badValue, "vpMbIcgTracker::track: unknown camera '" + name +
                                                   "' in the point clouds (the depth camera is \"Camera2\")");
    cloud = c.get();
  }
  if (!cloud) throw vpException(vpException::badValue, "vpMbIcgTracker::track: no point cloud of \"Camera2\"");
  require_organised(*cloud, "Camera2");
  return *cloud;
}

/// Z of an organised cloud's point.
template <typename Point>
float cloud_depth(const pcl::PointCloud<Point>& cloud, int row, int col) {
  return cloud.points[static_cast<std::size_t>(row) * cloud.width + col].z;
}

}  // namespace

void vpMbIcgTracker::track(std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                           std::map<std::string, std::shared_ptr<const pcl::PointCloud<pcl::PointXYZ>>>& mapOfPointClouds) {
  const pcl::PointCloud<pcl::PointXYZ>& cloud = depth_camera_cloud(mapOfPointClouds);
  track_with_depth(mapOfImages, cloud.width, cloud.height,
                   [&cloud](int row, int col) { return cloud_depth(cloud, row, col); });
}

void vpMbIcgTracker::track(std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
                           std::map<std::string, std::shared_ptr<const pcl::PointCloud<pcl::PointXYZ>>>& mapOfPointClouds) {
  const pcl::PointCloud<pcl::PointXYZ>& cloud = depth_camera_cloud(mapOfPointClouds);
  track_with_depth(mapOfColorImages, cloud.width, cloud.height,
                   [&cloud](int row, int col) { return cloud_depth(cloud, row, col); });
}

void vpMbIcgTracker::track(const std::shared_ptr<const pcl::PointCloud<pcl::PointXYZRGBA>>& cloud) {
  if (!cloud) throw vpException(vpException::badValue, "vpMbIcgTracker::track: null point cloud");
  require_organised(*cloud, "Camera1");
  vpImage<vpRGBa> color(cloud->height, cloud->width);
  for (std::size_t i = 0; i < cloud->points.size(); ++i) {
    const pcl::PointXYZRGBA& p = cloud->points[i];
    color.bitmap[i] = vpRGBa(p.r, p.g, p.b, p.a);
  }
  track_with_depth(color, cloud->width, cloud->height,
                   [&cloud](int row, int col) { return cloud_depth(*cloud, row, col); },
                   /*depthFromColorCamera=*/true);
}
