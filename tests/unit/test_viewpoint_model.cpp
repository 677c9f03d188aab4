// SPDX-License-Identifier: GPL-2.0-or-later
// Sparse viewpoint models against independent truth: icosphere geometry, the analytic
// outline and faces of a box, brute-force depth offsets, determinism, and a disk cache that
// never trusts a bad file. Coarse models (42 views, 400 px) keep this fast on llvmpipe.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <mutex>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "icgp/base/standard_stream_capture.h"
#include "icgp/base/stop_request.h"
#include "icgp/io/mesh_loader.h"
#include "icgp/model/icosphere.h"
#include "icgp/model/model_cache.h"
#include "icgp/model/model_key.h"
#include "icgp/model/viewpoint_model_generator.h"
#include "icgp/modality/view_selector.h"
#include "icgp/render/renderer.h"
#include "test_meshes.h"
#include "test_temp_dir.h"

using namespace icgp;
namespace fs = std::filesystem;

namespace {

const Eigen::Vector3d kHalf(0.05, 0.03, 0.02);  // the test box: 10 x 6 x 4 cm

Mesh box() { return test::make_box(2 * kHalf.x(), 2 * kHalf.y(), 2 * kHalf.z()); }

ViewpointModelParams coarse_params() {
  ViewpointModelParams p;
  p.n_divides = 1;
  p.image_size = 400;
  p.n_points = 60;
  p.max_radius_depth_offset = 0.02;
  return p;
}

ModelGenerationOptions quiet(int n_threads = 0) {
  ModelGenerationOptions o;
  o.n_threads = n_threads;
  o.print_progress = false;
  return o;
}

/// Distance of a point to the surface of the test box (exact near the surface).
double box_surface_distance(const Eigen::Vector3d& p) { return std::abs((p.cwiseAbs() - kHalf).maxCoeff()); }

Eigen::Vector2d project(const ViewCamera& camera, const Eigen::Vector3f& body_point) {
  return camera.intrinsics.project<double>(camera.camera_T_body * body_point.cast<double>());
}

cv::Point2f point2f(const Eigen::Vector2d& x) { return {static_cast<float>(x.x()), static_cast<float>(x.y())}; }

/// Visible area of the box from a camera at `eye` (body frame): a convex body shows every
/// face whose outer side the camera is on, whole.
double visible_box_area(const Eigen::Vector3d& eye) {
  double area = 0.0;
  for (int axis = 0; axis < 3; ++axis)
    if (std::abs(eye[axis]) > kHalf[axis]) area += 4.0 * kHalf[(axis + 1) % 3] * kHalf[(axis + 2) % 3];
  return area;
}

bool same_payload(const ViewpointModel& a, const ViewpointModel& b) {
  return a.payload_size() == b.payload_size() && std::memcmp(a.payload(), b.payload(), a.payload_size()) == 0;
}


struct BoxModels {
  ViewpointModel region, depth;
};

const BoxModels& box_models() {
  static const BoxModels models = [] {
    std::vector<ViewpointModel> m = generate_viewpoint_models(
        box(), {{ViewpointModel::Kind::kRegion, coarse_params()}, {ViewpointModel::Kind::kDepth, coarse_params()}},
        quiet());
    return BoxModels{m[0], m[1]};
  }();
  return models;
}

}  // namespace

TEST_CASE("icosphere: 10*4^n+2 unit directions, evenly spread, in a fixed order") {
  for (int n = 0; n <= 3; ++n) {
    const std::vector<Eigen::Vector3f> d = icosphere_directions(n);
    REQUIRE(d.size() == static_cast<std::size_t>(10 * (1 << (2 * n)) + 2));
    double smallest = 10.0, largest = 0.0;
    for (std::size_t i = 0; i < d.size(); ++i) {
      CHECK(d[i].norm() == Approx(1.0).margin(1e-6));
      float best = -2.f;
      for (std::size_t j = 0; j < d.size(); ++j)
        if (j != i) best = std::max(best, d[i].dot(d[j]));
      const double angle = std::acos(std::min(1.0, static_cast<double>(best)));
      smallest = std::min(smallest, angle);
      largest = std::max(largest, angle);
    }
    INFO("n_divides " << n << ": nearest-neighbour angles " << smallest << " to " << largest << " rad");
    CHECK(largest / smallest < 1.25);
    CHECK(icosphere_directions(n) == d);
  }
  // The axes are views from one subdivision on: fronto-parallel views of boxes exist.
  const std::vector<Eigen::Vector3f> d = icosphere_directions(1);
  for (const Eigen::Vector3f& axis :
       {Eigen::Vector3f(1, 0, 0), Eigen::Vector3f(0, 1, 0), Eigen::Vector3f(0, 0, 1), Eigen::Vector3f(0, 0, -1)}) {
    float best = -2.f;
    for (const auto& v : d) best = std::max(best, v.dot(axis));
    CHECK(best == Approx(1.f).margin(1e-6));
  }
  CHECK_THROWS_AS(icosphere_directions(-1), std::invalid_argument);
}

namespace {

/// A model with no points whose views look along the icosphere directions of n_divides 2.
ViewpointModel model_of_views() {
  ViewpointModelParams params;
  params.n_divides = 2;
  params.n_points = 1;
  ViewpointModel model(ViewpointModel::Kind::kDepth, params, 0);
  const std::vector<Eigen::Vector3f> d = icosphere_directions(2);
  for (std::size_t v = 0; v < d.size(); ++v) model.mutable_views()[v].direction = d[v];
  return model;
}

}  // namespace

TEST_CASE("viewpoint model: closest_view picks each view for its own direction") {
  const ViewpointModel model = model_of_views();
  const std::vector<Eigen::Vector3f> d = icosphere_directions(2);
  for (int v = 0; v < model.n_views(); ++v) {
    CHECK(model.closest_view(d[v]) == v);
    // A slightly tilted direction still belongs to its view (views are ~15 degrees apart).
    const Eigen::Vector3f tilted = (d[v] + 0.05f * d[v].unitOrthogonal()).normalized();
    CHECK(model.closest_view(tilted) == v);
  }
}

TEST_CASE("view selector: keeps its view across a boundary until another is closer by the margin") {
  const ViewpointModel model = model_of_views();
  const std::vector<Eigen::Vector3f> d = icosphere_directions(2);
  // Two neighbouring views A and B, and directions along the great circle from A to B.
  const int a = 0;
  int b = 1;
  for (int v = 1; v < model.n_views(); ++v)
    if (d[v].dot(d[a]) > d[b].dot(d[a])) b = v;
  const float spacing = std::acos(d[a].dot(d[b]));
  const Eigen::Vector3f axis = d[a].cross(d[b]).normalized();
  const auto towards_b = [&](float angle) { return Eigen::AngleAxisf(angle, axis) * d[a]; };
  const float margin = ViewSelector::kHysteresisDegrees * static_cast<float>(M_PI) / 180.f;

  ViewSelector selector;
  REQUIRE(selector.select(model, d[a]) == a);
  // Past the midpoint, but B not yet closer by the margin: A stays (a fresh selector picks B).
  const Eigen::Vector3f just_past = towards_b(0.5f * spacing + 0.4f * margin);
  REQUIRE(model.closest_view(just_past) == b);
  CHECK(selector.select(model, just_past) == a);
  ViewSelector fresh;
  CHECK(fresh.select(model, just_past) == b);
  // B closer by more than the margin: the selector moves to it, and back only past the
  // margin on the other side.
  CHECK(selector.select(model, towards_b(0.5f * spacing + 0.6f * margin)) == b);
  CHECK(selector.select(model, towards_b(0.5f * spacing - 0.4f * margin)) == b);
  CHECK(selector.select(model, towards_b(0.5f * spacing - 0.6f * margin)) == a);
}

TEST_CASE("viewpoint model: parameters are validated") {
  ViewpointModelParams p = coarse_params();
  CHECK(p.n_views() == 42);
  CHECK(p.n_depth_offsets() == 10);
  CHECK(ViewpointModelParams().n_depth_offsets() == 25);
  p.normal_chord_offset = 0;
  CHECK_THROWS_WITH(generate_viewpoint_model(ViewpointModel::Kind::kRegion, box(), p, quiet()),
                    Catch::Contains("normal_chord_offset"));
  p = coarse_params();
  p.sphere_radius = 0.05;  // inside the box's bounding sphere (6.2 cm)
  CHECK_THROWS_WITH(generate_viewpoint_model(ViewpointModel::Kind::kRegion, box(), p, quiet()),
                    Catch::Contains("sphere_radius"));
}

TEST_CASE("renderer: silhouette renders equal full renders, also across moving footprints") {
  Renderer renderer;
  const auto a = renderer.add_body(box(), 1);
  const auto b = renderer.add_body(test::make_box(0.03f, 0.03f, 0.03f), 5);
  const Intrinsics k = Intrinsics::centred(320, 240, 300.0);
  SilhouetteImages images;
  auto compare = [&](const Pose& camera_T_world) {
    renderer.render_silhouette(k, camera_T_world, images);
    const RenderOutput truth = renderer.render(k, camera_T_world, kRenderIds | kRenderDepth);
    CHECK(cv::countNonZero(images.ids != truth.ids) == 0);
    double worst = 0.0;
    for (int i = 0; i < k.height; ++i)
      for (int j = 0; j < k.width; ++j)
        worst = std::max(worst, static_cast<double>(std::abs(images.depth(i, j) - truth.depth.at<float>(i, j))));
    CHECK(worst < 1e-5);
    CHECK(cv::countNonZero(truth.ids) == cv::countNonZero(truth.ids(images.footprint)));
  };
  renderer.set_body_visible(b, false);  // one body: ids come from depth
  compare(look_at<double>(Eigen::Vector3d(0.1, 0.2, 0.4), Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ()));
  compare(look_at<double>(Eigen::Vector3d(-0.3, 0.05, 0.2), Eigen::Vector3d(0.02, 0, 0), Eigen::Vector3d::UnitZ()));
  renderer.set_body_visible(b, true);  // two bodies: ids drawn
  renderer.set_body_pose(b, Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.0, 0.06)));
  compare(look_at<double>(Eigen::Vector3d(0.05, 0.1, 0.5), Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY()));
  renderer.set_body_pose(a, Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.0, 5.0)));  // behind the camera
  renderer.set_body_pose(b, Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.0, 5.0)));
  compare(look_at<double>(Eigen::Vector3d(0.0, 0.0, 1.0), Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY()));
  CHECK(images.footprint.empty());
}

TEST_CASE("region model of a box: contour points on the box, on its outline, with outward normals") {
  const ViewpointModel& model = box_models().region;
  REQUIRE(model.n_views() == 42);
  REQUIRE(model.kind() == ViewpointModel::Kind::kRegion);
  const double radius = box().radius_about_origin();
  int checked = 0;
  for (int v = 0; v < model.n_views(); ++v) {
    const ViewCamera camera = view_camera(model.view(v).direction, model.params(), radius);
    const std::vector<cv::Point2f> outline = test::projected_box_outline(camera.intrinsics, camera.camera_T_body, kHalf);
    const double px_per_metre = camera.intrinsics.fu / model.params().sphere_radius;
    const double metres_per_px = (model.params().sphere_radius + radius) / camera.intrinsics.fu;
    REQUIRE(model.view_point_count(v) == model.n_points());
    CHECK(model.view(v).measure > 0.f);
    for (int p = 0; p < model.view_point_count(v); ++p) {
      const ModelPoint& point = model.points(v)[p];
      // Contour points sit on the silhouette's edge, up to half a pixel beside the last pixel centre on the box.
      CHECK(box_surface_distance(point.position.cast<double>()) < metres_per_px);
      const Eigen::Vector2d x = project(camera, point.position);
      CHECK(std::abs(cv::pointPolygonTest(outline, point2f(x), true)) < 1.2);
      CHECK(point.normal.norm() == Approx(1.f).margin(1e-5));
      // In the image plane, to the precision normals are stored with (octahedral, 16 bits).
      CHECK(std::abs(point.normal.dot(model.view(v).direction)) < 1e-4);
      // Three pixels along the normal leave the outline, three against it enter it.
      const Eigen::Vector2d n = (project(camera, point.position + 1e-3f * point.normal) - x).normalized();
      CHECK(cv::pointPolygonTest(outline, point2f(x + 3.0 * n), false) < 0);
      CHECK(cv::pointPolygonTest(outline, point2f(x - 3.0 * n), false) > 0);
      CHECK(point.foreground_distance * px_per_metre > 1.0);
      CHECK(point.background_distance > 0.f);
      ++checked;
    }
  }
  CHECK(checked == 42 * 60);
}

TEST_CASE("region model of a frame: normals on the hole's outline point into the hole") {
  Mesh frame;  // a square ring of four bars: seen from +z, a silhouette with a square hole
  for (const auto& [size, centre] : {std::pair{Eigen::Vector3f(0.10f, 0.02f, 0.02f), Eigen::Vector3f(0, 0.04f, 0)},
                                     std::pair{Eigen::Vector3f(0.10f, 0.02f, 0.02f), Eigen::Vector3f(0, -0.04f, 0)},
                                     std::pair{Eigen::Vector3f(0.02f, 0.10f, 0.02f), Eigen::Vector3f(0.04f, 0, 0)},
                                     std::pair{Eigen::Vector3f(0.02f, 0.10f, 0.02f), Eigen::Vector3f(-0.04f, 0, 0)}}) {
    Mesh bar = test::make_box(size.x(), size.y(), size.z());
    bar.transform(Posef(Eigen::Matrix3f::Identity(), centre));
    frame.append(bar);
  }
  const ViewpointModel model = generate_viewpoint_model(ViewpointModel::Kind::kRegion, frame, coarse_params(), quiet());
  const int v = model.closest_view(Eigen::Vector3f::UnitZ());
  const ViewCamera camera = view_camera(model.view(v).direction, model.params(), frame.radius_about_origin());
  Renderer renderer;
  renderer.add_body(frame, 1);
  const cv::Mat ids = renderer.render(camera.intrinsics, camera.camera_T_body, kRenderIds).ids;
  auto inside = [&](const Eigen::Vector2d& x) {
    return ids.at<uchar>(static_cast<int>(std::lround(x.y())), static_cast<int>(std::lround(x.x()))) != 0;
  };
  int on_hole = 0;
  for (int p = 0; p < model.view_point_count(v); ++p) {
    const ModelPoint& point = model.points(v)[p];
    const Eigen::Vector2d x = project(camera, point.position);
    const Eigen::Vector2d n = (project(camera, point.position + 1e-3f * point.normal) - x).normalized();
    CHECK(!inside(x + 3.0 * n));
    CHECK(inside(x - 3.0 * n));
    const bool hole = std::abs(point.position.x()) < 0.031f && std::abs(point.position.y()) < 0.031f;
    if (hole) {
      ++on_hole;
      CHECK(point.background_distance < 0.07f);  // across the hole to the opposite bar
      if (point.normal.cwiseAbs().maxCoeff() > 0.99f)
        CHECK(point.foreground_distance == Approx(0.02).margin(0.002));  // straight across the bar
    }
  }
  CHECK(on_hole > 10);
}

TEST_CASE("region model of a box: fronto-parallel distances are the box width and infinity") {
  const ViewpointModel& model = box_models().region;
  const int v = model.closest_view(Eigen::Vector3f::UnitZ());
  REQUIRE(model.view(v).direction.dot(Eigen::Vector3f::UnitZ()) == Approx(1.f));
  const ViewCamera camera = view_camera(model.view(v).direction, model.params(), box().radius_about_origin());
  // Only the front face (z = +h) is seen: its rectangle is the silhouette.
  const double metres_per_px = (model.params().sphere_radius - kHalf.z()) / camera.intrinsics.fu;
  int across = 0;
  for (int p = 0; p < model.view_point_count(v); ++p) {
    const ModelPoint& point = model.points(v)[p];
    CHECK(point.position.z() == Approx(kHalf.z()).margin(1e-5));
    CHECK(point.background_distance == std::numeric_limits<float>::infinity());
    const Eigen::Vector3f n = point.normal;
    const bool near_corner = (kHalf.x() - std::abs(point.position.x())) < 5 * metres_per_px &&
                             (kHalf.y() - std::abs(point.position.y())) < 5 * metres_per_px;
    if (near_corner) continue;
    if (std::abs(n.x()) > 0.99f) {
      CHECK(point.foreground_distance == Approx(2 * kHalf.x()).margin(2 * metres_per_px));
      ++across;
    } else if (std::abs(n.y()) > 0.99f) {
      CHECK(point.foreground_distance == Approx(2 * kHalf.y()).margin(2 * metres_per_px));
      ++across;
    }
  }
  CHECK(across > 40);
  // Contour length: the rectangle's perimeter, less the corners cut by pixel centres.
  CHECK(model.view(v).measure == Approx(4 * (kHalf.x() + kHalf.y())).epsilon(0.02));
}

TEST_CASE("depth model of a box: points on the faces, with their face normals, and the visible area") {
  const ViewpointModel& model = box_models().depth;
  REQUIRE(model.kind() == ViewpointModel::Kind::kDepth);
  for (int v = 0; v < model.n_views(); ++v) {
    const Eigen::Vector3f d = model.view(v).direction;
    REQUIRE(model.view_point_count(v) == model.n_points());
    for (int p = 0; p < model.view_point_count(v); ++p) {
      const ModelPoint& point = model.points(v)[p];
      const Eigen::Vector3d X = point.position.cast<double>();
      REQUIRE(box_surface_distance(X) < 1e-5);
      bool on_a_face_with_its_normal = false;  // a point on an edge may take either face
      for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(std::abs(X[axis]) - kHalf[axis]) > 1e-5) continue;
        const Eigen::Vector3f face_normal = (X[axis] > 0 ? 1.f : -1.f) * Eigen::Vector3f::Unit(axis);
        on_a_face_with_its_normal = on_a_face_with_its_normal || point.normal.dot(face_normal) > 0.99999f;
      }
      CHECK(on_a_face_with_its_normal);
      CHECK(point.normal.dot(d) > 0.f);  // seen faces face the camera
    }
    const double truth = visible_box_area(model.params().sphere_radius * d.cast<double>());
    CHECK(model.view(v).measure == Approx(truth).epsilon(0.015));
  }
}

TEST_CASE("depth model of a faceted cylinder: the normals the renderer's normal image shows") {
  const Mesh cylinder = load_mesh(std::string(ICGP_MODELS_DIR) + "/labelled_cylinder/labelled_cylinder.obj");
  const ViewpointModel model =
      generate_viewpoint_model(ViewpointModel::Kind::kDepth, cylinder, coarse_params(), quiet());
  Renderer renderer;
  renderer.add_body(cylinder, 1);
  int agree = 0, total = 0;
  for (int v = 0; v < model.n_views(); v += 5) {
    const ViewCamera camera = view_camera(model.view(v).direction, model.params(), cylinder.radius_about_origin());
    const cv::Mat normals = renderer.render(camera.intrinsics, camera.camera_T_body, kRenderNormals).normals;
    for (int p = 0; p < model.view_point_count(v); ++p, ++total) {
      const ModelPoint& point = model.points(v)[p];
      const Eigen::Vector2d x = project(camera, point.position);  // a pixel centre
      const cv::Vec3f n =
          normals.at<cv::Vec3f>(static_cast<int>(std::lround(x.y())), static_cast<int>(std::lround(x.x())));
      const Eigen::Vector3d body_normal =
          camera.camera_T_body.rotation().transpose() * Eigen::Vector3d(n[0], n[1], n[2]);
      agree += point.normal.cast<double>().dot(body_normal) > 0.9999;
    }
  }
  // A pixel centre on the edge between two facets may go to either: nearly all agree.
  CHECK(agree >= total - total / 100);
}

TEST_CASE("depth offsets: non-decreasing, zero inside a fronto-parallel face, bounded by brute force") {
  const ViewpointModel& region = box_models().region;
  const ViewpointModel& depth = box_models().depth;
  const int n = depth.n_depth_offsets();
  for (const ViewpointModel* model : {&region, &depth})
    for (int v = 0; v < model->n_views(); ++v)
      for (int p = 0; p < model->view_point_count(v); ++p) {
        const float* o = model->depth_offsets(v, p);
        CHECK(o[0] >= 0.f);
        for (int k = 1; k < n; ++k) CHECK(o[k] >= o[k - 1]);
      }

  // Fronto-parallel: discs that stay on the front face see no nearer surface.
  const int front = depth.closest_view(Eigen::Vector3f::UnitZ());
  const double stride = depth.params().stride_depth_offset;
  int zero_checks = 0;
  for (int p = 0; p < depth.view_point_count(front); ++p) {
    const Eigen::Vector3f X = depth.points(front)[p].position;
    const double margin = std::min(kHalf.x() - std::abs(X.x()), kHalf.y() - std::abs(X.y()));
    for (int k = 0; k < n && 1.4 * (k + 1) * stride + 0.001 < margin; ++k, ++zero_checks)
      CHECK(depth.depth_offsets(front, p)[k] == 0.f);
  }
  CHECK(zero_checks > 20);

  // Oblique views against a brute-force scan of an independent depth render: never below
  // the exact disc, never above the disc grown by the documented overreach. A contour
  // point lies up to a pixel from the pixel centre its offsets were taken at, so the discs
  // are shrunk and grown by that much around its projection.
  Renderer renderer;
  renderer.add_body(box(), 1);
  for (const ViewpointModel* model : {&region, &depth})
    for (const Eigen::Vector3f direction : {Eigen::Vector3f(1, 1, 1), Eigen::Vector3f(-1, 0.3f, 0.5f)}) {
      const int v = model->closest_view(direction.normalized());
      const ViewCamera camera = view_camera(model->view(v).direction, model->params(), box().radius_about_origin());
      const cv::Mat Z = renderer.render(camera.intrinsics, camera.camera_T_body, kRenderDepth).depth;
      const double slack = model == &region ? 1.0 : 0.0;
      for (int p = 0; p < model->view_point_count(v); p += 3) {
        const Eigen::Vector3d X = camera.camera_T_body * model->points(v)[p].position.cast<double>();
        const Eigen::Vector2d x = camera.intrinsics.project<double>(X);
        const double z = X.z();
        for (int k = 0; k < n; ++k) {
          const double R = (k + 1) * stride * camera.intrinsics.fu / z;
          const double inner = R - slack, outer = R + std::sqrt(2.0) * R / 4 + 1.5 + slack;
          double exact = 0.0, grown = 0.0;
          for (int i = std::max(0, static_cast<int>(x.y() - outer));
               i <= std::min(Z.rows - 1, static_cast<int>(x.y() + outer) + 1); ++i)
            for (int j = std::max(0, static_cast<int>(x.x() - outer));
                 j <= std::min(Z.cols - 1, static_cast<int>(x.x() + outer) + 1); ++j) {
              const float zij = Z.at<float>(i, j);
              if (zij <= 0.f) continue;
              const double r = std::hypot(i - x.y(), j - x.x());
              if (r <= inner) exact = std::max(exact, z - zij);
              if (r <= outer) grown = std::max(grown, z - zij);
            }
          const float offset = model->depth_offsets(v, p)[k];
          CHECK(offset >= exact - 1e-6);
          // Stored rounded up to the next step of a byte's logarithmic scale (5.9 % apart).
          CHECK(offset <= grown * 1.06 + 1e-5);
        }
      }
    }
}

TEST_CASE("viewpoint models are deterministic, whatever the threads") {
  const ViewpointModelParams p = coarse_params();
  const Mesh mesh = box();
  for (auto kind : {ViewpointModel::Kind::kRegion, ViewpointModel::Kind::kDepth}) {
    const ViewpointModel one = generate_viewpoint_model(kind, mesh, p, quiet(1));
    const ViewpointModel two = generate_viewpoint_model(kind, mesh, p, quiet(2));
    CHECK(same_payload(one, two));
    CHECK(same_payload(one, generate_viewpoint_model(kind, mesh, p, quiet(2))));
    CHECK(one.key() == viewpoint_model_key(kind, mesh, p));
  }
  // Alone or sharing renders with the other kind: the same models.
  CHECK(same_payload(generate_viewpoint_model(ViewpointModel::Kind::kDepth, mesh, p, quiet()), box_models().depth));
}

TEST_CASE("viewpoint models made in the background: any view on demand, then byte-identical to the foreground's") {
  const ViewpointModelParams p = coarse_params();
  const Mesh mesh = box();
  const std::vector<ModelRequest> requests = {{ViewpointModel::Kind::kRegion, p}, {ViewpointModel::Kind::kDepth, p}};
  ModelGenerationOptions options = quiet(1);
  options.in_background = true;
  // Called on a generation thread: only recorded there (Catch's assertions are not thread-safe).
  std::mutex completed_mutex;
  std::vector<std::pair<std::size_t, std::uint64_t>> completed;  // request, key
  options.on_complete = [&](std::size_t request, const ViewpointModel& model) {
    std::lock_guard<std::mutex> lock(completed_mutex);
    completed.emplace_back(request, model.key());
  };
  {
    const std::vector<ViewpointModel> models = generate_viewpoint_models(mesh, requests, options);
    REQUIRE(models.size() == 2);
    // Directions are there before any view is made; a required view is the foreground's.
    const ViewpointModel& region = models[0];
    const ViewpointModel& complete_region = box_models().region;
    for (int v = 0; v < region.n_views(); ++v) CHECK(region.view(v).direction == complete_region.view(v).direction);
    const Eigen::Vector3f direction = Eigen::Vector3f(0.3f, -0.8f, 0.5f).normalized();
    const int v = region.closest_view(direction);
    region.require_view(v);
    REQUIRE(region.view_point_count(v) == complete_region.view_point_count(v));
    CHECK(region.view_point_count(v) > 20);
    CHECK(region.view(v).measure == complete_region.view(v).measure);
    CHECK(std::memcmp(region.points(v), complete_region.points(v), sizeof(ModelPoint) * p.n_points) == 0);
    CHECK(std::memcmp(region.depth_offsets(v, 0), complete_region.depth_offsets(v, 0),
                      sizeof(float) * p.n_points * region.n_depth_offsets()) == 0);
    // A selector hands out readable views.
    ViewSelector selector;
    const int selected = selector.select(models[1], -direction);
    CHECK(models[1].view_point_count(selected) == box_models().depth.view_point_count(selected));

    models[1].require_all_views();
    CHECK(models[1].complete());
    CHECK(same_payload(models[1], box_models().depth));
  }
  // Destroying the last copy finished the other model too, and reported both.
  std::sort(completed.begin(), completed.end());
  REQUIRE(completed.size() == 2);
  for (std::size_t r = 0; r < 2; ++r) {
    CHECK(completed[r].first == r);
    CHECK(completed[r].second == viewpoint_model_key(requests[r].kind, mesh, p));
  }
}

TEST_CASE("model cache: models made in the background are used at once, and cached when complete") {
  icgp::test::TempDir folder("background-cache");
  const ViewpointModelParams p = coarse_params();
  ModelGenerationOptions options = quiet();
  options.in_background = true;
  std::vector<CachedModelInfo> info;
  {
    const std::vector<ViewpointModel> models =
        load_or_generate(box(), {{ViewpointModel::Kind::kRegion, p}}, folder.path().string(), options, &info);
    REQUIRE(info.size() == 1);
    CHECK(info[0].generated);
    const int v = models[0].closest_view(Eigen::Vector3f::UnitX());
    models[0].require_view(v);
    CHECK(models[0].view_point_count(v) == box_models().region.view_point_count(v));
  }
  // The file was written when the generation finished (at the latest, when the model went).
  const ViewpointModel loaded = load_viewpoint_model(info[0].path);
  CHECK(same_payload(loaded, box_models().region));
  CHECK_FALSE(fs::exists(info[0].path + ".lock"));
  const std::vector<ViewpointModel> again =
      load_or_generate(box(), {{ViewpointModel::Kind::kRegion, p}}, folder.path().string(), options, &info);
  CHECK_FALSE(info[0].generated);
  CHECK(again[0].complete());
}

TEST_CASE("model cache: a model still being made in this process is shared, not waited for") {
  icgp::test::TempDir folder("shared-cache");
  const ViewpointModelParams p = coarse_params();
  ModelGenerationOptions options = quiet(1);
  options.in_background = true;
  const std::vector<ViewpointModel> first =
      load_or_generate(box(), {{ViewpointModel::Kind::kRegion, p}}, folder.path().string(), options);
  // A second tracker (or a detector) of the same object: the same model, whose views are
  // made as either needs them; the file lock this process holds is not waited on.
  std::vector<CachedModelInfo> info;
  const std::vector<ViewpointModel> second =
      load_or_generate(box(), {{ViewpointModel::Kind::kRegion, p}}, folder.path().string(), options, &info);
  CHECK(info[0].generated);
  CHECK(second[0].points(0) == first[0].points(0));  // one block of views
  const int v = second[0].closest_view(Eigen::Vector3f::UnitY());
  second[0].require_view(v);
  CHECK(first[0].view_point_count(v) == box_models().region.view_point_count(v));
  // Asked for in the foreground, the same model once it is complete.
  options.in_background = false;
  const std::vector<ViewpointModel> third =
      load_or_generate(box(), {{ViewpointModel::Kind::kRegion, p}}, folder.path().string(), options);
  CHECK(third[0].complete());
  CHECK(same_payload(third[0], box_models().region));
}

TEST_CASE("viewpoint models made in the background: a generation error reaches the reader") {
  const ViewpointModelParams p = coarse_params();
  ModelGenerationOptions options = quiet(1);
  options.in_background = true;
  request_stop();  // the generation threads stop at their first view
  ViewpointModel model;
  try {
    model = generate_viewpoint_model(ViewpointModel::Kind::kRegion, box(), p, options);
    CHECK_THROWS_AS(model.require_view(0), StopRequested);
    CHECK_THROWS_AS(model.require_all_views(), StopRequested);
    CHECK_FALSE(model.complete());
  } catch (...) {
    clear_stop_request();
    throw;
  }
  clear_stop_request();
}

TEST_CASE("viewpoint model: a view with fewer valid pixels keeps fewer points") {
  ViewpointModelParams p = coarse_params();
  p.image_size = 64;
  p.image_margin = 4;
  p.min_contour_length = 0;
  p.n_points = 500;  // more than a 64 px silhouette's outline has
  const ViewpointModel model = generate_viewpoint_model(ViewpointModel::Kind::kRegion, box(), p, quiet());
  for (int v = 0; v < model.n_views(); ++v) {
    const int count = model.view_point_count(v);
    CHECK(count > 20);
    CHECK(count < p.n_points);
    for (int q = count; q < p.n_points; ++q) CHECK(model.points(v)[q].position.isZero());
  }
}

TEST_CASE("model keys: geometry and every parameter, not the file name") {
  const Mesh mesh = box();
  const ViewpointModelParams p = coarse_params();
  const auto kind = ViewpointModel::Kind::kRegion;
  const std::uint64_t key = viewpoint_model_key(kind, mesh, p);
  Mesh renamed = mesh;
  renamed.source = "elsewhere/other.obj";
  renamed.parts[0].material.diffuse_rgb = Eigen::Vector3f(1, 0, 0);
  CHECK(viewpoint_model_key(kind, renamed, p) == key);
  Mesh moved = mesh;
  moved.parts[0].vertices[3].x() += 1e-6f;
  CHECK(viewpoint_model_key(kind, moved, p) != key);
  CHECK(viewpoint_model_key(ViewpointModel::Kind::kDepth, mesh, p) != key);
  std::vector<ViewpointModelParams> variants(10, p);
  variants[0].n_divides = 2;
  variants[1].sphere_radius = 0.7;
  variants[2].image_size = 401;
  variants[3].image_margin = 21;
  variants[4].n_points = 61;
  variants[5].stride_depth_offset = 0.003;
  variants[6].max_radius_depth_offset = 0.03;
  variants[7].min_contour_length = 16;
  variants[8].normal_chord_offset = 4;
  variants[9].seed = 8;
  for (const auto& variant : variants) CHECK(viewpoint_model_key(kind, mesh, variant) != key);
}

TEST_CASE("model cache: round trip is exact, and the default folder follows the environment") {
  icgp::test::TempDir folder("round-trip");
  const ViewpointModel& model = box_models().region;
  const std::string path = (folder.path() / "sub" / "box.icgpmodel").string();
  save_viewpoint_model(model, path);
  const ViewpointModel loaded = load_viewpoint_model(path);
  CHECK(loaded.kind() == model.kind());
  CHECK(loaded.key() == model.key());
  CHECK(loaded.params() == model.params());
  CHECK(same_payload(loaded, model));
  // 45 bytes a point (20 + one per depth offset) and 20 a view, where memory takes 8 + 4 floats.
  const std::size_t slots = static_cast<std::size_t>(model.n_views()) * model.n_points();
  CHECK(fs::file_size(path) == 112 + model.n_views() * 20 + slots * (20 + model.n_depth_offsets()));
  CHECK(model.payload_size() == model.n_views() * 20 + slots * (32 + 4 * model.n_depth_offsets()));
  CHECK_THROWS_AS(load_viewpoint_model((folder.path() / "missing.icgpmodel").string()), ModelFileError);

  CHECK(model_cache_path("/c", "my box!", ViewpointModel::Kind::kDepth, 0xabcull) ==
        "/c/my_box_-depth-0000000000000abc.icgpmodel");
  const char* saved = std::getenv("ICGP_CACHE_DIR");
  const std::string previous = saved ? saved : "";
  ::setenv("ICGP_CACHE_DIR", "/some/where", 1);
  CHECK(default_model_cache_dir() == "/some/where");
  ::unsetenv("ICGP_CACHE_DIR");
  ::setenv("XDG_CACHE_HOME", "/xdg", 1);
  CHECK(default_model_cache_dir() == "/xdg/icgp");
  ::unsetenv("XDG_CACHE_HOME");
  CHECK(default_model_cache_dir() == std::string(std::getenv("HOME")) + "/.cache/icgp");
  if (saved) ::setenv("ICGP_CACHE_DIR", previous.c_str(), 1);
}

TEST_CASE("model cache: missing, truncated, corrupted, foreign and stale files are regenerated with a reason") {
  icgp::test::TempDir folder("damaged");
  const Mesh mesh = box();
  const ViewpointModelParams p = coarse_params();
  const auto kind = ViewpointModel::Kind::kDepth;
  const std::string dir = folder.path().string();
  const ViewpointModel& truth = box_models().depth;
  const std::string path = model_cache_path(dir, "box", kind, truth.key());

  auto load = [&](const std::string& expected_reason) {
    StandardStreamCapture err(std::cerr);
    std::vector<CachedModelInfo> info;
    const std::vector<ViewpointModel> m = load_or_generate(mesh, {{kind, p}}, dir, quiet(), &info);
    const std::string said = err.text();
    INFO("stderr: " << said);
    CHECK(same_payload(m[0], truth));
    CHECK(info[0].path == path);
    if (expected_reason.empty()) {
      CHECK(said.empty());
      CHECK(!info[0].generated);
    } else {
      CHECK_THAT(said, Catch::Contains(expected_reason) && Catch::Contains(path));
      CHECK(std::count(said.begin(), said.end(), '\n') == 1);
      CHECK(info[0].generated);
      CHECK(info[0].saved);
    }
  };
  auto rewrite = [&](const std::function<void(std::string&)>& change) {
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    change(bytes);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  };

  load("not found");
  load("");  // the saved file is used as it is
  rewrite([](std::string& b) { b.resize(b.size() / 2); });
  load("truncated");
  rewrite([](std::string& b) { b.resize(50); });
  load("truncated");
  rewrite([](std::string& b) { b[b.size() / 3] ^= 0x10; });
  load("corrupted");
  rewrite([](std::string& b) { b[30] ^= 0x01; });  // a parameter in the header
  load("corrupted");
  rewrite([](std::string& b) { b = "this is not a model file, just some text that is long enough to matter"; });
  load("not an icgp model file");
  // A model of another geometry under this name: intact, but stale.
  save_viewpoint_model(generate_viewpoint_model(kind, test::make_box(0.1f, 0.06f, 0.05f), p, quiet()), path);
  load("stale");
  load("");
}

TEST_CASE("model cache: an unwritable folder still gives the model, with a warning") {
  icgp::test::TempDir folder("unwritable");
  const fs::path file = folder.path() / "a-file";
  std::ofstream(file) << "not a folder";
  StandardStreamCapture err(std::cerr);
  std::vector<CachedModelInfo> info;
  const std::vector<ViewpointModel> m = load_or_generate(box(), {{ViewpointModel::Kind::kRegion, coarse_params()}},
                                                         (file / "cache").string(), quiet(), &info);
  CHECK(same_payload(m[0], box_models().region));
  CHECK(info[0].generated);
  CHECK(!info[0].saved);
  CHECK_THAT(err.text(), Catch::Contains("warning"));
}

TEST_CASE("model cache: a file with an intact checksum but values no generator makes is refused") {
  icgp::test::TempDir folder("contents");
  // A model as the generator's first constructor makes it (every array zero), filled by hand:
  // save_viewpoint_model writes it with a valid checksum, so only the contents are wrong.
  ViewpointModelParams params = coarse_params();
  params.n_divides = 0;
  const auto model_with = [&](const std::function<void(ViewpointModel&)>& fill) {
    ViewpointModel model(ViewpointModel::Kind::kDepth, params, 42);
    for (int v = 0; v < model.n_views(); ++v) {
      model.mutable_views()[v].direction = Eigen::Vector3f::UnitZ();
      model.mutable_counts()[v] = 1;
      model.mutable_points()[v * model.n_points()].normal = Eigen::Vector3f::UnitZ();
    }
    fill(model);
    const std::string path = (folder.path() / "model.icgpmodel").string();
    save_viewpoint_model(model, path);
    return path;
  };
  CHECK_NOTHROW(load_viewpoint_model(model_with([](ViewpointModel&) {})));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  CHECK_THROWS_WITH(load_viewpoint_model(model_with([&](ViewpointModel& m) { m.mutable_points()[0].position.x() = nan; })),
                    Catch::Contains("is corrupted (view 0: point 0 has a value that is not finite or negative)"));
  CHECK_THROWS_WITH(load_viewpoint_model(model_with([&](ViewpointModel& m) { m.mutable_views()[3].direction *= 2.f; })),
                    Catch::Contains("is corrupted (view 3: its direction is not a unit vector)"));
  CHECK_THROWS_WITH(load_viewpoint_model(model_with([&](ViewpointModel& m) { m.mutable_counts()[5] = -1; })),
                    Catch::Contains("is corrupted (view 5: point count -1 out of range)"));
  CHECK_THROWS_WITH(
      load_viewpoint_model(model_with([&](ViewpointModel& m) { m.mutable_points()[0].foreground_distance = -1.f; })),
      Catch::Contains("is corrupted (view 0: point 0 has a value that is not finite or negative)"));
  // Depth offsets are stored as codes of non-negative values: none can be out of range.
}

TEST_CASE("model cache: a folder where a file belongs is named as such, when saving and loading") {
  icgp::test::TempDir folder("directory");
  const std::string path = (folder.path() / "a-folder.icgpmodel").string();
  fs::create_directories(path);
  CHECK_THROWS_WITH(save_viewpoint_model(box_models().region, path),
                    Catch::Contains(path) && Catch::Contains("cannot be written: it is a directory"));
  CHECK_THROWS_WITH(load_viewpoint_model(path), Catch::Contains(path) && Catch::Contains("is not a regular file"));
}

TEST_CASE("viewpoint model: parameters that would make a model beyond the resource bounds are refused") {
  ViewpointModelParams p;
  p.image_size = 100000;
  CHECK_THROWS_WITH(p.validate(), Catch::Contains("image_size must be from 16 to 8192 px (got 100000)"));
  p = ViewpointModelParams();
  p.n_points = 2000000000;
  CHECK_THROWS_WITH(p.validate(), Catch::Contains("n_points must be from 1 to 5000"));
  p = ViewpointModelParams();
  p.n_divides = 6;
  p.n_points = 5000;  // 40962 views x 5000 points x (32 + 25 x 4) bytes
  CHECK_THROWS_WITH(p.validate(), Catch::Contains("make a model of 25783 MiB (expected at most 4096 MiB)"));
}
