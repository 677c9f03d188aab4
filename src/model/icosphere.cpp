// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/model/icosphere.h"

#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace icgp {

std::vector<Eigen::Vector3f> icosphere_directions(int n_divides) {
  if (n_divides < 0)
    throw std::invalid_argument("icosphere subdivisions must be >= 0, got " + std::to_string(n_divides));
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> vertices = {{-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0},
                                           {0, -1, phi}, {0, 1, phi}, {0, -1, -phi}, {0, 1, -phi},
                                           {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}};
  for (auto& v : vertices) v.normalize();
  std::vector<std::array<int, 3>> triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                               {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                               {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                               {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int d = 0; d < n_divides; ++d) {
    std::map<std::pair<int, int>, int> midpoints;  // each shared edge gets one new vertex
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto [it, added] = midpoints.emplace(key, static_cast<int>(vertices.size()));
      if (added) vertices.push_back((vertices[a] + vertices[b]).normalized());
      return it->second;
    };
    std::vector<std::array<int, 3>> finer;
    finer.reserve(4 * triangles.size());
    for (const auto& [a, b, c] : triangles) {
      const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      finer.push_back({a, ab, ca});
      finer.push_back({b, bc, ab});
      finer.push_back({c, ca, bc});
      finer.push_back({ab, bc, ca});
    }
    triangles = std::move(finer);
  }
  std::vector<Eigen::Vector3f> directions;
  directions.reserve(vertices.size());
  for (const auto& v : vertices) directions.push_back(v.cast<float>());
  return directions;
}

}  // namespace icgp
