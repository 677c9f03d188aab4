// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/detection/mesh_symmetries.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <unordered_map>

namespace icgp {

namespace {

constexpr int kSamples = 8000;
constexpr double kMatchingShare = 0.99;
constexpr double kToleranceInSpacings = 2.0;
/// Main face normals tried as axes besides the principal axes (a cube's are degenerate).
constexpr int kNormalAxes = 6;
/// Principal spreads closer than this share are taken as equal.
constexpr double kDistinctSpread = 0.2;
/// Turns this close count as one (the same symmetry found about two nearly equal axes).
constexpr double kSameRotation = deg_to_rad(10.0);

struct SurfaceSample {
  Eigen::Vector3d point;
  int colour;
};

/// A mesh's surface: its centroid and second moment by area, and points drawn uniformly by
/// area (a fixed seed: the same answer every run), each with the index of its part's flat
/// colour among the mesh's distinct colours (all 0 for its shape alone).
class SampledSurface {
 public:
  SampledSurface(const Mesh& mesh, Keeping keeping) {
    struct Triangle {
      Eigen::Vector3d a, b, c;
      int colour;
    };
    std::vector<Triangle> triangles;
    std::vector<double> cumulative_area;
    std::vector<Eigen::Vector3f> colours;
    double area = 0.0;
    for (const MeshPart& part : mesh.parts) {
      const auto same = [&](const Eigen::Vector3f& c) { return (c - part.material.diffuse_rgb).cwiseAbs().maxCoeff() < 1.f / 64; };
      auto found = std::find_if(colours.begin(), colours.end(), same);
      if (found == colours.end()) found = colours.insert(colours.end(), part.material.diffuse_rgb);
      const int colour = keeping == Keeping::kShape ? 0 : static_cast<int>(found - colours.begin());
      for (const Eigen::Vector3i& t : part.triangles) {
        Triangle triangle{part.vertices[t[0]].cast<double>(), part.vertices[t[1]].cast<double>(),
                          part.vertices[t[2]].cast<double>(), colour};
        const Eigen::Vector3d normal = (triangle.b - triangle.a).cross(triangle.c - triangle.a);
        if (normal.norm() == 0.0) continue;
        area += 0.5 * normal.norm();
        const Eigen::Vector3d sum = triangle.a + triangle.b + triangle.c;
        centroid_ += 0.5 * normal.norm() * sum / 3.0;
        // The triangle's exact second moment, ∫ x xᵀ dA = A/12 (Σ vᵢvᵢᵀ + s sᵀ), s = Σ vᵢ.
        second_moment_ += 0.5 * normal.norm() / 12.0 *
                          (triangle.a * triangle.a.transpose() + triangle.b * triangle.b.transpose() +
                           triangle.c * triangle.c.transpose() + sum * sum.transpose());
        face_normals_.push_back(normal);  // length: twice the area, the weight of its direction
        triangles.push_back(triangle);
        cumulative_area.push_back(area);
      }
    }
    if (area > 0.0) centroid_ /= area;
    area_ = area;
    if (!measurable()) return;
    spacing_ = std::sqrt(area / kSamples);
    std::mt19937 random(12345);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (int k = 0; k < kSamples; ++k) {
      const auto it = std::upper_bound(cumulative_area.begin(), cumulative_area.end(), uniform(random) * area);
      const Triangle& t = triangles[std::min<std::size_t>(it - cumulative_area.begin(), triangles.size() - 1)];
      // Uniform on the triangle: the square root keeps the density even towards vertex a.
      const double r1 = std::sqrt(uniform(random)), r2 = uniform(random);
      samples_.push_back({(1 - r1) * t.a + r1 * (1 - r2) * t.b + r1 * r2 * t.c, t.colour});
    }
    for (std::size_t i = 0; i < samples_.size(); ++i) cells_[cell_key(samples_[i].point)].push_back(static_cast<int>(i));
  }

  /// Enough area to sample: MeshLimits bound coordinates to 1e4 m, so with the spacing
  /// this gives, cell indices stay far inside 64 bits.
  bool measurable() const { return area_ > 1e-18; }
  const Eigen::Vector3d& centroid() const { return centroid_; }

  /// The axes worth turning about: the directions of the largest total face area
  /// (opposite normals counted as one; exact for flat faces), then the surface's principal
  /// axes (for curved surfaces).
  std::vector<Eigen::Vector3d> candidate_axes() const {
    std::vector<Eigen::Vector3d> axes;
    std::vector<std::pair<Eigen::Vector3d, double>> directions;  // unit direction, total weight
    for (const Eigen::Vector3d& normal : face_normals_) {
      const Eigen::Vector3d unit = normal.normalized();
      auto same = std::find_if(directions.begin(), directions.end(),
                               [&](const auto& d) { return std::abs(d.first.dot(unit)) > std::cos(deg_to_rad(5.0)); });
      if (same == directions.end())
        directions.emplace_back(unit, normal.norm());
      else
        same->second += normal.norm();
    }
    std::sort(directions.begin(), directions.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
    for (std::size_t k = 0; k < directions.size() && k < static_cast<std::size_t>(kNormalAxes); ++k)
      axes.push_back(directions[k].first);
    // Between the three main ones: a cube's edge and corner axes (its turns of 1/2 and 1/3).
    if (directions.size() >= 3) {
      const Eigen::Vector3d &a = directions[0].first, &b = directions[1].first, &c = directions[2].first;
      const Eigen::Vector3d between[] = {a + b, a - b, b + c, b - c, a + c, a - c, a + b + c, a + b - c, a - b + c, a - b - c};
      for (const Eigen::Vector3d& axis : between) axes.push_back(axis.normalized());
    }

    const Eigen::Matrix3d covariance = second_moment_ - area_ * centroid_ * centroid_.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> principal(covariance);
    const Eigen::Vector3d& spread = principal.eigenvalues();
    for (int k = 0; k < 3; ++k) {
      // An axis whose spread another shares is any direction of their plane (a cube's, a
      // cylinder's across): not one to try.
      const bool distinct = std::abs(spread[k] - spread[(k + 1) % 3]) > kDistinctSpread * spread[k] &&
                            std::abs(spread[k] - spread[(k + 2) % 3]) > kDistinctSpread * spread[k];
      if (distinct) axes.push_back(principal.eigenvectors().col(k));
    }
    return axes;
  }

  /// Whether the turn `rotation` about the centroid takes nearly every sample onto the
  /// surface of its own colour.
  bool maps_onto_itself(const Eigen::Matrix3d& rotation) const {
    const double tolerance = kToleranceInSpacings * spacing_;
    const auto allowed_misses = static_cast<std::size_t>((1.0 - kMatchingShare) * samples_.size());
    std::size_t misses = 0;
    for (const SurfaceSample& s : samples_)
      if (!has_sample_near(centroid_ + rotation * (s.point - centroid_), s.colour, tolerance) && ++misses > allowed_misses)
        return false;
    return true;
  }

 private:
  /// Cells of the tolerance's size: a sample within it lies in one of the 27 around.
  std::int64_t cell_key(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d cell = (p / (kToleranceInSpacings * spacing_)).array().floor();
    return cell_key(static_cast<std::int64_t>(cell.x()), static_cast<std::int64_t>(cell.y()),
                    static_cast<std::int64_t>(cell.z()));
  }
  static std::int64_t cell_key(std::int64_t x, std::int64_t y, std::int64_t z) {
    // 20 bits per axis: cells further apart may share a key, which only adds candidates
    // (has_sample_near measures the distance).
    return ((x & 0xFFFFF) << 40) | ((y & 0xFFFFF) << 20) | (z & 0xFFFFF);
  }

  bool has_sample_near(const Eigen::Vector3d& p, int colour, double tolerance) const {
    const Eigen::Vector3d cell = (p / (kToleranceInSpacings * spacing_)).array().floor();
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(cell_key(static_cast<std::int64_t>(cell.x()) + dx,
                                               static_cast<std::int64_t>(cell.y()) + dy,
                                               static_cast<std::int64_t>(cell.z()) + dz));
          if (it == cells_.end()) continue;
          for (int i : it->second)
            if (samples_[i].colour == colour && (samples_[i].point - p).norm() <= tolerance) return true;
        }
    return false;
  }

  std::vector<SurfaceSample> samples_;
  std::vector<Eigen::Vector3d> face_normals_;
  Eigen::Vector3d centroid_ = Eigen::Vector3d::Zero();  ///< of the surface, by area
  Eigen::Matrix3d second_moment_ = Eigen::Matrix3d::Zero();  ///< ∫ x xᵀ dA over the surface
  double area_ = 0.0;
  double spacing_ = 0.0;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
};

bool contains(const std::vector<Eigen::Matrix3d>& rotations, const Eigen::Matrix3d& r) {
  return std::any_of(rotations.begin(), rotations.end(),
                     [&](const Eigen::Matrix3d& q) { return rotation_angle_between(q, r) < kSameRotation; });
}

}  // namespace

std::vector<Pose> mesh_symmetries(const Mesh& mesh, Keeping keeping) {
  if ((keeping == Keeping::kAppearance && has_texture(mesh)) || mesh.empty()) return {};
  const SampledSurface surface(mesh, keeping);
  if (!surface.measurable()) return {};

  // Every turn is checked on its own: products of nearly symmetric turns (a box whose
  // sides are not quite square to each other) would compound into turns that are not.
  std::vector<Eigen::Matrix3d> group{Eigen::Matrix3d::Identity()};
  for (const Eigen::Vector3d& axis : surface.candidate_axes())
    for (int order : {2, 3, 4, 6})
      for (int k = 1; k < order; ++k) {
        const Eigen::Matrix3d turn = Eigen::AngleAxisd(2.0 * kPi * k / order, axis).toRotationMatrix();
        if (!contains(group, turn) && surface.maps_onto_itself(turn)) group.push_back(turn);
      }

  std::vector<Pose> symmetries;
  const Eigen::Vector3d& c = surface.centroid();
  for (std::size_t k = 1; k < group.size(); ++k) symmetries.emplace_back(group[k], c - group[k] * c);
  return symmetries;
}

std::vector<BodyAxis> round_axes(const Mesh& mesh) {
  if (mesh.empty()) return {};
  const SampledSurface surface(mesh, Keeping::kShape);
  if (!surface.measurable()) return {};
  std::vector<BodyAxis> round;
  for (const Eigen::Vector3d& axis : surface.candidate_axes()) {
    const auto same_axis = [&](const BodyAxis& a) { return std::abs(a.direction.dot(axis)) > std::cos(kSameRotation); };
    if (std::any_of(round.begin(), round.end(), same_axis)) continue;
    if (surface.maps_onto_itself(Eigen::AngleAxisd(kPi / 2.0, axis).toRotationMatrix()) &&
        surface.maps_onto_itself(Eigen::AngleAxisd(kPi / 3.0, axis).toRotationMatrix()))
      round.push_back({surface.centroid(), axis.normalized()});
  }
  return round;
}

std::vector<Pose> turns_about(const std::vector<BodyAxis>& axes, double step) {
  if (!(step > 0.0)) return {};
  const int steps = static_cast<int>(std::ceil(2.0 * kPi / step));
  std::vector<Pose> turns;
  for (const BodyAxis& axis : axes)
    for (int k = 1; k < steps; ++k) {
      const Eigen::Matrix3d turn = Eigen::AngleAxisd(2.0 * kPi * k / steps, axis.direction).toRotationMatrix();
      turns.emplace_back(turn, axis.point - turn * axis.point);
    }
  return turns;
}

Pose turned_towards(const Pose& reference_T_body, const BodyAxis& axis, const Pose& nearest) {
  // The turn Q = Rᵀ·R_nearest split into a twist about the axis and a swing about an axis
  // perpendicular to it: the twist is the turn about the axis nearest to Q.
  const Eigen::Quaterniond q(Eigen::Matrix3d(reference_T_body.rotation().transpose() * nearest.rotation()));
  const double angle = 2.0 * std::atan2(q.vec().dot(axis.direction), q.w());
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(angle, axis.direction).toRotationMatrix();
  return reference_T_body * Pose(turn, axis.point - turn * axis.point);
}

}  // namespace icgp
