// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/eval/metrics.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <stdexcept>

namespace icgp {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double fraction(double x) { return x - std::floor(x); }

/// `n` points spread over the mesh surface in proportion to area. Sample k falls in the
/// triangle whose cumulative-area interval holds (k + 0.5) / n of the total (so each
/// triangle gets its share to within one point), and the j-th point of a triangle sits at
/// the j-th term of the R2 low-discrepancy sequence, folded into the triangle. Triangles
/// are visited in order, so each one's points are consecutive k.
std::vector<Eigen::Vector3d> sample_surface(const Mesh& mesh, int n) {
  struct Triangle {
    Eigen::Vector3d a, ab, ac;
  };
  std::vector<Triangle> triangles;
  std::vector<double> cumulative_area;
  double total = 0.0;
  for (const MeshPart& part : mesh.parts)
    for (const Eigen::Vector3i& t : part.triangles) {
      const Eigen::Vector3d a = part.vertices[t[0]].cast<double>();
      const Eigen::Vector3d ab = part.vertices[t[1]].cast<double>() - a;
      const Eigen::Vector3d ac = part.vertices[t[2]].cast<double>() - a;
      const double area = 0.5 * ab.cross(ac).norm();
      if (!(area > 0.0)) continue;
      total += area;
      triangles.push_back({a, ab, ac});
      cumulative_area.push_back(total);
    }
  std::vector<Eigen::Vector3d> samples;
  if (triangles.empty()) return samples;

  // R2 sequence steps: the inverse powers of the plastic number.
  constexpr double kPlastic = 1.32471795724474602596;
  constexpr double kStepU = 1.0 / kPlastic, kStepV = 1.0 / (kPlastic * kPlastic);
  samples.reserve(n);
  std::size_t triangle = triangles.size();  // none yet
  int in_triangle = 0;
  for (int k = 0; k < n; ++k) {
    const double target = (k + 0.5) / n * total;
    const std::size_t t = std::min<std::size_t>(
        std::upper_bound(cumulative_area.begin(), cumulative_area.end(), target) - cumulative_area.begin(),
        triangles.size() - 1);
    in_triangle = t == triangle ? in_triangle + 1 : 0;
    triangle = t;
    // Starting at (1/3, 1/3) puts a triangle's first point on its centroid.
    double u = fraction(1.0 / 3.0 + in_triangle * kStepU), v = fraction(1.0 / 3.0 + in_triangle * kStepV);
    if (u + v > 1.0) {  // fold the unit square's far half onto the triangle: keeps uniformity
      u = 1.0 - u;
      v = 1.0 - v;
    }
    const Triangle& tri = triangles[t];
    samples.push_back(tri.a + u * tri.ab + v * tri.ac);
  }
  return samples;
}

std::vector<Eigen::Vector3d> distinct_vertices(const Mesh& mesh) {
  std::vector<Eigen::Vector3d> vertices;
  for (const Eigen::Vector3f& v : mesh.all_vertices()) vertices.push_back(v.cast<double>());
  const auto lexicographic = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  std::sort(vertices.begin(), vertices.end(), lexicographic);
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  return vertices;
}

/// Exact largest distance between two points. All pairs, but visited from the points
/// farthest from the centroid inwards: |a - b| <= r_a + r_b, so once the two radii
/// cannot beat the best distance found, no remaining pair can. Usually a few hundred
/// pairs, even for meshes with many vertices.
double diameter_of(std::vector<Eigen::Vector3d> points) {
  if (points.size() < 2) return 0.0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  std::vector<std::pair<double, Eigen::Vector3d>> by_radius;
  for (const auto& p : points) by_radius.emplace_back((p - centroid).norm(), p);
  std::sort(by_radius.begin(), by_radius.end(), [](const auto& a, const auto& b) { return a.first > b.first; });

  double best = 0.0;
  for (std::size_t i = 0; i + 1 < by_radius.size(); ++i) {
    if (by_radius[i].first + by_radius[i + 1].first <= best) break;
    for (std::size_t j = i + 1; j < by_radius.size(); ++j) {
      if (by_radius[i].first + by_radius[j].first <= best) break;
      best = std::max(best, (by_radius[i].second - by_radius[j].second).norm());
    }
  }
  return best;
}

double mean(const std::vector<double>& values) {
  return values.empty() ? kNaN : std::accumulate(values.begin(), values.end(), 0.0) / values.size();
}

double max_of(const std::vector<double>& values) {
  return values.empty() ? kNaN : *std::max_element(values.begin(), values.end());
}

}  // namespace

double translation_error_mm(const Pose& estimate, const Pose& truth) {
  return 1000.0 * (estimate.translation() - truth.translation()).norm();
}

double rotation_error_deg(const Pose& estimate, const Pose& truth) {
  return rotation_angle_between(truth.rotation(), estimate.rotation()) * 180.0 / M_PI;
}

double auc_score(const std::vector<double>& errors, double threshold) {
  if (errors.empty()) return kNaN;
  double sum = 0.0;
  for (const double e : errors) sum += std::max(1.0 - e / threshold, 0.0);
  return 100.0 * sum / errors.size();
}

double opt_auc_score(const std::vector<double>& errors, double diameter) {
  return auc_score(errors, 0.2 * diameter) * 20.0 / 100.0;
}

double median(std::vector<double> values) {
  if (values.empty()) return kNaN;
  const std::size_t half = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + half, values.end());
  const double upper = values[half];
  if (values.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + half));
}

double percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return kNaN;
  std::sort(values.begin(), values.end());
  const double rank = std::clamp(fraction, 0.0, 1.0) * static_cast<double>(values.size() - 1);
  return values[static_cast<std::size_t>(std::lround(rank))];
}

/// Exact nearest-neighbour distances in a fixed 3D point set: an implicit k-d tree, the
/// median of each index range at its middle, split along the range's widest axis.
class ModelPointErrors::KdTree {
 public:
  explicit KdTree(std::vector<Eigen::Vector3d> points) : points_(std::move(points)), axis_(points_.size(), 0) {
    build(0, points_.size());
  }

  double nearest_distance(const Eigen::Vector3d& query) const {
    double best2 = std::numeric_limits<double>::infinity();
    search(0, points_.size(), query, best2);
    return std::sqrt(best2);
  }

 private:
  static constexpr std::size_t kLeafSize = 8;  // below this a linear scan beats descending

  void build(std::size_t begin, std::size_t end) {
    if (end - begin <= kLeafSize) return;
    Eigen::Vector3d lo = points_[begin], hi = points_[begin];
    for (std::size_t i = begin; i < end; ++i) {
      lo = lo.cwiseMin(points_[i]);
      hi = hi.cwiseMax(points_[i]);
    }
    int axis;
    (hi - lo).maxCoeff(&axis);
    const std::size_t mid = begin + (end - begin) / 2;
    std::nth_element(points_.begin() + begin, points_.begin() + mid, points_.begin() + end,
                     [axis](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a[axis] < b[axis]; });
    axis_[mid] = static_cast<unsigned char>(axis);
    build(begin, mid);
    build(mid + 1, end);
  }

  void search(std::size_t begin, std::size_t end, const Eigen::Vector3d& q, double& best2) const {
    if (end - begin <= kLeafSize) {
      for (std::size_t i = begin; i < end; ++i) best2 = std::min(best2, (points_[i] - q).squaredNorm());
      return;
    }
    const std::size_t mid = begin + (end - begin) / 2;
    best2 = std::min(best2, (points_[mid] - q).squaredNorm());
    const double offset = q[axis_[mid]] - points_[mid][axis_[mid]];
    const bool below = offset < 0.0;
    search(below ? begin : mid + 1, below ? mid : end, q, best2);
    if (offset * offset < best2) search(below ? mid + 1 : begin, below ? end : mid, q, best2);
  }

  std::vector<Eigen::Vector3d> points_;
  std::vector<unsigned char> axis_;  ///< split axis of the range whose middle is this index
};

ModelPointErrors::ModelPointErrors(const Mesh& mesh, int n_surface_samples) {
  if (n_surface_samples < 0) throw std::invalid_argument("negative number of surface samples");
  const std::vector<Eigen::Vector3d> vertices = distinct_vertices(mesh);
  if (vertices.empty()) throw std::runtime_error("mesh '" + mesh.source + "' has no vertices to score poses with");
  points_ = sample_surface(mesh, n_surface_samples);
  points_.insert(points_.end(), vertices.begin(), vertices.end());
  diameter_ = diameter_of(vertices);
  tree_ = std::make_unique<KdTree>(points_);
}

ModelPointErrors::~ModelPointErrors() = default;
ModelPointErrors::ModelPointErrors(ModelPointErrors&&) noexcept = default;
ModelPointErrors& ModelPointErrors::operator=(ModelPointErrors&&) noexcept = default;

double ModelPointErrors::add(const Pose& estimate, const Pose& truth) const {
  double sum = 0.0;
  for (const Eigen::Vector3d& X : points_) sum += (truth * X - estimate * X).norm();
  return sum / points_.size();
}

double ModelPointErrors::adds(const Pose& estimate, const Pose& truth) const {
  // |truth X - estimate Y| = |estimate^-1 truth X - Y|: one tree in the body frame serves
  // every pose.
  const Pose body_T_truth = estimate.inverse() * truth;
  double sum = 0.0;
  for (const Eigen::Vector3d& X : points_) sum += tree_->nearest_distance(body_T_truth * X);
  return sum / points_.size();
}

JsonObject TrackingSummary::to_json() const {
  JsonObject json;
  json.add("frames", frames)
      .add("tracked", tracked)
      .add("mean_t_mm", mean_t_mm)
      .add("max_t_mm", max_t_mm)
      .add("mean_r_deg", mean_r_deg)
      .add("max_r_deg", max_r_deg)
      .add("add_auc", add_auc)
      .add("adds_auc", adds_auc)
      .add("median_ms", median_ms)
      .add("hz", hz)
      .add("frames_with_truth", frames_with_truth)
      .add("mean_add_mm", mean_add_mm)
      .add("mean_adds_mm", mean_adds_mm)
      .add("add_auc_opt", add_auc_opt)
      .add("diameter_mm", diameter_mm)
      .add("mean_ms", mean_ms);
  return json;
}

TrackingEvaluation::TrackingEvaluation(const Mesh& mesh, int n_surface_samples) : points_(mesh, n_surface_samples) {}

const FrameEvaluation& TrackingEvaluation::add(int frame, const Pose& estimate, const std::optional<Pose>& truth,
                                               bool tracked, double ms, double quality) {
  FrameEvaluation e;
  e.frame = frame;
  e.tracked = tracked;
  e.quality = quality;
  e.ms = ms;
  e.estimate = estimate;
  e.has_truth = truth.has_value();
  if (truth) {
    e.t_mm = translation_error_mm(estimate, *truth);
    e.r_deg = rotation_error_deg(estimate, *truth);
    e.add_m = points_.add(estimate, *truth);
    e.adds_m = points_.adds(estimate, *truth);
  } else {
    e.t_mm = e.r_deg = e.add_m = e.adds_m = kNaN;
  }
  frames_.push_back(e);
  return frames_.back();
}

TrackingSummary TrackingEvaluation::summary() const {
  std::vector<double> t_mm, r_deg, add_m, adds_m, ms;
  TrackingSummary s;
  for (const FrameEvaluation& f : frames_) {
    ++s.frames;
    s.tracked += f.tracked ? 1 : 0;
    ms.push_back(f.ms);
    if (!f.has_truth) continue;
    t_mm.push_back(f.t_mm);
    r_deg.push_back(f.r_deg);
    add_m.push_back(f.add_m);
    adds_m.push_back(f.adds_m);
  }
  s.frames_with_truth = static_cast<int>(t_mm.size());
  s.mean_t_mm = mean(t_mm);
  s.max_t_mm = max_of(t_mm);
  s.mean_r_deg = mean(r_deg);
  s.max_r_deg = max_of(r_deg);
  s.mean_add_mm = 1000.0 * mean(add_m);
  s.mean_adds_mm = 1000.0 * mean(adds_m);
  s.add_auc = auc_score(add_m, kYcbAucThreshold);
  s.adds_auc = auc_score(adds_m, kYcbAucThreshold);
  s.add_auc_opt = opt_auc_score(add_m, points_.diameter());
  s.diameter_mm = 1000.0 * points_.diameter();
  s.median_ms = median(ms);
  s.mean_ms = mean(ms);
  s.hz = 1000.0 / s.median_ms;
  return s;
}

void TrackingEvaluation::write_csv(const std::string& path) const {
  const std::filesystem::path file(path);
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file);
  out.precision(10);
  const auto field = [&out](double value) {
    out << ',';
    if (std::isfinite(value)) out << value;
  };
  out << "frame,tracked,quality,ms,t_mm,r_deg,add_mm,adds_mm,tx,ty,tz,rx,ry,rz\n";
  for (const FrameEvaluation& f : frames_) {
    out << f.frame << ',' << (f.tracked ? 1 : 0);
    field(f.quality);
    field(f.ms);
    field(f.t_mm);
    field(f.r_deg);
    field(1000.0 * f.add_m);
    field(1000.0 * f.adds_m);
    const Eigen::AngleAxisd rotation(f.estimate.rotation());
    const Eigen::Vector3d theta_u = rotation.angle() * rotation.axis();
    for (int i = 0; i < 3; ++i) field(f.estimate.translation()[i]);
    for (int i = 0; i < 3; ++i) field(theta_u[i]);
    out << '\n';
  }
  if (!out) throw std::runtime_error("cannot write CSV file '" + path + "'");
}

}  // namespace icgp
