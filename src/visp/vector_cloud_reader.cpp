// SPDX-License-Identifier: GPL-2.0-or-later
#include "vector_cloud_reader.h"

namespace icgp {

void VectorCloudReader::operator()(const std::vector<cv::Point>& pixels, std::vector<Eigen::Vector3f>& points) const {
  points.resize(pixels.size());
  for (std::size_t i = 0; i < pixels.size(); ++i)
    points[i] = point(static_cast<std::size_t>(pixels[i].y) * width_ + static_cast<std::size_t>(pixels[i].x));
}

}  // namespace icgp
