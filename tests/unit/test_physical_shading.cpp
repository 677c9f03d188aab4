// SPDX-License-Identifier: GPL-2.0-or-later
// The renderer's physically based colour renders against closed forms: a matte plane under a
// lamp and ambient light, the GGX highlight where a glossy plane mirrors the lamp into the
// camera, a metal's tinted reflection, and a box's shadow where the lamp's rays put it.
#include <catch2/catch.hpp>
#include <cmath>

#include "icgp/render/renderer.h"
#include "test_meshes.h"

using namespace icgp;

namespace {

/// Odd sides: the principal point is a pixel centre, whose ray is the optical axis.
const Intrinsics kCamera = Intrinsics::centred(321, 241, 300.0);

/// A square of half-size `half` in its x-y plane, normal along z.
Mesh square(float half, const Material& material) {
  MeshPart part;
  part.vertices = {{-half, -half, 0.f}, {half, -half, 0.f}, {half, half, 0.f}, {-half, half, 0.f}};
  part.triangles = {{0, 1, 2}, {0, 2, 3}};
  part.material = material;
  Mesh mesh;
  mesh.parts.push_back(part);
  return mesh;
}

Material matte(float albedo) {
  Material m;
  m.diffuse_rgb = Eigen::Vector3f::Constant(albedo);
  m.roughness = 1.f;
  m.specular = 0.f;
  return m;
}

/// The 8-bit sRGB value of a linear intensity, as a camera writes it.
double srgb(double linear) {
  const double c = std::clamp(linear, 0.0, 1.0);
  return 255.0 * (c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055);
}

Pose at_depth(double z) { return Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, z)); }

/// The BGR pixel seen through camera-frame point (x, y, z).
cv::Vec3b pixel_at(const cv::Mat& color, double x, double y, double z) {
  const int col = static_cast<int>(std::lround(kCamera.pu + kCamera.fu * x / z));
  const int row = static_cast<int>(std::lround(kCamera.pv + kCamera.fv * y / z));
  return color.at<cv::Vec3b>(row, col);
}

PhysicalLighting one_lamp(const Eigen::Vector3f& direction, float strength, float ambient) {
  PhysicalLighting lighting;
  lighting.ambient = ambient;
  lighting.lamps = {{direction.normalized(), strength, 0.f}};
  return lighting;
}

}  // namespace

TEST_CASE("physical shading: a matte plane reads albedo x (strength x cos + ambient), sRGB-encoded") {
  Renderer renderer;
  renderer.set_body_pose(renderer.add_body(square(0.3f, matte(0.5f)), 1), at_depth(0.5));
  // Head-on, then 60° off the normal: the cosine halves the lamp's part.
  renderer.set_physical_lighting(one_lamp({0.f, 0.f, 1.f}, 0.3f, 0.1f));
  const cv::Mat head_on = renderer.render(kCamera, Pose(), kRenderColor).color;
  renderer.set_physical_lighting(one_lamp({std::sin(1.0472f), 0.f, std::cos(1.0472f)}, 0.3f, 0.1f));
  const cv::Mat oblique = renderer.render(kCamera, Pose(), kRenderColor).color;
  for (const double x : {-0.15, 0.0, 0.12})
    for (int channel = 0; channel < 3; ++channel) {
      CHECK(head_on.at<cv::Vec3b>(120, static_cast<int>(160 + 600 * x))[channel] ==
            Approx(srgb(0.5 * (0.3 + 0.1))).margin(1.5));
      CHECK(oblique.at<cv::Vec3b>(120, static_cast<int>(160 + 600 * x))[channel] ==
            Approx(srgb(0.5 * (0.3 * 0.5 + 0.1))).margin(1.5));
    }
  // Lambertian shading in display values (the renderer's default) would read 0.5 x 0.4 x 255.
  CHECK(head_on.at<cv::Vec3b>(120, 160)[1] > 0.5 * 0.4 * 255.0 + 40.0);
}

TEST_CASE("physical shading: where a glossy plane mirrors the lamp into the camera it reads GGX's peak") {
  // Normal, view and lamp all along the optical axis: D = 1 / (π α²), Smith's G = 1, Fresnel
  // = F0, so the lamp adds π D F0 / 4 = F0 / (4 α²) of its strength to the albedo.
  const float roughness = 0.5f, strength = 0.3f;
  const double alpha2 = std::pow(roughness, 4.0);
  Material glossy = matte(0.2f);
  glossy.roughness = roughness;
  glossy.specular = 0.5f;  // F0 = 0.04
  Renderer renderer;
  renderer.set_body_pose(renderer.add_body(square(0.3f, glossy), 1), at_depth(0.5));
  renderer.set_physical_lighting(one_lamp({0.f, 0.f, 1.f}, strength, 0.f));
  const cv::Mat color = renderer.render(kCamera, Pose(), kRenderColor).color;
  const double peak = strength * (0.2 + 0.04 / (4.0 * alpha2));
  CHECK(color.at<cv::Vec3b>(120, 160)[0] == Approx(srgb(peak)).margin(1.5));
  // Away from the mirror direction the highlight fades towards the matte value.
  const double off_peak = color.at<cv::Vec3b>(120, 310)[0];
  CHECK(off_peak < srgb(peak) - 10.0);
  CHECK(off_peak > srgb(strength * 0.2) + 3.0);

  SECTION("a metal reflects in its own colour, and has no diffuse part") {
    Material metal = glossy;
    metal.diffuse_rgb = {0.9f, 0.6f, 0.2f};
    metal.metallic = 1.f;
    metal.roughness = 0.8f;
    Renderer metal_renderer;
    metal_renderer.set_body_pose(metal_renderer.add_body(square(0.3f, metal), 1), at_depth(0.5));
    metal_renderer.set_physical_lighting(one_lamp({0.f, 0.f, 1.f}, 0.5f, 0.f));
    const cv::Vec3b bgr = metal_renderer.render(kCamera, Pose(), kRenderColor).color.at<cv::Vec3b>(120, 160);
    const double scale = 0.5 / (4.0 * std::pow(0.8, 4.0));
    CHECK(bgr[2] == Approx(srgb(0.9 * scale)).margin(1.5));
    CHECK(bgr[1] == Approx(srgb(0.6 * scale)).margin(1.5));
    CHECK(bgr[0] == Approx(srgb(0.2 * scale)).margin(1.5));
  }
}

TEST_CASE("physical shading: a box's shadow falls where the lamp's rays past it meet the plane") {
  // A 5 cm cube at z 0.45 before a wall at z 0.6; the lamp's rays go 0.5 m right per metre
  // forward. The cube's shadow on the wall spans x in [0.0375, 0.1125], |y| < 0.025;
  // from the camera the cube itself hides the wall only up to x = 0.035.
  Renderer renderer;
  renderer.set_body_pose(renderer.add_body(square(0.4f, matte(0.5f)), 1), at_depth(0.6));
  const auto box = renderer.add_body(test::make_box(0.05f, 0.05f, 0.05f), 2);
  renderer.set_body_pose(box, at_depth(0.45));
  const Eigen::Vector3f direction(0.5f, 0.f, 1.f);
  renderer.set_physical_lighting(one_lamp(direction, 0.4f, 0.1f));
  const double cosine = 1.0 / direction.norm();
  const double lit = srgb(0.5 * (0.4 * cosine + 0.1)), shadowed = srgb(0.5 * 0.1);
  const cv::Mat color = renderer.render(kCamera, Pose(), kRenderColor).color;
  for (const double x : {0.05, 0.075, 0.1}) CHECK(pixel_at(color, x, 0.0, 0.6)[1] == Approx(shadowed).margin(1.5));
  CHECK(pixel_at(color, 0.075, 0.035, 0.6)[1] == Approx(lit).margin(1.5));
  CHECK(pixel_at(color, 0.125, 0.0, 0.6)[1] == Approx(lit).margin(1.5));
  CHECK(pixel_at(color, -0.1, 0.0, 0.6)[1] == Approx(lit).margin(1.5));

  SECTION("a body that casts no shadows leaves the wall lit") {
    renderer.set_body_casts_shadows(box, false);
    const cv::Mat unshadowed = renderer.render(kCamera, Pose(), kRenderColor).color;
    CHECK(pixel_at(unshadowed, 0.075, 0.0, 0.6)[1] == Approx(lit).margin(1.5));
  }
  // The lamp's map is kept from render to render while nothing it shows moves: what moves
  // must move the shadow.
  SECTION("the shadow follows the box when the box moves") {
    renderer.set_body_pose(box, Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.05, 0.45)));
    const cv::Mat moved = renderer.render(kCamera, Pose(), kRenderColor).color;
    CHECK(pixel_at(moved, 0.075, 0.0, 0.6)[1] == Approx(lit).margin(1.5));
    CHECK(pixel_at(moved, 0.075, 0.05, 0.6)[1] == Approx(shadowed).margin(1.5));
  }
  SECTION("the shadow follows the lamp when the lamp turns") {
    renderer.set_physical_lighting(one_lamp({-0.5f, 0.f, 1.f}, 0.4f, 0.1f));  // shadow at x in [-0.1125, -0.0375]
    const cv::Mat turned = renderer.render(kCamera, Pose(), kRenderColor).color;
    CHECK(pixel_at(turned, 0.075, 0.0, 0.6)[1] == Approx(lit).margin(1.5));
    CHECK(pixel_at(turned, -0.075, 0.0, 0.6)[1] == Approx(shadowed).margin(1.5));
  }
  SECTION("the shadow stays on the wall when the camera moves with the lamp fixed in the scene") {
    // The camera 5 cm to the left (the scene shifts right in its frame), the lamp's
    // direction given in the moved camera's frame, as the scene's lamps are: the same.
    const Pose moved_camera_T_world(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.05, 0.0, 0.0));
    const cv::Mat seen = renderer.render(kCamera, moved_camera_T_world, kRenderColor).color;
    CHECK(pixel_at(seen, 0.125, 0.0, 0.6)[1] == Approx(shadowed).margin(1.5));  // world x 0.075
    CHECK(pixel_at(seen, 0.175, 0.0, 0.6)[1] == Approx(lit).margin(1.5));       // world x 0.125
  }
  SECTION("a lamp of some size softens the shadow's edge, not its core") {
    PhysicalLighting wide = one_lamp(direction, 0.4f, 0.1f);
    wide.lamps[0].angle_deg = 10.f;  // penumbra ±0.15 x tan 5° ≈ ±13 mm at the far edge
    renderer.set_physical_lighting(wide);
    const cv::Mat soft = renderer.render(kCamera, Pose(), kRenderColor).color;
    CHECK(pixel_at(soft, 0.075, 0.0, 0.6)[1] == Approx(shadowed).margin(1.5));
    const double edge = pixel_at(soft, 0.1125, 0.0, 0.6)[1];
    CHECK(edge > shadowed + 10.0);
    CHECK(edge < lit - 10.0);
  }
}

TEST_CASE("physical shading: bad lamps are refused with the rule they break") {
  Renderer renderer;
  PhysicalLighting five;
  five.lamps.resize(5);
  CHECK_THROWS_WITH(renderer.set_physical_lighting(five), Catch::Contains("at most 4 lamps, got 5"));
  CHECK_THROWS_WITH(renderer.set_physical_lighting(one_lamp({0.f, 0.f, 0.f}, 0.3f, 0.1f)),
                    Catch::Contains("non-zero direction"));
  PhysicalLighting negative = one_lamp({0.f, 0.f, 1.f}, -0.3f, 0.1f);
  CHECK_THROWS_WITH(renderer.set_physical_lighting(negative), Catch::Contains("strength >= 0"));
}
