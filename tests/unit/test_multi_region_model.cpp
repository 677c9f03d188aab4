// SPDX-License-Identifier: GPL-2.0-or-later
// Multi-region region models (ALGORITHMS.md §6) against independent truth: the two-region
// box of models/two_region, whose geometry is known exactly (box 0.10 x 0.08 x 0.06 m, lid
// above y = 0.015, body below), checked with an analytic ray caster, not the renderer.
// Coarse models (42 views, 400 px, 60 points) keep this fast on llvmpipe.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cstring>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "icgp/io/mesh_loader.h"
#include "icgp/model/model_key.h"
#include "icgp/model/viewpoint_model_generator.h"
#include "test_meshes.h"

using namespace icgp;

namespace {

constexpr double kBoundaryY = 0.015;
const Eigen::Vector3d kHalf(0.05, 0.04, 0.03);
constexpr float kInfinity = std::numeric_limits<float>::infinity();

std::string model(const std::string& name) { return std::string(ICGP_MODELS_DIR) + "/" + name; }
const Mesh& lid() {
  static const Mesh mesh = load_mesh(model("two_region/region_lid.obj"));
  return mesh;
}
const Mesh& body() {
  static const Mesh mesh = load_mesh(model("two_region/region_body.obj"));
  return mesh;
}

ViewpointModelParams coarse_params() {
  ViewpointModelParams p;
  p.n_divides = 1;
  p.image_size = 400;
  p.n_points = 60;
  p.max_radius_depth_offset = 0.02;
  return p;
}

ModelGenerationOptions with(std::vector<AssociatedBody> bodies) {
  ModelGenerationOptions o;
  o.print_progress = false;
  o.associated_bodies = std::move(bodies);
  return o;
}

AssociatedBody associated(const Mesh& mesh, AssociatedBody::Kind kind, bool same_region_fixed = true,
                          const Eigen::Vector3d& offset = Eigen::Vector3d::Zero()) {
  AssociatedBody b;
  b.mesh = mesh;
  b.main_T_body = Pose(Eigen::Matrix3d::Identity(), offset);
  b.kind = kind;
  b.same_region_fixed = same_region_fixed;
  return b;
}

ViewpointModel region_model(const Mesh& main, std::vector<AssociatedBody> bodies) {
  return generate_viewpoint_model(ViewpointModel::Kind::kRegion, main, coarse_params(), with(std::move(bodies)));
}

// ---- analytic scene: axis-aligned boxes, each pixel labelled by its first hit -------------

enum Label { kNothing = 0, kLid = 1, kBody = 2, kExtra = 3 };

struct SceneBox {
  Eigen::Vector3d min, max;
  bool two_region;  ///< the two-region box: lid above kBoundaryY, body below; else kExtra
};

struct Hit {
  Label label = kNothing;
  double depth = 0.0;  ///< camera Z
};

struct Scene {
  std::vector<SceneBox> boxes{{-kHalf, kHalf, true}};
  ViewCamera camera;
  Eigen::Vector3d eye;  ///< camera centre, body frame
  Eigen::Matrix3d body_R_camera;

  explicit Scene(const ViewCamera& c) : camera(c) {
    const Pose body_T_camera = c.camera_T_body.inverse();
    eye = body_T_camera.translation();
    body_R_camera = body_T_camera.rotation();
  }

  Hit at(const Eigen::Vector2d& x) const {
    const Eigen::Vector3d ray = body_R_camera * camera.intrinsics.back_project<double>(x.x(), x.y(), 1.0);
    Hit best;
    double best_t = std::numeric_limits<double>::infinity();
    for (const SceneBox& b : boxes) {
      double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
      for (int a = 0; a < 3; ++a) {
        const double u = (b.min[a] - eye[a]) / ray[a], w = (b.max[a] - eye[a]) / ray[a];
        t0 = std::max(t0, std::min(u, w));
        t1 = std::min(t1, std::max(u, w));
      }
      if (t0 > t1 || t0 >= best_t) continue;
      best_t = t0;  // ray = direction with camera z = 1, so t is the camera depth
      best.depth = t0;
      best.label = !b.two_region ? kExtra : (eye + t0 * ray).y() > kBoundaryY ? kLid : kBody;
    }
    return best;
  }

  /// Pixels (in 1/8 px steps) from x along n until `keep` stops holding, looking from one
  /// pixel on (the contour point may lie up to half a pixel off the true edge); +inf past
  /// the image.
  template <typename Keep>
  double run(const Eigen::Vector2d& x, const Eigen::Vector2d& n, Keep keep) const {
    for (double s = 1.0;; s += 0.125) {
      const Eigen::Vector2d y = x + s * n;
      if (y.x() < -0.5 || y.y() < -0.5 || y.x() > camera.intrinsics.width - 0.5 ||
          y.y() > camera.intrinsics.height - 0.5)
        return std::numeric_limits<double>::infinity();
      if (!keep(at(y).label)) return s;
    }
  }
};

/// Image distance from x to the lid/body boundary: the rectangle y = kBoundaryY around the box.
double boundary_distance(const ViewCamera& camera, const Eigen::Vector2d& x) {
  const double cx[4] = {-kHalf.x(), kHalf.x(), kHalf.x(), -kHalf.x()};
  const double cz[4] = {-kHalf.z(), -kHalf.z(), kHalf.z(), kHalf.z()};
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector2d a =
        camera.intrinsics.project<double>(camera.camera_T_body * Eigen::Vector3d(cx[i], kBoundaryY, cz[i]));
    const Eigen::Vector2d b = camera.intrinsics.project<double>(
        camera.camera_T_body * Eigen::Vector3d(cx[(i + 1) % 4], kBoundaryY, cz[(i + 1) % 4]));
    const double t = std::clamp((x - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + t * (b - a) - x).norm());
  }
  return best;
}

struct ImagePoint {
  Eigen::Vector2d x, n;  ///< projected point, unit image normal
  double depth;          ///< camera Z
  double px_per_metre;   ///< at that depth
};

ImagePoint image_point(const ViewCamera& camera, const ModelPoint& p) {
  const Eigen::Vector3d X = camera.camera_T_body * p.position.cast<double>();
  const Eigen::Vector2d x = camera.intrinsics.project<double>(X);
  const Eigen::Vector2d y =
      camera.intrinsics.project<double>(camera.camera_T_body * (p.position + 1e-3f * p.normal).cast<double>());
  return {x, (y - x).normalized(), X.z(), camera.intrinsics.fu / X.z()};
}

double outline_distance(const std::vector<cv::Point2f>& hull, const Eigen::Vector2d& x) {
  return std::abs(cv::pointPolygonTest(hull, cv::Point2f(static_cast<float>(x.x()), static_cast<float>(x.y())), true));
}

struct Counts {
  int points = 0, on_outline = 0, on_boundary = 0;
  int foreground_off = 0;  ///< foreground distances more than 2.5 px off the truth
};

/// Foreground distances (px) agree with the truth walk to 2.5 px, except near corners where
/// the pixel-stepped walk and the exact ray can exit through different edges (counted: at
/// most 1 % of the points may be such).
void check_foreground(double model_px, double truth_px, Counts& counts) {
  if (std::abs(model_px - truth_px) > 2.5) ++counts.foreground_off;
}

/// Checks a region model of one region of the two-region box (main = kLid or kBody) with the
/// other region associated: every point on the main region, on the box's outline or on the
/// shared boundary (only there where the other region lies beyond it, not in front), with
/// foreground distances equal to an analytic walk (across the other region too when it is a
/// fixed same-region body) and infinite background distances (both regions are convex).
Counts check_two_region_model(const ViewpointModel& m, Label main, bool other_is_same_region_fixed,
                              bool expect_boundary_points) {
  const Label other = main == kLid ? kBody : kLid;
  Counts counts;
  for (int v = 0; v < m.n_views(); ++v) {
    const ViewCamera camera = view_camera(m.view(v).direction, m.params(), main == kLid ? lid().radius_about_origin()
                                                                                         : body().radius_about_origin());
    const Scene scene(camera);
    const std::vector<cv::Point2f> hull = test::projected_box_outline(camera.intrinsics, camera.camera_T_body, kHalf);
    for (int p = 0; p < m.view_point_count(v); ++p) {
      const ModelPoint& point = m.points(v)[p];
      const ImagePoint ip = image_point(camera, point);
      const double metres_per_px = 1.0 / ip.px_per_metre;
      ++counts.points;
      INFO("view " << v << " point " << p << " at " << point.position.transpose() << " normal "
                   << point.normal.transpose());
      // On the main region's surface.
      const Eigen::Vector3d X = point.position.cast<double>();
      CHECK(std::abs((X.cwiseAbs() - kHalf).maxCoeff()) < 1.5 * metres_per_px);
      if (main == kLid) CHECK(X.y() > kBoundaryY - 1.5 * metres_per_px);
      if (main == kBody) CHECK(X.y() < kBoundaryY + 1.5 * metres_per_px);
      // Just inside the contour the main region is what the camera sees (nothing covers it);
      // just outside, it is not.
      const Hit inside = scene.at(ip.x - 1.0 * ip.n), outside = scene.at(ip.x + 1.0 * ip.n);
      CHECK(inside.label == main);
      CHECK(outside.label != main);
      const bool on_outline = outline_distance(hull, ip.x) < 1.2;
      const bool on_boundary = boundary_distance(camera, ip.x) < 1.2;
      CHECK((on_outline || on_boundary));
      counts.on_outline += on_outline;
      if (on_boundary && !on_outline) {
        ++counts.on_boundary;
        // The other region lies beyond the contour, and not in front of the main one.
        CHECK(outside.label == other);
        CHECK(outside.depth > inside.depth - 10.0 * metres_per_px);
        // Foreground distance: across the main region only, up to its far side.
        const double fg = scene.run(ip.x, -ip.n, [&](int label) { return label == main; });
        check_foreground(point.foreground_distance * ip.px_per_metre, fg, counts);
        // Background distance: crosses the other region into the background, and never
        // meets the main region again (both regions are convex).
        const double across_other = scene.run(ip.x, ip.n, [&](int label) { return label == other; });
        CHECK(across_other > 1.0);
        CHECK(point.background_distance == kInfinity);
      } else {
        // On the outline: the foreground walk crosses the main region and, when fixed and of
        // the same region, the other one.
        const double fg = scene.run(ip.x, -ip.n, [&](int label) {
          return label == main || (other_is_same_region_fixed && label == other);
        });
        check_foreground(point.foreground_distance * ip.px_per_metre, fg, counts);
        CHECK(point.background_distance == kInfinity);
      }
    }
  }
  CHECK(counts.foreground_off <= counts.points / 100);
  if (expect_boundary_points)
    CHECK(counts.on_boundary > counts.points / 10);
  else
    CHECK(counts.on_boundary == 0);
  return counts;
}

std::uint64_t payload_hash(const ViewpointModel& m) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (std::size_t i = 0; i < m.payload_size(); ++i) h = (h ^ m.payload()[i]) * 0x100000001b3ull;
  return h;
}

}  // namespace

TEST_CASE("multi-region: lid with the body as fixed neighbour, contour on the lid's outline and shared boundary") {
  const ViewpointModel m = region_model(lid(), {associated(body(), AssociatedBody::Kind::kFixed)});
  REQUIRE(m.n_views() == 42);
  const Counts c = check_two_region_model(m, kLid, false, true);
  CHECK(c.points > 42 * 50);
  CHECK(c.on_outline > c.points / 4);
}

TEST_CASE("multi-region: body with the lid as fixed neighbour, contour on the body's outline and shared boundary") {
  const ViewpointModel m = region_model(body(), {associated(lid(), AssociatedBody::Kind::kFixed)});
  const Counts c = check_two_region_model(m, kBody, false, true);
  CHECK(c.points > 42 * 50);
}

TEST_CASE("multi-region: a same-region neighbour gives no points on the shared boundary, fixed it lets walks cross") {
  SECTION("fixed same-region: foreground walks cross into the body") {
    const ViewpointModel m = region_model(lid(), {associated(body(), AssociatedBody::Kind::kSameRegion, true)});
    check_two_region_model(m, kLid, true, false);
  }
  SECTION("movable same-region: foreground walks stop at the body") {
    const ViewpointModel m = region_model(lid(), {associated(body(), AssociatedBody::Kind::kSameRegion, false)});
    check_two_region_model(m, kLid, false, false);
  }
  SECTION("movable (other region), flush with the lid: the shared boundary is covered, no points") {
    const ViewpointModel m = region_model(lid(), {associated(body(), AssociatedBody::Kind::kMovable)});
    check_two_region_model(m, kLid, false, false);
  }
}

TEST_CASE("multi-region: background walks stop at a same-region body, not at a fixed one") {
  // A copy of the lid 0.12 m along +x: from +z, a gap right of the lid.
  for (const auto kind : {AssociatedBody::Kind::kSameRegion, AssociatedBody::Kind::kFixed}) {
    const ViewpointModel m =
        region_model(lid(), {associated(lid(), kind, true, Eigen::Vector3d(0.12, 0.0, 0.0))});
    const int v = m.closest_view(Eigen::Vector3f::UnitZ());
    REQUIRE(m.view(v).direction.dot(Eigen::Vector3f::UnitZ()) == Approx(1.f));
    const ViewCamera camera = view_camera(m.view(v).direction, m.params(), lid().radius_about_origin());
    const double metres_per_px = (m.params().sphere_radius - kHalf.z()) / camera.intrinsics.fu;
    int right = 0;
    for (int p = 0; p < m.view_point_count(v); ++p) {
      const ModelPoint& point = m.points(v)[p];
      if (point.normal.x() < 0.99f || std::abs(point.position.y() - 0.0275f) > 0.008f) continue;  // right edge
      ++right;
      CHECK(point.position.x() == Approx(0.05).margin(metres_per_px));
      // The gap in the image: from the lid's front edge (x = 0.05, z = 0.03) to the copy's
      // nearer side face, seen up to its back edge (x = 0.07, z = -0.03), at the point's depth.
      const double R = m.params().sphere_radius;
      const double gap = (0.07 / (R + kHalf.z()) - 0.05 / (R - kHalf.z())) * (R - kHalf.z());
      if (kind == AssociatedBody::Kind::kSameRegion)
        CHECK(point.background_distance == Approx(gap).margin(2.5 * metres_per_px));
      else
        CHECK(point.background_distance == kInfinity);
    }
    CHECK(right >= 2);
  }
}

TEST_CASE("multi-region: a movable body in front of the lid removes the contour it makes, behind it removes none") {
  // From +z the lid's front face spans x in [-0.05, 0.05], y in [0.015, 0.04] at z = 0.03.
  const Mesh small = test::make_box(0.02f, 0.015f, 0.01f);
  const Eigen::Vector3d in_front(0.0, 0.0275, 0.06);  // hides a 0.02 x 0.015 patch of that face
  // The body closes the lid's open bottom (the camera on +z looks up into it otherwise).
  for (const auto kind : {AssociatedBody::Kind::kMovable, AssociatedBody::Kind::kFixed}) {
    const ViewpointModel m = region_model(
        lid(), {associated(body(), AssociatedBody::Kind::kFixed), associated(small, kind, true, in_front)});
    const int v = m.closest_view(Eigen::Vector3f::UnitZ());
    REQUIRE(m.view(v).direction.dot(Eigen::Vector3f::UnitZ()) == Approx(1.f));
    const ViewCamera camera = view_camera(m.view(v).direction, m.params(), lid().radius_about_origin());
    Scene scene(camera);
    scene.boxes.push_back({in_front - Eigen::Vector3d(0.01, 0.0075, 0.005), in_front + Eigen::Vector3d(0.01, 0.0075, 0.005),
                           false});
    REQUIRE(m.view_point_count(v) == m.n_points());
    for (int p = 0; p < m.view_point_count(v); ++p) {
      const ImagePoint ip = image_point(camera, m.points(v)[p]);
      // Every point is on the front face's outline (top face edge-on), none around the patch.
      CHECK(std::abs(m.points(v)[p].position.z() - kHalf.z()) < 1e-4);
      const double from_patch_x = std::abs(m.points(v)[p].position.x()) - 0.01;
      const double from_patch_y = std::abs(m.points(v)[p].position.y() - 0.0275) - 0.0075;
      CHECK(std::max(from_patch_x, from_patch_y) > 0.002);
      CHECK(scene.at(ip.x - ip.n).label == kLid);
    }
  }
  // A movable plate behind the whole lid: the lid's edges are in front of it, all kept.
  const Mesh plate = test::make_box(0.2f, 0.2f, 0.01f);
  const ViewpointModel behind =
      region_model(lid(), {associated(plate, AssociatedBody::Kind::kMovable, true, Eigen::Vector3d(0, 0, -0.05))});
  const ViewpointModel alone = generate_viewpoint_model(ViewpointModel::Kind::kRegion, lid(), coarse_params(),
                                                        with({}));
  const int v = behind.closest_view(Eigen::Vector3f::UnitZ());
  CHECK(behind.view_point_count(v) == behind.n_points());
  CHECK(behind.view(v).measure == Approx(alone.view(v).measure).epsilon(1e-6));
}

TEST_CASE("multi-region: associated bodies enter region keys (geometry, pose, kind), single-body keys unchanged") {
  const ViewpointModelParams p = coarse_params();
  const auto region = ViewpointModel::Kind::kRegion, depth = ViewpointModel::Kind::kDepth;
  const std::uint64_t single = viewpoint_model_key(region, lid(), p);
  CHECK(viewpoint_model_key(region, lid(), p, {}) == single);
  const AssociatedBody base = associated(body(), AssociatedBody::Kind::kFixed);
  const std::uint64_t with_body = viewpoint_model_key(region, lid(), p, {base});
  CHECK(with_body != single);
  CHECK(viewpoint_model_key(region, lid(), p, {base}) == with_body);
  std::vector<AssociatedBody> variants(5, base);
  variants[0].kind = AssociatedBody::Kind::kSameRegion;
  variants[1].kind = AssociatedBody::Kind::kMovable;
  variants[2].same_region_fixed = false;
  variants[3].main_T_body = Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 1e-6));
  variants[4].mesh.parts[0].vertices[2].y() += 1e-6f;
  for (const auto& variant : variants) CHECK(viewpoint_model_key(region, lid(), p, {variant}) != with_body);
  CHECK(viewpoint_model_key(region, lid(), p, {base, base}) != with_body);
  // Depth models do not see associated bodies.
  CHECK(viewpoint_model_key(depth, lid(), p, {base}) == viewpoint_model_key(depth, lid(), p));
  const std::vector<ViewpointModel> models =
      generate_viewpoint_models(lid(), {{region, p}, {depth, p}}, with({base}));
  CHECK(models[0].key() == with_body);
  CHECK(models[1].key() == viewpoint_model_key(depth, lid(), p));
  const ViewpointModel depth_alone = generate_viewpoint_model(depth, lid(), p, with({}));
  CHECK(payload_hash(models[1]) == payload_hash(depth_alone));
}

TEST_CASE("multi-region: without associated bodies, keys and models are those of the code before multi-region") {
  // Golden values of the generator as it was before associated bodies existed, carried over
  // to model version 2 (keys include the version; payloads rounded to the cache file's
  // precision, stored_model.h), which changed nothing else of the generation.
  const Mesh box = test::make_box(0.10f, 0.06f, 0.04f);
  const ViewpointModelParams p = coarse_params();
  const std::vector<ViewpointModel> models = generate_viewpoint_models(
      box, {{ViewpointModel::Kind::kRegion, p}, {ViewpointModel::Kind::kDepth, p}}, with({}));
  CHECK(models[0].key() == 0x5f31fcf58fd4ac83ull);
  CHECK(models[1].key() == 0x6b88aec343c9babcull);
  CHECK(payload_hash(models[0]) == 0xb07fbf9ee534f619ull);
  CHECK(payload_hash(models[1]) == 0x7d7c02bd20236a1full);
  const ViewpointModel lid_model = generate_viewpoint_model(ViewpointModel::Kind::kRegion, lid(), p, with({}));
  CHECK(lid_model.key() == 0xe81e0e848dfa0108ull);
  CHECK(payload_hash(lid_model) == 0xedc44d550f12bee6ull);
}
