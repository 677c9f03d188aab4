// SPDX-License-Identifier: GPL-2.0-or-later
// The headless renderer against analytic truth: ray-box intersections, projected vertices,
// silhouette areas, face normals, texture orientation.
#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "icgp/render/renderer.h"
#include "test_meshes.h"

using namespace icgp;

namespace {

Intrinsics vga() {
  Intrinsics k;
  k.fu = 520.0;
  k.fv = 515.0;
  k.pu = 318.3;
  k.pv = 242.7;
  k.width = 640;
  k.height = 480;
  return k;
}

// A box pose with all three rotation angles non-zero so no edge is axis-aligned.
Pose box_pose() {
  return Pose::from_rotation_vector(Eigen::Vector3d(0.4, -0.7, 0.25), Eigen::Vector3d(0.012, -0.018, 0.45));
}

/// Z of the first intersection of the ray through pixel (u, v) with the axis-aligned box
/// of half-sizes h at camera_T_box, or 0 when it misses (slab method in the box frame).
double ray_box_depth(const Intrinsics& k, double u, double v, const Pose& camera_T_box, const Eigen::Vector3d& h) {
  const Pose box_T_camera = camera_T_box.inverse();
  const Eigen::Vector3d dir_cam((u - k.pu) / k.fu, (v - k.pv) / k.fv, 1.0);  // Z component 1: t == Z
  const Eigen::Vector3d o = box_T_camera.translation();
  const Eigen::Vector3d d = box_T_camera.rotation() * dir_cam;
  double t_near = -1e9, t_far = 1e9;
  for (int a = 0; a < 3; ++a) {
    const double t1 = (-h[a] - o[a]) / d[a], t2 = (h[a] - o[a]) / d[a];
    t_near = std::max(t_near, std::min(t1, t2));
    t_far = std::min(t_far, std::max(t1, t2));
  }
  return (t_near <= t_far && t_near > 0) ? t_near : 0.0;
}

double polygon_area(const std::vector<cv::Point2f>& hull) { return std::abs(cv::contourArea(hull)); }

}  // namespace

TEST_CASE("renderer: box depth equals the ray-plane intersection within 0.1 mm") {
  Renderer renderer;
  const Eigen::Vector3d half(0.04, 0.03, 0.08);
  const auto body = renderer.add_body(test::make_box(0.08f, 0.06f, 0.16f), 1);
  renderer.set_body_pose(body, box_pose());
  const Intrinsics k = vga();
  const RenderOutput out = renderer.render(k, Pose(), kRenderDepth | kRenderIds);

  int both = 0, only_render = 0, only_truth = 0;
  double max_error = 0.0;
  for (int i = 0; i < k.height; ++i)
    for (int j = 0; j < k.width; ++j) {
      const double truth = ray_box_depth(k, j, i, box_pose(), half);
      const float rendered = out.depth.at<float>(i, j);
      const bool hit = out.ids.at<uchar>(i, j) == 1;
      REQUIRE(hit == (rendered > 0.f));
      if (truth > 0 && hit) {
        ++both;
        max_error = std::max(max_error, std::abs(truth - rendered));
      } else if (hit) {
        ++only_render;
      } else if (truth > 0) {
        ++only_truth;
      }
    }
  INFO("pixels on the box " << both << ", rendered only " << only_render << ", analytic only " << only_truth);
  CHECK(both > 10000);
  CHECK(max_error < 1e-4);
  // Sampling at pixel centres is exact: disagreement only where a centre lies on an edge.
  CHECK(only_render + only_truth <= 4);
}

TEST_CASE("renderer: silhouette area matches the projected convex hull within 1 %") {
  Renderer renderer;
  const auto body = renderer.add_body(test::make_box(0.08f, 0.06f, 0.16f), 7);
  const Intrinsics k = vga();
  for (const Pose& pose : {box_pose(), Pose::from_rotation_vector(Eigen::Vector3d(-1.1, 0.2, 0.9),
                                                                  Eigen::Vector3d(-0.05, 0.03, 0.7))}) {
    renderer.set_body_pose(body, pose);
    const RenderOutput out = renderer.render(k, Pose(), kRenderIds);
    const std::vector<cv::Point2f> hull = test::projected_box_outline(k, pose, Eigen::Vector3d(0.04, 0.03, 0.08));
    const double rendered_area = cv::countNonZero(out.ids == 7);
    CHECK(rendered_area == Approx(polygon_area(hull)).epsilon(0.01));
  }
}

TEST_CASE("renderer: triangle vertices land within 0.5 px of their projection") {
  // Fit each edge line to the row-wise coverage transitions (sub-pixel by least squares),
  // intersect neighbouring edges and compare with Intrinsics::project of the vertices.
  const Intrinsics k = vga();
  const Eigen::Vector3f a(-0.11f, -0.07f, 0.62f), b(0.13f, -0.02f, 0.55f), c(-0.02f, 0.12f, 0.5f);
  Renderer renderer;
  renderer.add_body(test::make_triangle(a, b, c), 1);
  const cv::Mat ids = renderer.render(k, Pose(), kRenderIds).ids;
  const std::array<Eigen::Vector2d, 3> p = {k.project<double>(a.cast<double>()), k.project<double>(b.cast<double>()),
                                            k.project<double>(c.cast<double>())};

  // Line u = s v + o of edge (p[e], p[e+1]) from transitions in rows away from its ends.
  auto fit_edge = [&](int e) {
    const Eigen::Vector2d p0 = p[e], p1 = p[(e + 1) % 3], other = p[(e + 2) % 3];
    const int v_lo = static_cast<int>(std::ceil(std::min(p0.y(), p1.y()))) + 3;
    const int v_hi = static_cast<int>(std::floor(std::max(p0.y(), p1.y()))) - 3;
    const double s_true = (p1.x() - p0.x()) / (p1.y() - p0.y());
    Eigen::Matrix2d AtA = Eigen::Matrix2d::Zero();
    Eigen::Vector2d Atb = Eigen::Vector2d::Zero();
    for (int v = v_lo; v <= v_hi; ++v) {
      // The edge bounds the span on the left when the third vertex lies right of its line.
      const bool left_boundary = other.x() > p0.x() + s_true * (other.y() - p0.y());
      const cv::Mat row = ids.row(v);
      int first = -1, last = -1;
      for (int u = 0; u < k.width; ++u)
        if (row.at<uchar>(u)) {
          if (first < 0) first = u;
          last = u;
        }
      REQUIRE(first >= 0);
      const double transition = left_boundary ? first - 0.5 : last + 0.5;
      const Eigen::Vector2d r(v, 1.0);
      AtA += r * r.transpose();
      Atb += r * transition;
    }
    return Eigen::Vector2d(AtA.ldlt().solve(Atb));  // (s, o)
  };
  std::array<Eigen::Vector2d, 3> lines = {fit_edge(0), fit_edge(1), fit_edge(2)};
  for (int vtx = 0; vtx < 3; ++vtx) {
    // Vertex vtx joins edge vtx-1 and edge vtx.
    const Eigen::Vector2d l0 = lines[(vtx + 2) % 3], l1 = lines[vtx];
    const double v = (l1.y() - l0.y()) / (l0.x() - l1.x());
    const Eigen::Vector2d rendered(l0.x() * v + l0.y(), v);
    INFO("vertex " << vtx << " projected " << p[vtx].transpose() << " rendered " << rendered.transpose());
    CHECK((rendered - p[vtx]).norm() < 0.5);
  }
}

TEST_CASE("renderer: normals are the camera-facing face normals") {
  Renderer renderer;
  const auto body = renderer.add_body(test::make_box(0.08f, 0.06f, 0.16f), 1);
  renderer.set_body_pose(body, box_pose());
  const Intrinsics k = vga();
  const RenderOutput out = renderer.render(k, Pose(), kRenderNormals | kRenderDepth);
  const Eigen::Matrix3d R = box_pose().rotation();
  int checked = 0;
  for (int i = 2; i < k.height - 2; i += 3)
    for (int j = 2; j < k.width - 2; j += 3) {
      if (out.depth.at<float>(i, j) <= 0.f) continue;
      const cv::Vec3f n = out.normals.at<cv::Vec3f>(i, j);
      const Eigen::Vector3d rendered(n[0], n[1], n[2]);
      // The normal must be one of the box's six face normals and face the camera.
      double best = 0.0;
      for (int a = 0; a < 3; ++a)
        for (double sign : {-1.0, 1.0}) best = std::max(best, rendered.dot(sign * R.col(a)));
      CHECK(best > 1.0 - 1e-5);
      const Eigen::Vector3d X = k.back_project<double>(j, i, out.depth.at<float>(i, j));
      CHECK(rendered.dot(X) < 0.0);
      ++checked;
    }
  CHECK(checked > 1000);
}

TEST_CASE("renderer: ids and depth resolve occlusion between bodies") {
  Renderer renderer;
  const auto far_box = renderer.add_body(test::make_box(0.2f, 0.2f, 0.01f), 3);
  const auto near_box = renderer.add_body(test::make_box(0.05f, 0.05f, 0.05f), 9);
  renderer.set_body_pose(far_box, Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 0.8)));
  renderer.set_body_pose(near_box, Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 0.5)));
  Intrinsics k = vga();
  k.pu = 319.5;
  k.pv = 239.5;
  const RenderOutput out = renderer.render(k, Pose(), kRenderIds | kRenderDepth);
  CHECK(out.ids.at<uchar>(240, 320) == 9);
  CHECK(out.depth.at<float>(240, 320) == Approx(0.475).margin(1e-5));
  CHECK(out.ids.at<uchar>(240, 320 + 50) == 3);  // beside the small box (27 px half-width), on the plate (65 px)
  CHECK(out.depth.at<float>(240, 320 + 50) == Approx(0.795).margin(1e-5));
  CHECK(out.ids.at<uchar>(10, 10) == 0);
  CHECK(out.depth.at<float>(10, 10) == 0.f);

  renderer.set_body_visible(near_box, false);
  CHECK(renderer.render(k, Pose(), kRenderIds).ids.at<uchar>(240, 320) == 3);
}

TEST_CASE("renderer: a focused render is the same image as the crop of the full render") {
  Renderer renderer;
  const auto body = renderer.add_body(test::make_box(0.08f, 0.06f, 0.16f), 1);
  renderer.set_body_pose(body, box_pose());
  const Intrinsics k = vga();
  const RenderOutput full = renderer.render(k, Pose(), kRenderIds | kRenderDepth);
  Intrinsics crop_k;
  const RenderOutput crop = renderer.render_focused(k, Pose(), 250, 170, 200, 200, kRenderIds | kRenderDepth, &crop_k);
  REQUIRE(crop.ids.size() == cv::Size(200, 200));
  CHECK(cv::countNonZero(crop.ids != full.ids(cv::Rect(250, 170, 200, 200))) <= 2);
  cv::Mat difference;
  cv::absdiff(crop.depth, full.depth(cv::Rect(250, 170, 200, 200)), difference);
  difference.setTo(0, crop.ids != full.ids(cv::Rect(250, 170, 200, 200)));
  double max_difference = 0;
  cv::minMaxLoc(difference, nullptr, &max_difference);
  CHECK(max_difference < 1e-5);

  // Half resolution: output pixel (j, i) covers full-resolution pixels 2j..2j+1, so its
  // centre is at full-image u = 250 + 2j + 0.5; depth must match the analytic ray there.
  const RenderOutput half = renderer.render_focused(k, Pose(), 250, 170, 200, 100, kRenderDepth, &crop_k);
  const Eigen::Vector3d h(0.04, 0.03, 0.08);
  int checked = 0;
  for (int i = 0; i < 100; i += 7)
    for (int j = 0; j < 100; j += 7) {
      const double truth = ray_box_depth(k, 250 + 2 * j + 0.5, 170 + 2 * i + 0.5, box_pose(), h);
      const float rendered = half.depth.at<float>(i, j);
      if (truth > 0 && rendered > 0) {
        CHECK(rendered == Approx(truth).margin(1e-4));
        ++checked;
      }
    }
  CHECK(checked > 30);
}

TEST_CASE("renderer: textures appear upright with unshaded colours on a fronto-parallel quad") {
  // A 2x2 texture: top-left red, top-right green, bottom-left blue, bottom-right white.
  cv::Mat texture(2, 2, CV_8UC3);
  texture.at<cv::Vec3b>(0, 0) = {0, 0, 255};
  texture.at<cv::Vec3b>(0, 1) = {0, 255, 0};
  texture.at<cv::Vec3b>(1, 0) = {255, 0, 0};
  texture.at<cv::Vec3b>(1, 1) = {255, 255, 255};
  cv::resize(texture, texture, cv::Size(64, 64), 0, 0, cv::INTER_NEAREST);
  MeshPart part;
  // Camera y points down: the quad's top edge (image top) has y = -0.1 and texture v = 1.
  part.vertices = {{-0.1f, -0.1f, 0.f}, {0.1f, -0.1f, 0.f}, {0.1f, 0.1f, 0.f}, {-0.1f, 0.1f, 0.f}};
  part.texcoords = {{0.f, 1.f}, {1.f, 1.f}, {1.f, 0.f}, {0.f, 0.f}};
  part.triangles = {{0, 1, 2}, {0, 2, 3}};
  part.material.texture_bgr = texture;
  Mesh quad;
  quad.parts.push_back(part);

  Renderer renderer;
  const auto body = renderer.add_body(quad, 1);
  renderer.set_body_pose(body, Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 0.5)));
  Lighting light;
  light.ambient = 0.f;
  light.diffuse = 1.f;  // normal facing the headlight: shade exactly 1
  renderer.set_lighting(light);
  Intrinsics k = vga();
  k.pu = 319.5;
  k.pv = 239.5;
  const cv::Mat color = renderer.render(k, Pose(), kRenderColor).color;
  // The quad spans +-104 px around the centre; sample each quadrant's middle.
  CHECK(color.at<cv::Vec3b>(240 - 52, 320 - 52) == cv::Vec3b(0, 0, 255));
  CHECK(color.at<cv::Vec3b>(240 - 52, 320 + 52) == cv::Vec3b(0, 255, 0));
  CHECK(color.at<cv::Vec3b>(240 + 52, 320 - 52) == cv::Vec3b(255, 0, 0));
  CHECK(color.at<cv::Vec3b>(240 + 52, 320 + 52) == cv::Vec3b(255, 255, 255));
  CHECK(color.at<cv::Vec3b>(5, 5) == cv::Vec3b(0, 0, 0));
}

TEST_CASE("renderer: a body behind the camera renders nothing") {
  Renderer renderer;
  const auto body = renderer.add_body(test::make_box(0.1f, 0.1f, 0.1f), 1);
  renderer.set_body_pose(body, Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, -0.5)));
  const RenderOutput out = renderer.render(vga(), Pose(), kRenderDepth | kRenderIds);
  CHECK(cv::countNonZero(out.depth) == 0);
  CHECK(cv::countNonZero(out.ids) == 0);
}

TEST_CASE("renderer: one renderer per thread, identical results") {
  auto render_depth = [] {
    Renderer renderer;
    const auto body = renderer.add_body(test::make_box(0.08f, 0.06f, 0.16f), 1);
    renderer.set_body_pose(body, box_pose());
    return renderer.render(vga(), Pose(), kRenderDepth).depth;
  };
  cv::Mat a, b;
  std::thread t1([&] { a = render_depth(); }), t2([&] { b = render_depth(); });
  t1.join();
  t2.join();
  CHECK(cv::countNonZero(a != b) == 0);
  CHECK(cv::countNonZero(a) > 10000);
}

TEST_CASE("renderer: image motion is the largest shift of a body's corner in view") {
  Renderer renderer;
  const Intrinsics k = Intrinsics::centred(320, 240, 300.0);
  const auto box = renderer.add_body(test::make_box(0.1f, 0.1f, 0.1f), 1);
  renderer.set_body_pose(box, Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 0.5)));
  const Pose still;
  CHECK(renderer.image_motion(k, still, still) == 0.0);
  // A sideways step of 1 cm shifts a point at depth Z by f 0.01 / Z: most for the near corners.
  const Pose stepped(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.01, 0, 0));
  CHECK(renderer.image_motion(k, still, stepped) == Approx(300.0 * 0.01 / 0.45).epsilon(1e-6));
  // A turn of 0.01 rad about the optical axis moves a corner at image radius r by r 0.01.
  const Pose turned(Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitZ()).toRotationMatrix(), Eigen::Vector3d::Zero());
  const double corner_radius = 300.0 * std::hypot(0.05, 0.05) / 0.45;
  CHECK(renderer.image_motion(k, still, turned) == Approx(2.0 * corner_radius * std::sin(0.005)).epsilon(1e-6));
  // Nothing of the body in view: no corner to follow.
  renderer.set_body_pose(box, Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, -0.5)));
  CHECK(renderer.image_motion(k, still, stepped) == 0.0);
}

TEST_CASE("renderer: bad input gives clear errors") {
  Renderer renderer;
  CHECK_THROWS_WITH(renderer.add_body(test::make_box(0.1f, 0.1f, 0.1f), 0), Catch::Contains("reserved"));
  CHECK_THROWS_WITH(renderer.add_body(Mesh{}, 1), Catch::Contains("no triangles"));
  Mesh broken = test::make_box(0.1f, 0.1f, 0.1f);
  broken.parts[0].triangles[0] = Eigen::Vector3i(0, 1, 99);
  CHECK_THROWS_WITH(renderer.add_body(broken, 1), Catch::Contains("outside"));
  Intrinsics zero = vga();
  zero.fu = 0.0;
  CHECK_THROWS_AS(renderer.render(zero, Pose(), kRenderDepth), std::invalid_argument);
  CHECK_THROWS_AS(renderer.set_body_pose(5, Pose()), std::out_of_range);
}
