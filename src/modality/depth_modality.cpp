// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/modality/depth_modality.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "icgp/geometry/rounding.h"
#include "icgp/modality/iteration_value.h"
#include "icgp/modality/normal_equations.h"

namespace icgp {
namespace {

/// The pixel (row, col) nearest to `projection`; false outside the image.
bool nearest_pixel(const DepthImage& depth, const Eigen::Vector2f& projection, int& row, int& col) {
  row = round_to_int(projection.y());
  col = round_to_int(projection.x());
  return row >= 0 && row < depth.depth.rows && col >= 0 && col < depth.depth.cols;
}

}  // namespace

DepthModality::DepthModality(Body& body, std::shared_ptr<const ViewpointModel> model, DepthParams params,
                             Sampling sampling)
    : Modality(body),
      model_(std::move(model)),
      params_(std::move(params)),
      crop_(body, params_.depth_camera, params_.occlusion.render_size),
      noise_(params_.noise) {
  if (!model_ || model_->kind() != ViewpointModel::Kind::kDepth)
    throw std::invalid_argument("depth modality of '" + body.name + "' needs a depth viewpoint model");
  occlusion_ = {params_.occlusion.radius, params_.occlusion.threshold};
  occlusion_offset_index_ = depth_offset_index(*model_, params_.occlusion.radius);
  modeled_offset_index_ = depth_offset_index(*model_, params_.occlusion.modeled_radius);
  if (sampling == Sampling::kDense) dense_.emplace(body, params_.depth_camera, params_.dense);
  correspondences_.reserve(params_.n_points_max);
}

const DepthImage* DepthModality::depth_image(const Frame& frame) const {
  const DepthImage* depth = frame.find_depth(params_.depth_camera);
  if (!depth)
    throw std::invalid_argument("depth modality of '" + body().name + "': the frame has no depth camera '" +
                                params_.depth_camera + "'");
  if (!depth->delivered()) return nullptr;
  if (depth->depth.type() != CV_32FC1 || depth->depth.cols != depth->intrinsics.width ||
      depth->depth.rows != depth->intrinsics.height)
    throw std::invalid_argument("depth modality of '" + body().name + "': camera '" + params_.depth_camera +
                                "' must give a CV_32FC1 depth image of its intrinsics' size " +
                                std::to_string(depth->intrinsics.width) + "x" +
                                std::to_string(depth->intrinsics.height) + " (got " +
                                std::to_string(depth->depth.cols) + "x" + std::to_string(depth->depth.rows) + ")");
  return depth;
}

Posef DepthModality::depth_T_body() const { return depth_T_reference_ * body().reference_T_body.cast<float>(); }

void DepthModality::start(const Frame&, const Renders&) {
  frames_since_start_ = 0;
  view_selector_.reset();  // a start owes nothing to the views of earlier frames
  noise_.reset();
  occlusions_.reset();
  hidden_by_bodies_.reset();
  scene_ = {};
  if (dense_) dense_->forget();
}

std::vector<RenderRequest> DepthModality::render_requests(const Frame& frame, Stage stage) const {
  const DepthImage* depth = frame.find_depth(params_.depth_camera);
  if (!depth) return {};
  if (dense_) {
    if (std::optional<RenderRequest> request = dense_->request(stage, *depth)) return {*request};
    return {};
  }
  if (!params_.occlusion.model) return {};
  if (std::optional<RenderRequest> request =
          crop_.request(stage, depth->intrinsics, depth->camera_T_reference))
    return {*request};
  return {};
}

DepthModality::Search DepthModality::search_of_pass(const DepthImage& depth, const Posef& depth_T_body,
                                                    int corr_iter) const {
  // At most considered_distance / stride_length samples along each side of the window: a
  // sparse grid finds a surface point close enough for a point-to-plane error, and the
  // first, widest search stays as cheap as the later ones. The grid is the image lattice
  // of multiples of one step for all points of the pass (their spacing at the body origin's
  // depth), not a grid of each window's own: the windows of neighbouring points then read
  // the same pixels, so a frame reads (and converts, see DepthImage::source) few distinct
  // pixels.
  Search search;
  search.considered_distance = static_cast<float>(iteration_value(params_.considered_distances, corr_iter));
  const float spacing = std::min(search.considered_distance, static_cast<float>(params_.stride_length));
  const float body_z = std::max(depth_T_body.translation().z(), 0.01f);
  search.step = std::max(1, static_cast<int>(std::ceil(2.f * spacing * static_cast<float>(depth.intrinsics.fu) / body_z)));
  // In the last, narrowest searches a window holds only a few lattice samples, and the one
  // nearest to a point near an edge may lie across it; the pixel the point projects to
  // keeps such points on their own surface at the right pose.
  search.projected_pixel = corr_iter + 1 >= static_cast<int>(params_.considered_distances.size());
  return search;
}

bool DepthModality::find_closest_measurement(const DepthImage& depth, const Eigen::Vector3f& point,
                                             const Search& search, Eigen::Vector3f& closest,
                                             bool& saw_depth) const {
  const Intrinsics& k = depth.intrinsics;
  const Eigen::Vector2f centre = k.project<float>(point);
  const float half = search.considered_distance * static_cast<float>(k.fu) / point.z();
  float best = search.considered_distance * search.considered_distance;
  bool found = false;
  const float ifu = static_cast<float>(1.0 / k.fu), ifv = static_cast<float>(1.0 / k.fv);
  const float pu = static_cast<float>(k.pu), pv = static_cast<float>(k.pv);
  const bool pinhole_rays = depth.rays.empty();
  // The measured point at a pixel, false where the pixel holds no measurement.
  const auto measured = [&](int row, int col, Eigen::Vector3f& P) {
    const float z = depth.at(row, col);
    if (!(z > 0.f && z < std::numeric_limits<float>::infinity())) return false;
    P = pinhole_rays ? Eigen::Vector3f((col - pu) * ifu * z, (row - pv) * ifv * z, z) : depth.point(row, col, z);
    return true;
  };
  const auto consider = [&](int row, int col) {
    Eigen::Vector3f P;
    if (!measured(row, col, P)) return;
    saw_depth = true;
    const float d2 = (P - point).squaredNorm();
    if (d2 < best) {
      best = d2;
      closest = P;
      found = true;
    }
  };
  int projected_row = 0, projected_col = 0;
  if (search.projected_pixel && nearest_pixel(depth, centre, projected_row, projected_col))
    consider(projected_row, projected_col);
  const int step = search.step;
  const int row_min = std::max(0, lattice_ceil(centre.y() - half, step));
  const int row_max = std::min(depth.depth.rows - 1, static_cast<int>(std::floor(centre.y() + half)));
  const int col_min = std::max(0, lattice_ceil(centre.x() - half, step));
  const int col_max = std::min(depth.depth.cols - 1, static_cast<int>(std::floor(centre.x() + half)));
  if (row_min > row_max || col_min > col_max) return found;

  // Any valid sample of the window bounds the winner's squared distance from above; the
  // sample nearest to the projection is usually close to the winner. The rays of one image
  // row all lie in a plane through the camera centre, so the point's distance to that plane
  // bounds the distance of every sample of the row from below (likewise for columns): rows
  // and columns that cannot hold a sample within the upper bound are not read. The samples
  // left are visited in the full search's order, so the result is the full search's.
  // Points off the pinhole rays (a distorted sensor's cloud) have no such bound.
  if (!pinhole_rays) {
    for (int row = row_min; row <= row_max; row += step)
      for (int col = col_min; col <= col_max; col += step) consider(row, col);
    return found;
  }
  float upper = best;
  const int near_row = std::clamp(round_to_int(centre.y() / step) * step, row_min, row_max - (row_max - row_min) % step);
  const int near_col = std::clamp(round_to_int(centre.x() / step) * step, col_min, col_max - (col_max - col_min) % step);
  Eigen::Vector3f near;
  if (measured(near_row, near_col, near)) upper = std::min(upper, (near - point).squaredNorm());
  // The margin covers the rounding of the bounds, which must never exclude a winner.
  const float limit = upper * 1.001f + 1e-12f;
  const auto beyond = [&](float gap, float normalised) { return gap * gap > limit * (1.f + normalised * normalised); };
  for (int row = row_min; row <= row_max; row += step) {
    const float y = (row - pv) * ifv;
    if (beyond(point.y() - y * point.z(), y)) continue;
    for (int col = col_min; col <= col_max; col += step) {
      const float x = (col - pu) * ifu;
      if (!beyond(point.x() - x * point.z(), x)) consider(row, col);
    }
  }
  return found;
}

void DepthModality::correspondences(const Frame& frame, const Renders& renders, int corr_iter) {
  const DepthImage* delivered = depth_image(frame);
  last_corr_iter_ = corr_iter;
  if (!delivered) {  // no depth this frame: no data, and the cue abstains
    correspondences_.clear();
    n_not_expected_ = 0;
    saw_depth_ = false;
    return;
  }
  depth_T_reference_ = delivered->camera_T_reference.cast<float>();
  if (dense_)
    dense_correspondences(*delivered, renders, corr_iter);
  else
    model_point_correspondences(*delivered, renders, corr_iter);
  estimate_noise();
}

void DepthModality::dense_correspondences(const DepthImage& depth, const Renders& renders, int corr_iter) {
  const auto considered_distance = static_cast<float>(iteration_value(params_.considered_distances, corr_iter));
  const DenseDepthSampling::Counts counts = dense_->collect(renders, depth, considered_distance, correspondences_);
  n_considered_ = counts.n_on_body;
  n_not_expected_ = 0;  // pixels another body covers show that body in the render: not counted
  saw_depth_ = counts.saw_depth;
}

void DepthModality::model_point_correspondences(const DepthImage& depth, const Renders& renders, int corr_iter) {
  const Posef depth_T_body_now = depth_T_body();
  const Eigen::Vector3f camera_in_body = depth_T_body_now.inverse().translation();
  const int view = view_selector_.select(*model_, camera_in_body.normalized());
  const Search search = search_of_pass(depth, depth_T_body_now, corr_iter);
  const bool test_occlusions = params_.occlusion.measure && frames_since_start_ >= params_.n_unoccluded_iterations;

  n_considered_ = std::min(model_->view_point_count(view), params_.n_points_max);
  const ModelPoint* points = model_->points(view);
  if (corr_iter == 0)
    scene_ = crop_.find(renders, depth.intrinsics, depth.camera_T_reference);
  const OcclusionParams& o = params_.occlusion;
  hidden_by_bodies_.update(corr_iter, view, n_considered_, [&](int p) {
    return scene_.hidden(depth_T_body_now * points[p].position, model_->depth_offsets(view, p)[modeled_offset_index_],
                         o.modeled_radius, o.modeled_threshold);
  });
  if (test_occlusions)
    occlusions_.update(corr_iter, view, n_considered_, [&](int p) {
      return occlusion_.occluded(depth, depth_T_body_now * points[p].position,
                                 model_->depth_offsets(view, p)[occlusion_offset_index_]);
    });
  // The last pass's searches start at the pixel each point projects to: scattered pixels
  // that move with the body, which a depth converted on read had not read before.
  if (search.projected_pixel && depth.takes_read_soon()) {
    projected_pixels_.clear();
    for (int p = 0; p < n_considered_; ++p) {
      const Eigen::Vector3f X = depth_T_body_now * points[p].position;
      int row = 0, col = 0;
      if (X.z() > 0.f && nearest_pixel(depth, depth.intrinsics.project<float>(X), row, col))
        projected_pixels_.emplace_back(col, row);
    }
    depth.read_soon(projected_pixels_);
  }
  auto collect = [&](bool with_occlusion_test) {
    correspondences_.clear();
    saw_depth_ = false;
    n_not_expected_ = 0;
    for (int p = 0; p < n_considered_; ++p) {
      const Eigen::Vector3f X = depth_T_body_now * points[p].position;
      if (X.z() <= 0.f) continue;
      if (hidden_by_bodies_.occluded(p)) {
        ++n_not_expected_;
        continue;
      }
      if (with_occlusion_test && occlusions_.occluded(p)) continue;
      // What the camera cannot see (outside the image or the mask) is not expected either.
      int row = 0, col = 0;
      if (!nearest_pixel(depth, depth.intrinsics.project<float>(X), row, col) || !depth.mask.usable(row, col)) {
        ++n_not_expected_;
        continue;
      }
      Eigen::Vector3f measured;
      if (!find_closest_measurement(depth, X, search, measured, saw_depth_)) continue;
      correspondences_.push_back({points[p].position, points[p].normal, measured});
    }
  };
  collect(test_occlusions);
  if (test_occlusions && static_cast<int>(correspondences_.size()) < params_.min_n_unoccluded_points) collect(false);
}

void DepthModality::estimate_noise() {
  noise_.estimate([&](auto add) {
    const Posef body_T_depth = depth_T_body().inverse();
    for (const DepthCorrespondence& c : correspondences_)
      add(c.body_normal.dot(c.body_point - body_T_depth * c.measured) / c.measured.z());
  });
}

double DepthModality::sigma(int corr_iter) const {
  return noise_.sigma(iteration_value(params_.standard_deviations, corr_iter));
}

CueTerms DepthModality::gradient_hessian(int corr_iter, int) {
  const Posef body_T_depth = depth_T_body().inverse();
  const Eigen::Matrix3f& R = body_T_depth.rotation();
  const Eigen::Vector3f& t = body_T_depth.translation();
  const float sigma = static_cast<float>(this->sigma(corr_iter));
  // A block of correspondences at a time, each step a loop over its lanes (NormalEquations):
  // dense depth pairs thousands of pixels, and lane by lane every step is vectorised.
  constexpr int kLanes = NormalEquations::kLanes;
  NormalEquations sums;
  const std::size_t n = correspondences_.size();
  for (std::size_t first = 0; first < n; first += kLanes) {
    const int count = static_cast<int>(std::min<std::size_t>(kLanes, n - first));
    float measured[3][kLanes], point[3][kLanes], normal[3][kLanes];
    for (int l = 0; l < kLanes; ++l) {
      // A partial block repeats its last correspondence, with weight 0.
      const DepthCorrespondence& c = correspondences_[first + std::min(l, count - 1)];
      for (int i = 0; i < 3; ++i) {
        measured[i][l] = c.measured[i];
        point[i][l] = c.body_point[i];
        normal[i][l] = c.body_normal[i];
      }
    }
    float rows[6][kLanes], residuals[kLanes], normalised[kLanes], weights[kLanes], weighted_residuals[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      float P[3];  // the measured point in the body frame
      for (int i = 0; i < 3; ++i)
        P[i] = R(i, 0) * measured[0][l] + R(i, 1) * measured[1][l] + R(i, 2) * measured[2][l] + t[i];
      residuals[l] = normal[0][l] * (point[0][l] - P[0]) + normal[1][l] * (point[1][l] - P[1]) +
                     normal[2][l] * (point[2][l] - P[2]);
      normalised[l] = residuals[l] / measured[2][l];
      rows[0][l] = P[1] * normal[2][l] - P[2] * normal[1][l];  // P × n
      rows[1][l] = P[2] * normal[0][l] - P[0] * normal[2][l];
      rows[2][l] = P[0] * normal[1][l] - P[1] * normal[0][l];
      for (int i = 0; i < 3; ++i) rows[3 + i][l] = normal[i][l];
    }
    noise_.weights(normalised, sigma, weights);
    for (int l = 0; l < kLanes; ++l) {
      const float z = measured[2][l];
      weights[l] /= sigma * sigma * z * z;
      weighted_residuals[l] = weights[l] * residuals[l];
    }
    for (int l = count; l < kLanes; ++l) weights[l] = weighted_residuals[l] = 0.f;
    sums.add(rows, weights, weighted_residuals);
  }
  return sums.terms(static_cast<int>(n));
}

double DepthModality::log_likelihood(int corr_iter) const {
  // Double precision throughout: numeric derivatives of this function must resolve
  // variations far below float resolution of a pose.
  const Pose body_T_depth = (depth_T_reference_.cast<double>() * body().reference_T_body).inverse();
  const double sigma = this->sigma(corr_iter);
  double sum = 0.0;
  for (const DepthCorrespondence& c : correspondences_) {
    const double residual = c.body_normal.cast<double>().dot(c.body_point.cast<double>() -
                                                             body_T_depth * c.measured.cast<double>());
    sum -= noise_.loss(residual / (sigma * c.measured.z()));
  }
  return sum;
}

void DepthModality::append_residuals(std::vector<double>& residuals, std::vector<double>& weights) const {
  const Pose body_T_depth = (depth_T_reference_.cast<double>() * body().reference_T_body).inverse();
  for (const DepthCorrespondence& c : correspondences_) {
    residuals.push_back(c.body_normal.cast<double>().dot(c.body_point.cast<double>() - body_T_depth * c.measured.cast<double>()));
    weights.push_back(1.0);  // every correspondence passed the distance gate and counts fully
  }
}

void DepthModality::finish(const Frame&, const Renders&) {
  update_quality();
  ++frames_since_start_;
}

void DepthModality::update_quality() {
  // A point fits when its point-to-plane error is below half the last search radius
  // (5 mm by default): far below what a wrong pose leaves, far above sensor noise.
  const float inlier = 0.5f * static_cast<float>(params_.considered_distances.back());
  const Posef body_T_depth = depth_T_body().inverse();
  int n_inliers = 0;
  for (const DepthCorrespondence& c : correspondences_)
    if (std::abs(c.body_normal.dot(c.body_point - body_T_depth * c.measured)) < inlier) ++n_inliers;
  // Points another body hides or the camera cannot see are not expected to find data,
  // unlike those an unknown occluder hides: they do not count against the score.
  const int n_expected = n_considered_ - n_not_expected_;
  quality_.n_valid = static_cast<int>(correspondences_.size());
  quality_.valid_fraction = n_expected > 0 ? static_cast<double>(correspondences_.size()) / n_expected : 0.0;
  quality_.score = n_expected > 0 ? static_cast<double>(n_inliers) / n_expected : 0.0;
  quality_.abstained = !saw_depth_;
  quality_.sigma = sigma(last_corr_iter_);
}

}  // namespace icgp
