// SPDX-License-Identifier: GPL-2.0-or-later
#include "view_samplers.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "icgp/base/splitmix64.h"

namespace icgp {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
constexpr int kAreaSamplesAcross = 500;  ///< visible surface area: samples per image row and column

/// SplitMix64 seeded from (seed, view): each view draws its own stream, so the points of a
/// view do not depend on which thread renders it or in which order.
class ViewRandom : public SplitMix64 {
 public:
  ViewRandom(std::uint64_t seed, int view)
      : SplitMix64(seed ^ (0x9e3779b97f4a7c15ull * (static_cast<std::uint64_t>(view) + 1))) {}
};

/// n distinct indices of [0, population) drawn uniformly, in random order: Floyd's algorithm,
/// whose cost depends on n only (the population can be a million silhouette pixels), then a
/// shuffle, so that any prefix of the result is a uniform sample as well.
class UniformSubset {
 public:
  const std::vector<int>& draw(int n, int population, ViewRandom& random) {
    sorted_.clear();
    chosen_.clear();
    for (int j = population - n; j < population; ++j) {
      const int t = random.below(j + 1);
      const auto at = std::lower_bound(sorted_.begin(), sorted_.end(), t);
      const int pick = (at != sorted_.end() && *at == t) ? j : t;  // j is new: it exceeds all picks so far
      sorted_.insert(pick == t ? at : sorted_.end(), pick);
      chosen_.push_back(pick);
    }
    for (int i = static_cast<int>(chosen_.size()) - 1; i > 0; --i) std::swap(chosen_[i], chosen_[random.below(i + 1)]);
    return chosen_;
  }

 private:
  std::vector<int> sorted_, chosen_;
};

/// Depth offsets of a point seen at `pixel` with depth Z (ALGORITHMS.md §3.6): for radius
/// r_k = (k+1)·stride, how much nearer than Z the rendered surface comes within r_k·f/Z pixels.
/// Non-decreasing in k by construction, as the exact values are.
void write_depth_offsets(const RenderedView& view, const ViewpointModelParams& params, cv::Point pixel, float depth,
                         float* offsets) {
  const int n = params.n_depth_offsets();
  const float radius_step = static_cast<float>(params.stride_depth_offset * view.camera.intrinsics.fu) / depth;
  view.pyramid->max_in_discs(static_cast<float>(pixel.x), static_cast<float>(pixel.y), radius_step, n, offsets);
  const float depth_scale = static_cast<float>(view.images->depth_scale);
  float offset = 0.f;
  for (int k = 0; k < n; ++k) {
    // The disc contains the point's own pixel, so its maximum inverse depth is positive.
    offset = std::max(offset, depth - depth_scale / offsets[k]);
    offsets[k] = offset;
  }
}

int count_equal(const std::uint8_t* values, int n, std::uint8_t value) {
  int count = 0;
  for (int i = 0; i < n; ++i) count += values[i] == value;
  return count;
}

/// Body-frame point seen at a pixel centre with depth Z.
Eigen::Vector3f body_point(const RenderedView& view, cv::Point pixel, float depth) {
  const Eigen::Vector3d camera_point = view.camera.intrinsics.back_project<double>(pixel.x, pixel.y, depth);
  return (view.body_T_camera * camera_point).cast<float>();
}

/// The 3D contour point of a boundary pixel. The silhouette's edge does not pass through
/// the centre of the last pixel inside it but between it and the first pixel outside: for
/// a straight edge with unit normal n, stepping one pixel along the dominant axis moves
/// max(|n_x|, |n_y|) along n, so the edge lies on average half of that beyond the centre.
/// Without this shift every contour point sits inside the true silhouette and the region
/// modality pulls the object towards the camera to make it look larger.
Eigen::Vector3f contour_body_point(const RenderedView& view, cv::Point pixel, const Eigen::Vector2f& normal,
                                   float depth) {
  const double shift = 0.5 * std::max(std::abs(normal.x()), std::abs(normal.y()));
  const Eigen::Vector3d camera_point =
      view.camera.intrinsics.back_project<double>(pixel.x + shift * normal.x(), pixel.y + shift * normal.y(), depth);
  return (view.body_T_camera * camera_point).cast<float>();
}

float* view_offsets(ViewpointModel& model, int view, int point) {
  const std::size_t n = static_cast<std::size_t>(model.n_points());
  return model.mutable_depth_offsets() + (static_cast<std::size_t>(view) * n + point) * model.n_depth_offsets();
}

ModelPoint* view_points(ViewpointModel& model, int view) {
  return model.mutable_points() + static_cast<std::size_t>(view) * model.n_points();
}

/// Walks from a pixel centre along a unit image direction, one pixel per step along the
/// dominant axis (so no pixel on the way is skipped), and returns the distance in pixels to
/// the first pixel for which `arrived(id)` holds, `id` being that pixel's id; +infinity when
/// the walk reaches the image border first.
template <typename Arrived>
float walk(const cv::Mat& ids, cv::Point start, const Eigen::Vector2f& direction, Arrived arrived) {
  const bool along_u = std::abs(direction.x()) >= std::abs(direction.y());
  const float major = along_u ? direction.x() : direction.y();
  const float minor_step = (along_u ? direction.y() : direction.x()) / std::abs(major);
  const int major_step = major > 0.f ? 1 : -1;
  const float step_length = std::sqrt(1.f + minor_step * minor_step);
  const int major_size = along_u ? ids.cols : ids.rows, minor_size = along_u ? ids.rows : ids.cols;
  const std::size_t major_stride = along_u ? 1 : ids.step, minor_stride = along_u ? ids.step : 1;
  const int major_start = along_u ? start.x : start.y;
  // +0.5 so that truncation rounds to the nearest pixel (the minor coordinate stays >= -0.5).
  const float minor_start = static_cast<float>(along_u ? start.y : start.x) + 0.5f;
  for (int k = 1;; ++k) {
    const int a = major_start + k * major_step;
    const float b = minor_start + static_cast<float>(k) * minor_step;
    if (a < 0 || a >= major_size || b < 0.f || b >= static_cast<float>(minor_size)) return kInfinity;
    const std::uint8_t id = ids.data[a * major_stride + static_cast<std::size_t>(b) * minor_stride];
    if (arrived(id)) return static_cast<float>(k) * step_length;
  }
}

/// Region model of one view (ALGORITHMS.md §3, region steps 1 to 6).
class RegionViewSampler : public ViewSampler {
 public:
  explicit RegionViewSampler(const ViewpointModelParams& params) : params_(params) {}

  void sample(const RenderedView& view, ViewpointModel& model) override {
    // A render of the main body alone has ids that are its silhouette mask as they are; with
    // associated bodies the mask is where the main body shows.
    const cv::Rect& footprint = view.images->footprint;
    contours_.clear();
    hierarchy_.clear();
    if (!footprint.empty()) {
      if (view.with_associated_bodies) cv::compare(view.images->ids(footprint), view.body_id, mask_, cv::CMP_EQ);
      cv::findContours(view.with_associated_bodies ? mask_ : view.images->ids(footprint), contours_, hierarchy_,
                       cv::RETR_CCOMP, cv::CHAIN_APPROX_NONE, footprint.tl());
    }
    const float contour_length = collect_valid_pixels(view);

    ViewRandom random(params_.seed, view.index);
    const int n = std::min(params_.n_points, static_cast<int>(candidates_.size()));
    const std::vector<int>& chosen = subset_.draw(n, static_cast<int>(candidates_.size()), random);
    ModelPoint* points = view_points(model, view.index);
    const Eigen::Matrix3f body_R_camera = view.body_T_camera.rotation().cast<float>();
    const float metres_per_px_at_unit_depth = 1.f / static_cast<float>(view.camera.intrinsics.fu);
    for (int p = 0; p < n; ++p) {
      const Candidate& c = candidates_[chosen[p]];
      const cv::Point pixel = contours_[c.contour][c.index];
      const float depth = view.images->depth(pixel.y, pixel.x);
      const Eigen::Vector2f normal = outward_normal(c);
      const float metres_per_px = depth * metres_per_px_at_unit_depth;
      const cv::Mat& ids = view.images->ids;
      ModelPoint& point = points[p];
      point.position = contour_body_point(view, pixel, normal, depth);
      // In the image plane, so perpendicular to the view direction.
      point.normal = body_R_camera * Eigen::Vector3f(normal.x(), normal.y(), 0.f);
      if (!view.with_associated_bodies) {
        const std::uint8_t body = view.body_id;
        point.foreground_distance =
            metres_per_px * walk(ids, pixel, -normal, [body](std::uint8_t id) { return id != body; });
        bool left = false;  // the background walk first leaves the silhouette, then looks for it
        point.background_distance = metres_per_px * walk(ids, pixel, normal, [&left, body](std::uint8_t id) {
                                      left = left || id != body;
                                      return left && id == body;
                                    });
      } else {
        // Foreground: across the main body and fixed same-region bodies. Background: once off
        // every surface of the main body's region, up to the first one of them.
        point.foreground_distance = metres_per_px * walk(ids, pixel, -normal, [](std::uint8_t id) {
                                      return id != kMainRegionId && id != kFixedSameRegionBodyId;
                                    });
        auto same_region = [](std::uint8_t id) {
          return id == kMainRegionId || id == kFixedSameRegionBodyId || id == kMovableSameRegionBodyId;
        };
        bool left = false;
        point.background_distance = metres_per_px * walk(ids, pixel, normal, [&left, &same_region](std::uint8_t id) {
                                      left = left || !same_region(id);
                                      return left && same_region(id);
                                    });
      }
      write_depth_offsets(view, params_, pixel, depth, view_offsets(model, view.index, p));
    }
    model.mutable_counts()[view.index] = n;
    model.mutable_views()[view.index].measure = contour_length;
  }

 private:
  struct Candidate {
    int contour, index;
  };

  /// Gathers the valid pixels of the contours that are long enough and returns their
  /// length in metres (each step to the next contour pixel at the depth of the valid pixel).
  float collect_valid_pixels(const RenderedView& view) {
    candidates_.clear();
    outward_sign_.assign(contours_.size(), 0.f);
    const int k = params_.normal_chord_offset;
    const int last_col = view.images->ids.cols - 1, last_row = view.images->ids.rows - 1;
    const double metres_per_px_at_unit_depth = 1.0 / view.camera.intrinsics.fu;
    double length = 0.0;
    for (int c = 0; c < static_cast<int>(contours_.size()); ++c) {
      const std::vector<cv::Point>& contour = contours_[c];
      const int size = static_cast<int>(contour.size());
      if (size < std::max(1, params_.min_contour_length)) continue;
      outward_sign_[c] = outward_sign(contour, hierarchy_[c][3] >= 0);
      for (int i = 0; i < size; ++i) {
        const cv::Point& p = contour[i];
        const bool on_border = p.x == 0 || p.y == 0 || p.x == last_col || p.y == last_row;
        if (on_border || chord(contour, i, k) == cv::Point(0, 0)) continue;
        if (view.with_associated_bodies && !valid_next_to_associated_bodies(view, p)) continue;
        candidates_.push_back({c, i});
        length += cv::norm(contour[(i + 1) % size] - p) * view.images->depth(p.y, p.x) * metres_per_px_at_unit_depth;
      }
    }
    return static_cast<float>(length);
  }

  /// The multi-region rules (ALGORITHMS.md §6) for a contour pixel p of the main body's mask
  /// that is not on the image border. Its neighbours are its 4-neighbours that do not show
  /// the main body; when there are none (the contour touches the outside only diagonally),
  /// its diagonal neighbours that do not show the main body. With Z the point's depth and
  /// tolerance = 10 px · pixel_to_metre = 10 · Z / f:
  ///   * a neighbour showing a same-region body (fixed or movable) rejects p ("next to");
  ///   * a neighbour showing a movable body at a depth < Z + tolerance rejects p: the body
  ///     covers the main body there (or touches it and may move over it); only where the
  ///     main body's own edge is clearly in front of the movable body is p kept;
  ///   * neighbours showing fixed bodies keep p only if their mean depth is >= Z − tolerance:
  ///     a nearer fixed neighbour means p is the shadow of its elevated edge;
  ///   * background neighbours impose nothing.
  static bool valid_next_to_associated_bodies(const RenderedView& view, cv::Point p) {
    static constexpr std::array<std::array<int, 2>, 8> kNeighbours = {
        {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {1, -1}, {-1, 1}, {-1, -1}}};
    const SilhouetteImages& images = *view.images;
    const float depth = images.depth(p.y, p.x);
    const float tolerance = 10.f * depth / static_cast<float>(view.camera.intrinsics.fu);
    int outside = 0, n_fixed = 0;
    float fixed_depth_sum = 0.f;
    for (int n = 0; n < 8 && !(n == 4 && outside > 0); ++n) {  // diagonals only if no 4-neighbour is outside
      const int row = p.y + kNeighbours[n][1], col = p.x + kNeighbours[n][0];
      const std::uint8_t id = images.ids.at<std::uint8_t>(row, col);
      if (id == view.body_id) continue;
      ++outside;
      switch (id) {
        case kFixedSameRegionBodyId:
        case kMovableSameRegionBodyId:
          return false;
        case kMovableBodyId:
          if (images.depth(row, col) < depth + tolerance) return false;
          break;
        case kFixedBodyId:
          fixed_depth_sum += images.depth(row, col);
          ++n_fixed;
          break;
        default:  // background
          break;
      }
    }
    return n_fixed == 0 || fixed_depth_sum / static_cast<float>(n_fixed) >= depth - tolerance;
  }

  static cv::Point chord(const std::vector<cv::Point>& contour, int i, int k) {
    const int size = static_cast<int>(contour.size());
    return contour[(i + k) % size] - contour[((i - k) % size + size) % size];
  }

  /// +1 when the right-hand normal (t.y, -t.x) of the tracing direction t points away from
  /// the silhouette, else -1. A positive shoelace area means the polygon's inside is on the
  /// left of t; the silhouette is that inside for an outer contour and outside it for a hole.
  static float outward_sign(const std::vector<cv::Point>& contour, bool hole) {
    double twice_area = 0.0;
    for (std::size_t i = 0, size = contour.size(); i < size; ++i) {
      const cv::Point& a = contour[i];
      const cv::Point& b = contour[(i + 1) % size];
      twice_area += static_cast<double>(a.x) * b.y - static_cast<double>(b.x) * a.y;
    }
    return (twice_area > 0.0) != hole ? 1.f : -1.f;
  }

  Eigen::Vector2f outward_normal(const Candidate& c) const {
    const cv::Point t = chord(contours_[c.contour], c.index, params_.normal_chord_offset);
    return outward_sign_[c.contour] * Eigen::Vector2f(static_cast<float>(t.y), static_cast<float>(-t.x)).normalized();
  }

  ViewpointModelParams params_;
  std::vector<std::vector<cv::Point>> contours_;
  std::vector<cv::Vec4i> hierarchy_;
  cv::Mat mask_;  ///< the main body's mask in the footprint, with associated bodies
  std::vector<float> outward_sign_;
  std::vector<Candidate> candidates_;
  UniformSubset subset_;
};

/// Depth model of one view (ALGORITHMS.md §3, depth model).
class DepthViewSampler : public ViewSampler {
 public:
  explicit DepthViewSampler(const ViewpointModelParams& params) : params_(params) {}

  void sample(const RenderedView& view, ViewpointModel& model) override {
    const cv::Mat& ids = view.images->ids;
    const cv::Rect& footprint = view.images->footprint;
    count_silhouette_rows(ids, footprint, view.body_id);
    const int population = rows_before_.back();

    ViewRandom random(params_.seed, view.index);
    const int n = std::min(params_.n_points, population);
    const std::vector<int>& chosen = subset_.draw(n, population, random);
    ModelPoint* points = view_points(model, view.index);
    const Intrinsics& k = view.camera.intrinsics;
    const Eigen::Vector3d camera_centre = view.body_T_camera.translation();
    int count = 0;
    for (int p = 0; p < n; ++p) {
      const cv::Point pixel = silhouette_pixel(ids, footprint, view.body_id, chosen[p]);
      const float depth = view.images->depth(pixel.y, pixel.x);
      // The pixel's ray (x, y, 1) reaches the rendered surface at ray parameter Z.
      const Eigen::Vector3d ray = view.body_T_camera.rotation() * k.back_project<double>(pixel.x, pixel.y, 1.0);
      Eigen::Vector3d normal;
      if (!view.faces->normal_at(camera_centre, ray, depth, normal)) continue;  // only if rounding lost it
      ModelPoint& point = points[count];
      point.position = body_point(view, pixel, depth);
      point.normal = normal.cast<float>();
      point.foreground_distance = point.background_distance = 0.f;
      write_depth_offsets(view, params_, pixel, depth, view_offsets(model, view.index, count));
      ++count;
    }
    model.mutable_counts()[view.index] = count;
    model.mutable_views()[view.index].measure = static_cast<float>(visible_surface_area(view));
  }

 private:
  /// Counts the silhouette pixels per row of the footprint (rows_before_ is indexed by
  /// image row; rows outside the footprint have none).
  void count_silhouette_rows(const cv::Mat& ids, const cv::Rect& footprint, std::uint8_t body_id) {
    rows_before_.assign(ids.rows + 1, 0);
    for (int i = 0; i < ids.rows; ++i) {
      const bool inside = i >= footprint.y && i < footprint.br().y;
      rows_before_[i + 1] =
          rows_before_[i] +
          (inside ? count_equal(ids.ptr<std::uint8_t>(i) + footprint.x, footprint.width, body_id) : 0);
    }
  }

  /// The silhouette pixel number `index` in row-major order.
  cv::Point silhouette_pixel(const cv::Mat& ids, const cv::Rect& footprint, std::uint8_t body_id, int index) const {
    const int row =
        static_cast<int>(std::upper_bound(rows_before_.begin(), rows_before_.end(), index) - rows_before_.begin()) - 1;
    const std::uint8_t* pixels = ids.ptr<std::uint8_t>(row);
    int nth = index - rows_before_[row];
    int j = footprint.x;
    // Whole chunks first: counting a chunk vectorises, testing pixel by pixel does not.
    for (constexpr int kChunk = 32; j + kChunk <= footprint.br().x; j += kChunk) {
      const int count = count_equal(pixels + j, kChunk, body_id);
      if (nth < count) break;
      nth -= count;
    }
    for (; j < footprint.br().x; ++j)
      if (pixels[j] == body_id && nth-- == 0) break;
    return {j, row};
  }

  /// Visible surface area in m²: the sum over silhouette pixels of the pixel's footprint on
  /// the surface, Z²/(f²·|n·r|) with r = (x, y, 1) the pixel's ray. Inverse depth w = s/Z is
  /// affine in (u, v) on a plane, with gradient (n_x, n_y)·s/(h f) for the plane n·X = h,
  /// so one-sided differences of w give m = n/h exactly inside faces, and the footprint is
  /// Z³·|m|/f² (since n·r = h/Z). Of the two one-sided differences per axis the smaller one
  /// is used: at a depth step or the silhouette edge that is the pixel's own surface; at a
  /// crease it may be the neighbouring face's slope, an error confined to crease pixels.
  /// The sum samples a grid of about 500 x 500 pixels (every 4th pixel of every 4th row at
  /// 2000 px, each weighing 16 pixels; every pixel up to 500 px): 16 times cheaper at the
  /// default size, for an error of at most about half a grid step along the outline
  /// (0.6 % for a view filling the image, well below in practice).
  double visible_surface_area(const RenderedView& view) const {
    const cv::Mat& w = view.images->inverse_depth;
    const cv::Mat& ids = view.images->ids;
    const Intrinsics& k = view.camera.intrinsics;
    const float s = static_cast<float>(view.images->depth_scale);
    const float f_over_s = static_cast<float>(k.fu) / s, inverse_s = 1.f / s;
    const float inverse_f = 1.f / static_cast<float>(k.fu);
    // Neighbours off the image or on the background come as 0.
    auto slope = [](float backward_neighbour, float centre, float forward_neighbour) {
      const float forward = forward_neighbour - centre, backward = centre - backward_neighbour;
      if (forward_neighbour > 0.f && backward_neighbour > 0.f)
        return std::abs(forward) < std::abs(backward) ? forward : backward;
      return forward_neighbour > 0.f ? forward : backward_neighbour > 0.f ? backward : 0.f;
    };
    const int stride = std::max(1, w.cols / kAreaSamplesAcross);
    const cv::Rect& footprint = view.images->footprint;
    double area = 0.0;
    for (int i = footprint.y; i < footprint.br().y; i += stride) {
      if (rows_before_[i + 1] == rows_before_[i]) continue;
      const float* row = w.ptr<float>(i);
      const float* above = i > 0 ? w.ptr<float>(i - 1) : nullptr;
      const float* below = i + 1 < w.rows ? w.ptr<float>(i + 1) : nullptr;
      const std::uint8_t* id_row = ids.ptr<std::uint8_t>(i);
      const float y = (static_cast<float>(i) - static_cast<float>(k.pv)) * inverse_f;
      float row_area = 0.f;
      for (int j = footprint.x; j < footprint.br().x; j += stride) {
        if (id_row[j] != view.body_id) continue;
        const float c = row[j];
        const float du = slope(j > 0 ? row[j - 1] : 0.f, c, j + 1 < w.cols ? row[j + 1] : 0.f);
        const float dv = slope(above ? above[j] : 0.f, c, below ? below[j] : 0.f);
        const float x = (static_cast<float>(j) - static_cast<float>(k.pu)) * inverse_f;
        const float mx = f_over_s * du, my = f_over_s * dv, mz = c * inverse_s - mx * x - my * y;
        const float z = s / c;
        row_area += z * z * z * std::sqrt(mx * mx + my * my + mz * mz);
      }
      area += row_area;
    }
    return stride * stride * area * inverse_f * inverse_f;
  }

  ViewpointModelParams params_;
  std::vector<int> rows_before_;  ///< silhouette pixels in the rows above row i
  UniformSubset subset_;
};

}  // namespace

std::uint8_t region_render_id(const AssociatedBody& body) {
  switch (body.kind) {
    case AssociatedBody::Kind::kFixed:
      return kFixedBodyId;
    case AssociatedBody::Kind::kSameRegion:
      return body.same_region_fixed ? kFixedSameRegionBodyId : kMovableSameRegionBodyId;
    case AssociatedBody::Kind::kMovable:
      return kMovableBodyId;
  }
  throw std::invalid_argument("viewpoint model: unknown kind of associated body");
}

std::unique_ptr<ViewSampler> make_view_sampler(ViewpointModel::Kind kind, const ViewpointModelParams& params) {
  if (kind == ViewpointModel::Kind::kRegion) return std::make_unique<RegionViewSampler>(params);
  return std::make_unique<DepthViewSampler>(params);
}

}  // namespace icgp
