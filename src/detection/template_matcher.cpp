// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/detection/template_matcher.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <queue>

namespace icgp {
namespace {

/// A template is matched on the pyramid level where its bounding sphere's radius is at
/// most this many pixels: larger, and the image grid is finer than its contour needs.
constexpr double kMaxTemplateRadius = 36.0;
/// Below this radius at full resolution a contour has too few distinct pixels to match.
constexpr double kMinTemplateRadius = 10.0;
/// With depth, a template position is scored only where the surface just outside its
/// contour (this many full-resolution pixels out) steps back behind the surface at its
/// centre, at this many of its probes: a body stands out of what is behind it, a picture
/// of one (a painted rectangle on a wall) does not.
constexpr double kProbeOffsetPx = 8.0;
constexpr int kProbes = 12;
constexpr double kMinProbesOutside = 0.4;

int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

/// A template's points at one distance and level: grid offsets, bins, and the box they span.
struct PlacedTemplate {
  struct Point {
    int dx, dy, bin;
    bool operator<(const Point& o) const { return std::tie(dx, dy, bin) < std::tie(o.dx, o.dy, o.bin); }
    bool operator==(const Point& o) const { return dx == o.dx && dy == o.dy && bin == o.bin; }
  };
  std::vector<Point> points;
  /// Pixels (of the level) just outside the contour, relative to the centre.
  std::vector<Eigen::Vector2d> probes;
  int min_x = 0, max_x = 0, min_y = 0, max_y = 0;

  void place(const ShapeTemplates::Template& t, const Intrinsics& K, double distance, double probe_offset) {
    points.clear();
    probes.clear();
    const std::size_t probe_step = std::max<std::size_t>(1, t.contour.size() / kProbes);
    for (std::size_t k = 0; k < t.contour.size(); ++k) {
      const ShapeTemplates::ContourPoint& p = t.contour[k];
      const double z = distance + p.position.z();
      const Eigen::Vector2d at(K.fu * p.position.x() / z, K.fv * p.position.y() / z);
      points.push_back({static_cast<int>(std::lround(at.x())), static_cast<int>(std::lround(at.y())), p.bin});
      if (k % probe_step == 0) probes.push_back(at + probe_offset * p.image_normal.cast<double>());
    }
    std::sort(points.begin(), points.end());
    points.erase(std::unique(points.begin(), points.end()), points.end());
    min_x = min_y = 1 << 30;
    max_x = max_y = -(1 << 30);
    for (const Point& p : points) {
      min_x = std::min(min_x, p.dx);
      max_x = std::max(max_x, p.dx);
      min_y = std::min(min_y, p.dy);
      max_y = std::max(max_y, p.dy);
    }
  }
};

/// Whether the measured depth agrees with a template placed at level pixel (x, y) of a
/// level `scale` times smaller, at `distance`: the surface at its centre lies between its
/// centre's distance and one radius nearer (within a distance step), and beyond enough of
/// its contour the surface steps back or vanishes. True where nothing is measured.
bool stands_out(const RayDepth& depth, const PlacedTemplate& placed, int x, int y, int scale, double distance,
                double radius) {
  const auto full = [scale](double level_px) { return (level_px + 0.5) * scale - 0.5; };
  const float z = depth.nearest(full(x), full(y));
  if (!(z > 0.f)) return true;
  const double slack = (TemplateMatcher::kDistanceStep - 1.0) * distance;
  if (z > distance + slack || z < distance - radius - slack) return false;
  const double step_back = std::max(0.02, 0.3 * radius);
  int outside = 0;
  for (const Eigen::Vector2d& probe : placed.probes) {
    const float behind = depth.nearest(full(x + probe.x()), full(y + probe.y()), 0);
    outside += !(behind > 0.f) || behind > z + step_back;
  }
  return outside >= kMinProbesOutside * static_cast<double>(placed.probes.size());
}

struct RawMatch {
  float score;
  int template_index, level, x, y;  ///< x, y: pixels of the level
  double distance;
  bool operator>(const RawMatch& o) const { return score > o.score; }
};

/// The camera ray through pixel (x, y) of a camera.
Eigen::Vector3d ray_through(const Intrinsics& K, double x, double y) {
  return Eigen::Vector3d((x - K.pu) / K.fu, (y - K.pv) / K.fv, 1.0).normalized();
}

/// The rotation a template would have for `camera_T_body` (its rotation with the turn
/// towards the sphere centre's ray taken out).
Eigen::Matrix3d centred_rotation(const Pose& camera_T_body, const Eigen::Vector3d& centre) {
  const Eigen::Vector3d ray = (camera_T_body * centre).normalized();
  const Eigen::Matrix3d turn = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), ray).toRotationMatrix();
  return turn.transpose() * camera_T_body.rotation();
}

}  // namespace

const cv::Mat& OrientationPyramid::image(int L) {
  if (images_[L].empty()) {
    if (L == 0) {
      images_[0] = color_.image;
    } else {
      const cv::Mat& above = image(L - 1);
      cv::resize(above, images_[L], cv::Size(above.cols / 2, above.rows / 2), 0, 0, cv::INTER_AREA);
    }
  }
  return images_[L];
}

const OrientationPyramid::Level& OrientationPyramid::level(int L) {
  if (levels_[L]) return *levels_[L];
  const cv::Mat& level_image = image(L);
  Level& level = levels_[L].emplace();
  level.intrinsics = color_.intrinsics.scaled(level_image.cols, level_image.rows);
  cv::Mat usable;
  if (!color_.mask.all_pixels()) {
    // A pixel of a level is usable when all the image's pixels it averages are (a mask
    // marks them with any non-zero value: ViSP's are 1).
    cv::resize(color_.mask.mask != 0, usable, level_image.size(), 0, 0, cv::INTER_AREA);
    usable = usable == 255;
  }
  level.responses.compute(level_image, usable);
  return level;
}

std::vector<PoseCandidate> TemplateMatcher::match(OrientationPyramid& pyramid, const SearchWindow& window,
                                                  double min_score, int limit, const CandidateCheck& check,
                                                  std::string* why_none) {
  constexpr int kLevels = OrientationPyramid::kLevels;
  const Intrinsics& K = pyramid.color().intrinsics;
  const double radius = templates_.sphere().radius;
  const std::vector<ShapeTemplates::Template>& all = templates_.templates();

  std::optional<Eigen::Matrix3d> near_R;
  Eigen::Vector2d near_px = Eigen::Vector2d::Zero();
  if (window.near) {
    const Eigen::Vector3d centre = *window.near * templates_.sphere().centre;
    near_R = centred_rotation(*window.near, templates_.sphere().centre);
    near_px = K.project(centre);
    templates_.fill_near(*near_R, window.max_rotation);
  } else {
    templates_.fill_all();
  }

  std::priority_queue<RawMatch, std::vector<RawMatch>, std::greater<RawMatch>> best;
  PlacedTemplate placed;
  int searched = 0;
  double smallest = 0.0, largest = 0.0;
  for (double distance = window.min_distance; distance <= window.max_distance * 1.0001; distance *= kDistanceStep) {
    const double radius_px = K.fu * radius / distance;
    smallest = smallest == 0.0 ? radius_px : std::min(smallest, radius_px);
    largest = std::max(largest, radius_px);
    if (radius_px < kMinTemplateRadius || radius_px > 0.75 * std::max(K.width, K.height)) continue;
    int L = 0;
    while (L + 1 < kLevels && radius_px / (1 << L) > kMaxTemplateRadius) ++L;
    ++searched;
    const OrientationPyramid::Level& lv = pyramid.level(L);
    const OrientationResponses& responses = lv.responses;
    constexpr int S = OrientationResponses::kStride;
    const int cols = responses.grid_cols(), rows = responses.grid_rows(), size = responses.grid_size();
    if (size == 0) continue;
    // The grid positions to report: all, or those near the pose.
    int i0 = 0, i1 = cols - 1, j0 = 0, j1 = rows - 1;
    if (window.near) {
      const double scale = 1 << L;
      const double x = (near_px.x() + 0.5) / scale - 0.5, y = (near_px.y() + 0.5) / scale - 0.5;
      const double r = window.radius_px / scale;
      i0 = std::max(0, static_cast<int>(std::floor((x - r) / S)));
      i1 = std::min(cols - 1, static_cast<int>(std::ceil((x + r) / S)));
      j0 = std::max(0, static_cast<int>(std::floor((y - r) / S)));
      j1 = std::min(rows - 1, static_cast<int>(std::ceil((y + r) / S)));
      if (i0 > i1 || j0 > j1) continue;
    }
    scores_.resize(size);
    for (std::size_t index = 0; index < all.size(); ++index) {
      const ShapeTemplates::Template& t = all[index];
      if (t.contour.empty()) continue;  // a view not filled (out of the window's turn) or showing too little
      if (near_R && rotation_angle_between(*near_R, t.camera_R_body) > window.max_rotation) continue;
      placed.place(t, lv.intrinsics, distance, kProbeOffsetPx / (1 << L));
      // Positions where the whole template lies in the image.
      const int ci0 = std::max(i0, floor_div(-placed.min_x + S - 1, S));
      const int ci1 = std::min(i1, floor_div(responses.width() - 1 - placed.max_x, S));
      const int cj0 = std::max(j0, floor_div(-placed.min_y + S - 1, S));
      const int cj1 = std::min(j1, floor_div(responses.height() - 1 - placed.max_y, S));
      if (ci0 > ci1 || cj0 > cj1) continue;
      // Scores are summed over the grid rows of those positions and their neighbours (the
      // local-maximum test reads them): a window near a pose costs its own rows only.
      const int run0 = std::max(0, cj0 - 1) * cols, run1 = std::min(rows, cj1 + 2) * cols;
      std::fill(scores_.begin() + run0, scores_.begin() + run1, 0);
      for (const PlacedTemplate::Point& p : placed.points) {
        const int qx = floor_div(p.dx, S), qy = floor_div(p.dy, S);
        const std::uint8_t* source = responses.linear(p.bin, p.dx - qx * S, p.dy - qy * S);
        const int shift = qy * cols + qx;
        const int k0 = std::max(run0, -shift), k1 = std::min(run1, size - shift);
        std::uint16_t* out = scores_.data();
        // Indexing from the run's start, so that no pointer is formed outside the array.
        for (int k = k0; k < k1; ++k) out[k] = static_cast<std::uint16_t>(out[k] + source[k + shift]);
      }
      const float normaliser = 1.f / (OrientationResponses::kMaxResponse * static_cast<float>(placed.points.size()));
      const std::uint16_t threshold = static_cast<std::uint16_t>(std::ceil(min_score / normaliser));
      for (int j = cj0; j <= cj1; ++j)
        for (int i = ci0; i <= ci1; ++i) {
          const int k = j * cols + i;
          const std::uint16_t s = scores_[k];
          if (s < threshold) continue;
          // Local maxima only: the neighbours of a peak say the same thing.
          if ((i > 0 && scores_[k - 1] > s) || (i + 1 < cols && scores_[k + 1] > s) ||
              (j > 0 && scores_[k - cols] > s) || (j + 1 < rows && scores_[k + cols] > s))
            continue;
          if (window.depth && !stands_out(*window.depth, placed, i * S, j * S, 1 << L, distance, radius)) continue;
          const float score = s * normaliser;
          if (static_cast<int>(best.size()) == kMaxMatches && score <= best.top().score) continue;
          best.push({score, static_cast<int>(index), L, i * S, j * S, distance});
          if (static_cast<int>(best.size()) > kMaxMatches) best.pop();
        }
    }
  }
  if (searched == 0 && why_none) {
    if (largest < kMinTemplateRadius)
      *why_none = "the object would be at most " + std::to_string(static_cast<int>(2 * largest)) +
                  " pixels wide at the distances searched (" + std::to_string(window.min_distance) + " to " +
                  std::to_string(window.max_distance) + " m): too small to detect";
    else
      *why_none = "the object would be at least " + std::to_string(static_cast<int>(2 * smallest)) +
                  " pixels wide at the distances searched: larger than the image";
  }

  std::vector<RawMatch> raw;
  while (!best.empty()) {
    raw.push_back(best.top());
    best.pop();
  }
  std::reverse(raw.begin(), raw.end());  // best first
  std::vector<PoseCandidate> candidates;
  std::vector<Eigen::Vector2d> centres_px;
  for (const RawMatch& m : raw) {
    if (static_cast<int>(candidates.size()) >= limit) break;
    const Intrinsics& KL = pyramid.level(m.level).intrinsics;
    const ShapeTemplates::Template& t = all[m.template_index];
    PoseCandidate c{templates_.pose(t, ray_through(KL, m.x, m.y), m.distance), m.score, m.template_index, m.distance};
    if (check && !check(c)) continue;
    const Eigen::Vector2d centre_px = K.project(Eigen::Vector3d(c.camera_T_body * templates_.sphere().centre));
    // Non-maximum suppression: the same place, distance and rotation is one candidate.
    bool distinct = true;
    for (std::size_t k = 0; k < candidates.size() && distinct; ++k) {
      const PoseCandidate& o = candidates[k];
      const double r_px = K.fu * radius / o.distance;
      distinct = (centres_px[k] - centre_px).norm() > 0.3 * r_px ||
                 std::max(o.distance, c.distance) / std::min(o.distance, c.distance) > kDistanceStep * 1.01 ||
                 rotation_angle_between(all[o.template_index].camera_R_body, t.camera_R_body) >
                     1.5 * templates_.roll_step();
    }
    if (!distinct) continue;
    candidates.push_back(c);
    centres_px.push_back(centre_px);
  }
  return candidates;
}

}  // namespace icgp
