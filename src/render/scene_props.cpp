// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/render/scene_props.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "icgp/base/splitmix64.h"

namespace icgp {
namespace {

/// The seeded_stream purpose of the clutter (the sequence writer's streams are 1, 3 and 4).
constexpr std::uint64_t kClutterStream = 2;

/// Clutter for the background: random filled rectangles, discs and thick lines on a
/// random base colour, so edges and colours vary at several scales.
cv::Mat clutter_texture(SplitMix64& random) {
  const auto colour = [&random] {
    return cv::Scalar(random.uniform(0, 256), random.uniform(0, 256), random.uniform(0, 256));
  };
  const auto point = [&random](int size) { return cv::Point(int(random.uniform(0, size)), int(random.uniform(0, size))); };
  constexpr int kSize = 512;
  cv::Mat texture(kSize, kSize, CV_8UC3, colour());
  for (int i = 0; i < 160; ++i) {
    switch (random.next() % 3) {
      case 0:
        cv::rectangle(texture, point(kSize), point(kSize), colour(), cv::FILLED);
        break;
      case 1:
        cv::circle(texture, point(kSize), int(random.uniform(4, 60)), colour(), cv::FILLED, cv::LINE_AA);
        break;
      default:
        cv::line(texture, point(kSize), point(kSize), colour(), int(random.uniform(1, 8)), cv::LINE_AA);
    }
  }
  return texture;
}

}  // namespace

cv::Mat procedural_clutter_texture(std::uint64_t seed) {
  SplitMix64 random = seeded_stream(seed, kClutterStream);
  return clutter_texture(random);
}

Mesh tiled_plane(const cv::Mat& texture, double half_extent, double tile, const Eigen::Vector2d& centre, double z) {
  MeshPart part;
  part.material.texture_bgr = texture;
  const int tiles = int(std::ceil(half_extent / tile));
  for (int i = -tiles; i < tiles; ++i) {
    for (int j = -tiles; j < tiles; ++j) {
      const int first = int(part.vertices.size());
      const double x = centre.x() + i * tile, y = centre.y() + j * tile;
      part.vertices.emplace_back(float(x), float(y), float(z));
      part.vertices.emplace_back(float(x + tile), float(y), float(z));
      part.vertices.emplace_back(float(x + tile), float(y + tile), float(z));
      part.vertices.emplace_back(float(x), float(y + tile), float(z));
      part.texcoords.insert(part.texcoords.end(), {{0.f, 0.f}, {1.f, 0.f}, {1.f, 1.f}, {0.f, 1.f}});
      part.triangles.emplace_back(first, first + 1, first + 2);
      part.triangles.emplace_back(first, first + 2, first + 3);
    }
  }
  Mesh mesh;
  mesh.source = "background plane";
  mesh.parts.push_back(std::move(part));
  return mesh;
}

}  // namespace icgp
