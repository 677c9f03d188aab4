// SPDX-License-Identifier: GPL-2.0-or-later
// load_mesh against independent truth: small meshes written here in several formats with
// known geometry, colours and texture pixels, and the project's models against the sizes
// documented in models/README.md.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>
#include <tuple>
#include <typeinfo>
#include <vector>

#include "icgp/io/mesh_loader.h"
#include "test_meshes.h"
#include "test_temp_dir.h"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using icgp::load_mesh;
using icgp::Mesh;
using icgp::test::mesh_signed_volume;
using icgp::test::mesh_surface_area;
using icgp::test::TempDir;

namespace {

// ---- test fixtures -------------------------------------------------------------------

// A unit cube centred at the origin: corner i has x, y, z set by bits 0, 1, 2 of i; faces
// counter-clockwise seen from outside.
Eigen::Vector3f cube_corner(int i) {
  return Eigen::Vector3f(i & 1 ? 0.5f : -0.5f, i & 2 ? 0.5f : -0.5f, i & 4 ? 0.5f : -0.5f);
}
const int kCubeQuads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};

std::string xyz(const Eigen::Vector3f& v) {
  return std::to_string(v.x()) + " " + std::to_string(v.y()) + " " + std::to_string(v.z());
}

/// The quad's corner indices, counted from first_index (1 in OBJ, 0 in PLY).
std::string quad_indices(const int (&quad)[4], int first_index) {
  std::string text;
  for (int corner : quad) text += " " + std::to_string(corner + first_index);
  return text;
}

std::string write_cube_obj(const TempDir& dir) {
  std::string text = "mtllib cube.mtl\n";
  for (int i = 0; i < 8; ++i) text += "v " + xyz(cube_corner(i)) + "\n";
  text += "usemtl paint\n";
  for (const auto& quad : kCubeQuads) text += "f" + quad_indices(quad, 1) + "\n";
  dir.write("cube.mtl", "newmtl paint\nKd 0.2 0.4 0.6\n");
  return dir.write("cube.obj", text);
}

std::string cube_ply_text() {
  std::string text =
      "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 6\nproperty list uchar int vertex_indices\nend_header\n";
  for (int i = 0; i < 8; ++i) text += xyz(cube_corner(i)) + "\n";
  for (const auto& quad : kCubeQuads) text += "4" + quad_indices(quad, 0) + "\n";
  return text;
}

std::string cube_stl_text() {
  std::string text = "solid cube\n";
  for (const auto& q : kCubeQuads)
    for (const auto& tri : {std::array<int, 3>{q[0], q[1], q[2]}, std::array<int, 3>{q[0], q[2], q[3]}}) {
      const Eigen::Vector3f a = cube_corner(tri[0]), b = cube_corner(tri[1]), c = cube_corner(tri[2]);
      text += "facet normal " + xyz((b - a).cross(c - a).normalized()) + "\nouter loop\n";
      for (const auto& v : {a, b, c}) text += "vertex " + xyz(v) + "\n";
      text += "endloop\nendfacet\n";
    }
  return text + "endsolid cube\n";
}

/// A 3x2 image whose pixels all differ, so any flip or transposition shows.
cv::Mat small_texture_bgr() {
  cv::Mat image(2, 3, CV_8UC3);
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 3; ++c) image.at<cv::Vec3b>(r, c) = cv::Vec3b(10 + 40 * c, 20 + 100 * r, 200 - 30 * (r + c));
  return image;
}

// ---- measurements --------------------------------------------------------------------

/// Every directed edge, with vertices identified by position (texture seams split vertices),
/// appears once and its reverse once: the surface is closed and consistently oriented.
bool closed_and_consistently_oriented(const Mesh& mesh) {
  using Key = std::tuple<float, float, float>;
  std::map<Key, int> ids;
  auto id = [&ids](const Eigen::Vector3f& v) { return ids.emplace(Key(v.x(), v.y(), v.z()), ids.size()).first->second; };
  std::map<std::pair<int, int>, int> directed;
  for (const auto& part : mesh.parts)
    for (const auto& t : part.triangles)
      for (int k = 0; k < 3; ++k) ++directed[{id(part.vertices[t[k]]), id(part.vertices[t[(k + 1) % 3]])}];
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    if (count != 1 || reverse == directed.end() || reverse->second != 1) return false;
  }
  return true;
}

void check_bounds(const Mesh& mesh, const Eigen::Vector3f& expected_min, const Eigen::Vector3f& expected_max,
                  float tolerance = 1e-6f) {
  Eigen::Vector3f lo, hi;
  mesh.bounds(lo, hi);
  INFO("bounds " << lo.transpose() << " .. " << hi.transpose());
  CHECK((lo - expected_min).cwiseAbs().maxCoeff() <= tolerance);
  CHECK((hi - expected_max).cwiseAbs().maxCoeff() <= tolerance);
}

bool same_image(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

template <typename Exception, typename Call>
std::string message_of(Call call) {
  try {
    call();
  } catch (const Exception& e) {
    return e.what();
  }
  return "(no " + std::string(typeid(Exception).name()) + " thrown)";
}

// ---- glTF writing --------------------------------------------------------------------

std::string base64(const std::string& bytes) {
  static const char* const alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t block = 0;
    for (std::size_t k = 0; k < 3; ++k)
      block = (block << 8) | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k) out += k <= n ? alphabet[(block >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

template <typename T>
void append_raw(std::string& bytes, const std::vector<T>& values) {
  bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// A 1x1 quad in z = 0 moved by its node (scale 2, then translation (1, 2, 3)), textured
// with small_texture_bgr(). glTF puts texture coordinates' origin at the top-left.
const std::vector<float> kQuadPositions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
const std::vector<float> kQuadGltfTexcoords = {0.25f, 0.75f, 0.75f, 0.75f, 0.75f, 0.25f, 0.25f, 0.25f};
const std::vector<std::uint16_t> kQuadIndices = {0, 1, 2, 0, 2, 3};  // 12 bytes: keeps 4-byte alignment

std::string quad_geometry_bytes() {
  std::string bytes;
  append_raw(bytes, kQuadPositions);
  append_raw(bytes, kQuadGltfTexcoords);
  append_raw(bytes, kQuadIndices);
  return bytes;
}

std::string png_bytes(const cv::Mat& image) {
  std::vector<unsigned char> png;
  cv::imencode(".png", image, png);
  return std::string(png.begin(), png.end());
}

/// buffer_json: the "buffers" entry; image_json: the "images" entry; extra_view: an optional
/// fourth bufferView (the image in a .glb).
std::string quad_gltf_json(const std::string& buffer_json, const std::string& image_json,
                           const std::string& extra_view = "") {
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
"nodes":[{"mesh":0,"translation":[1,2,3],"scale":[2,2,2]}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"indices":2,"material":0}]}],
"materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.1,0.2,0.3,1.0],"baseColorTexture":{"index":0}}}],
"textures":[{"source":0}],
"images":[)" + image_json + R"(],
"buffers":[)" + buffer_json + R"(],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":32},
{"buffer":0,"byteOffset":80,"byteLength":12})" + extra_view + R"(],
"accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
{"bufferView":1,"componentType":5126,"count":4,"type":"VEC2"},
{"bufferView":2,"componentType":5123,"count":6,"type":"SCALAR"}]})";
}

std::string write_quad_gltf(const TempDir& dir, const cv::Mat& texture) {
  const std::string geometry = quad_geometry_bytes();
  const std::string buffer = R"({"byteLength":)" + std::to_string(geometry.size()) +
                             R"(,"uri":"data:application/octet-stream;base64,)" + base64(geometry) + R"("})";
  const std::string image = R"({"uri":"data:image/png;base64,)" + base64(png_bytes(texture)) + R"("})";
  return dir.write("quad.gltf", quad_gltf_json(buffer, image));
}

std::string padded(std::string chunk, char pad) {
  chunk.resize((chunk.size() + 3) / 4 * 4, pad);
  return chunk;
}

std::string glb_chunk(const std::string& data, std::uint32_t type) {
  std::string chunk;
  append_raw(chunk, std::vector<std::uint32_t>{static_cast<std::uint32_t>(data.size()), type});
  return chunk + data;
}

std::string write_quad_glb(const TempDir& dir, const cv::Mat& texture) {
  const std::string png = png_bytes(texture);
  const std::string binary = padded(quad_geometry_bytes() + png, '\0');
  const std::string json = padded(
      quad_gltf_json(R"({"byteLength":)" + std::to_string(binary.size()) + "}",
                     R"({"bufferView":3,"mimeType":"image/png"})",
                     R"(,{"buffer":0,"byteOffset":92,"byteLength":)" + std::to_string(png.size()) + "}"),
      ' ');
  const std::string chunks = glb_chunk(json, 0x4E4F534Au) + glb_chunk(binary, 0x004E4942u);
  std::string file;
  append_raw(file, std::vector<std::uint32_t>{0x46546C67u, 2u, static_cast<std::uint32_t>(12 + chunks.size())});
  return dir.write("quad.glb", file + chunks);
}

// ---- the project's models --------------------------------------------------------------

std::string model(const std::string& relative) { return std::string(ICGP_MODELS_DIR) + "/" + relative; }

void check_textured_everywhere(const Mesh& mesh) {
  for (const auto& part : mesh.parts) {
    CHECK(part.texcoords.size() == part.vertices.size());
    CHECK(part.material.texture_bgr.type() == CV_8UC3);
    CHECK(!part.material.texture_bgr.empty());
    for (const auto& uv : part.texcoords) CHECK((uv.minCoeff() >= 0.f && uv.maxCoeff() <= 1.f));
  }
}

void check_untextured(const Mesh& mesh) {
  for (const auto& part : mesh.parts) {
    CHECK(part.texcoords.empty());
    CHECK(part.material.texture_bgr.empty());
  }
}

/// Volume of the prism with a regular polygon base that the cylinders are made of.
double cylinder_prism_volume(double radius, double height, int segments) {
  return 0.5 * segments * radius * radius * std::sin(2.0 * icgp::kPi / segments) * height;
}

}  // namespace

// ---- formats -----------------------------------------------------------------------------

TEST_CASE("OBJ cube: shared vertices, triangles, bounds, area, orientation and MTL colour") {
  TempDir dir("icgp_mesh_loader");
  const std::string path = write_cube_obj(dir);
  const Mesh mesh = load_mesh(path);
  CHECK(mesh.source == path);
  REQUIRE(mesh.parts.size() == 1);
  CHECK(mesh.vertex_count() == 8);
  CHECK(mesh.triangle_count() == 12);
  check_bounds(mesh, Eigen::Vector3f::Constant(-0.5f), Eigen::Vector3f::Constant(0.5f));
  CHECK(mesh_surface_area(mesh) == Approx(6.0));
  CHECK(mesh_signed_volume(mesh) == Approx(1.0));
  CHECK(closed_and_consistently_oriented(mesh));
  CHECK(mesh.parts[0].material.diffuse_rgb.isApprox(Eigen::Vector3f(0.2f, 0.4f, 0.6f)));
  check_untextured(mesh);
}

TEST_CASE("scale option multiplies every vertex") {
  TempDir dir("icgp_mesh_loader");
  const Mesh mesh = load_mesh(write_cube_obj(dir), {0.01});
  check_bounds(mesh, Eigen::Vector3f::Constant(-0.005f), Eigen::Vector3f::Constant(0.005f), 1e-9f);
  CHECK(mesh_surface_area(mesh) == Approx(6e-4));
  CHECK(mesh_signed_volume(mesh) == Approx(1e-6));
}

TEST_CASE("ASCII PLY and ASCII STL cubes load with the same geometry as the OBJ") {
  TempDir dir("icgp_mesh_loader");
  const std::string path = GENERATE(as<std::string>{}, "cube.ply", "cube.stl");
  const Mesh mesh = load_mesh(dir.write(path, path == "cube.ply" ? cube_ply_text() : cube_stl_text()));
  INFO(path);
  CHECK(mesh.triangle_count() == 12);
  // STL repeats each corner per facet with a facet normal; normals are stripped, so the
  // corners are shared again.
  CHECK(mesh.vertex_count() == 8);
  check_bounds(mesh, Eigen::Vector3f::Constant(-0.5f), Eigen::Vector3f::Constant(0.5f));
  CHECK(mesh_surface_area(mesh) == Approx(6.0));
  CHECK(mesh_signed_volume(mesh) == Approx(1.0));
  CHECK(closed_and_consistently_oriented(mesh));
}

TEST_CASE("textured OBJ: texture coordinates unflipped, texture read relative to the model's folder") {
  TempDir dir("icgp_mesh_loader");
  const cv::Mat texture = small_texture_bgr();
  fs::create_directories(dir.file("tex"));
  REQUIRE(cv::imwrite(dir.file("tex/quad.png"), texture));
  // A Windows-style separator in map_Kd must still find the file.
  const std::string separator = GENERATE(as<std::string>{}, "/", "\\");
  dir.write("quad.mtl", "newmtl printed\nKd 1 0.5 0.25\nmap_Kd tex" + separator + "quad.png\n");
  const std::string path = dir.write("quad.obj",
                                     "mtllib quad.mtl\nv 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\n"
                                     "vt 0.1 0.2\nvt 0.9 0.2\nvt 0.9 0.7\nvt 0.1 0.7\n"
                                     "usemtl printed\nf 1/1 2/2 3/3 4/4\n");
  const Mesh mesh = load_mesh(path);
  REQUIRE(mesh.parts.size() == 1);
  const icgp::MeshPart& part = mesh.parts[0];
  CHECK(part.triangles.size() == 2);
  REQUIRE(part.texcoords.size() == part.vertices.size());
  for (std::size_t i = 0; i < part.vertices.size(); ++i) {
    const Eigen::Vector2f expected(part.vertices[i].x() > 1.f ? 0.9f : 0.1f, part.vertices[i].y() > 0.5f ? 0.7f : 0.2f);
    CHECK(part.texcoords[i].isApprox(expected));
  }
  CHECK(same_image(part.material.texture_bgr, texture));
  CHECK(part.material.diffuse_rgb.isApprox(Eigen::Vector3f(1.f, 0.5f, 0.25f)));
}

TEST_CASE("glTF and GLB: node transform applied, base colour, embedded PNG texture") {
  TempDir dir("icgp_mesh_loader");
  const cv::Mat texture = small_texture_bgr();
  const bool binary = GENERATE(false, true);
  const std::string path = binary ? write_quad_glb(dir, texture) : write_quad_gltf(dir, texture);
  INFO(path);
  const Mesh mesh = load_mesh(path);
  REQUIRE(mesh.parts.size() == 1);
  const icgp::MeshPart& part = mesh.parts[0];
  CHECK(part.triangles.size() == 2);
  check_bounds(mesh, Eigen::Vector3f(1.f, 2.f, 3.f), Eigen::Vector3f(3.f, 4.f, 3.f));
  CHECK(mesh_surface_area(mesh) == Approx(4.0));
  // The file's (u, v) with v down becomes (u, 1 - v): the same image point, v up.
  REQUIRE(part.texcoords.size() == part.vertices.size());
  for (std::size_t i = 0; i < part.vertices.size(); ++i) {
    const Eigen::Vector2f expected(part.vertices[i].x() > 2.f ? 0.75f : 0.25f, part.vertices[i].y() > 3.f ? 0.75f : 0.25f);
    CHECK(part.texcoords[i].isApprox(expected));
  }
  CHECK(same_image(part.material.texture_bgr, texture));
  CHECK(part.material.diffuse_rgb.isApprox(Eigen::Vector3f(0.1f, 0.2f, 0.3f)));
}

TEST_CASE("points and lines are dropped, triangles kept") {
  TempDir dir("icgp_mesh_loader");
  const Mesh mesh = load_mesh(dir.write("mixed.obj",
                                        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nv 6 6 6\n"
                                        "f 1 2 3\nl 4 5\np 5\n"));
  CHECK(mesh.triangle_count() == 1);
  check_bounds(mesh, Eigen::Vector3f(0.f, 0.f, 0.f), Eigen::Vector3f(1.f, 1.f, 0.f));
}

// ---- errors --------------------------------------------------------------------------------

TEST_CASE("a missing file is an error naming it") {
  TempDir dir("icgp_mesh_loader");
  const std::string path = dir.file("nowhere.obj");
  CHECK_THAT(message_of<std::runtime_error>([&] { load_mesh(path); }), Contains(path) && Contains("no such file"));
  CHECK_THAT(message_of<std::runtime_error>([&] { load_mesh(dir.file("")); }), Contains("no such file"));
}

TEST_CASE("garbage and triangle-free files are errors naming the file") {
  TempDir dir("icgp_mesh_loader");
  std::string noise;
  for (int i = 0; i < 3000; ++i) noise += static_cast<char>((i * 7919 + 13) % 256);
  const std::string name = GENERATE(as<std::string>{}, "garbage.ply", "garbage.stl", "garbage.glb", "garbage.obj",
                                    "garbage.dae", "garbage.unknown");
  const std::string path = dir.write(name, noise);
  CHECK_THAT(message_of<std::runtime_error>([&] { load_mesh(path); }), Contains(path));

  const std::string lines = dir.write("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\n");
  CHECK_THAT(message_of<std::runtime_error>([&] { load_mesh(lines); }), Contains(lines) && Contains("no triangles"));
  const std::string empty = dir.write("empty.obj", "");
  CHECK_THAT(message_of<std::runtime_error>([&] { load_mesh(empty); }), Contains(empty));
}

TEST_CASE("a missing texture file is an error naming the model and the texture") {
  TempDir dir("icgp_mesh_loader");
  dir.write("lost.mtl", "newmtl printed\nmap_Kd missing.png\n");
  const std::string path = dir.write("lost.obj",
                                     "mtllib lost.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                                     "usemtl printed\nf 1/1 2/2 3/3\n");
  CHECK_THAT(message_of<std::runtime_error>([&] { load_mesh(path); }), Contains(path) && Contains("missing.png"));
}

TEST_CASE("MTL reflectance: Pr and Pm as given, roughness from Ns as Blender reads it, specular from Ks") {
  TempDir dir("icgp_mesh_loader");
  dir.write("shiny.mtl",
            "newmtl metal\nKd 0.5 0.5 0.5\nKs 0.3 0.4 0.5\nNs 250\nPr 0.2\nPm 1\n"
            "newmtl phong\nKd 0.5 0.5 0.5\nKs 0 0 0\nNs 360\n");
  const std::string path = dir.write("shiny.obj",
                                     "mtllib shiny.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                                     "usemtl metal\nf 1 2 3\nusemtl phong\nf 2 4 3\n");
  const Mesh mesh = load_mesh(path);
  REQUIRE(mesh.parts.size() == 2);
  const icgp::Material& metal = mesh.parts[0].material.roughness == Approx(0.2f) ? mesh.parts[0].material
                                                                                  : mesh.parts[1].material;
  const icgp::Material& phong = &metal == &mesh.parts[0].material ? mesh.parts[1].material : mesh.parts[0].material;
  CHECK(metal.roughness == Approx(0.2f));  // Pr wins over Ns
  CHECK(metal.metallic == 1.0f);
  CHECK(metal.specular == Approx(0.4f));
  CHECK(phong.roughness == Approx(0.4f));  // 1 - sqrt(360 / 1000)
  CHECK(phong.metallic == 0.0f);
  CHECK(phong.specular == 0.0f);
  // A mesh without materials keeps the defaults: a dielectric of medium gloss.
  const Mesh plain = load_mesh(dir.write("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  CHECK(plain.parts[0].material.roughness == 0.5f);
  CHECK(plain.parts[0].material.metallic == 0.0f);
}

TEST_CASE("a reflectance parameter out of range is an error naming the file, the material and the key") {
  TempDir dir("icgp_mesh_loader");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"Pr 1.5", "material 'bad': Pr (roughness) is 1.5; expected a number in [0, 1]"},
      {"Pm -0.2", "material 'bad': Pm (metallic) is -0.2; expected a number in [0, 1]"},
      {"Ns 5000", "material 'bad': Ns (shininess) is 5000; expected a number in [0, 1000]"},
      {"Ks 0.5 2 0.5", "material 'bad': Ks (specular colour) has 2; expected three numbers in [0, 1]"},
  };
  for (const auto& [line, message] : cases) {
    INFO(line);
    dir.write("bad.mtl", "newmtl bad\nKd 0.5 0.5 0.5\n" + line + "\n");
    const std::string path = dir.write("bad.obj", "mtllib bad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl bad\nf 1 2 3\n");
    CHECK_THAT(message_of<std::runtime_error>([&] { load_mesh(path); }), Contains(path) && Contains(message));
  }
}

TEST_CASE("a non-positive or non-finite scale is an invalid argument naming the file") {
  TempDir dir("icgp_mesh_loader");
  const std::string path = write_cube_obj(dir);
  const double scale = GENERATE(0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                                std::numeric_limits<double>::infinity());
  CHECK_THAT(message_of<std::invalid_argument>([&] { load_mesh(path, {scale}); }), Contains(path) && Contains("scale"));
}

// ---- models/ (sizes as documented in models/README.md) -----------------------------------

TEST_CASE("models/textured_box: 0.08 x 0.16 x 0.06 m, closed, a texture on every face") {
  const Mesh mesh = load_mesh(model("textured_box/textured_box.obj"));
  CHECK(mesh.triangle_count() == 12);
  check_bounds(mesh, Eigen::Vector3f(-0.04f, -0.08f, -0.03f), Eigen::Vector3f(0.04f, 0.08f, 0.03f));
  CHECK(mesh_surface_area(mesh) == Approx(2 * (0.08 * 0.16 + 0.16 * 0.06 + 0.08 * 0.06)));
  CHECK(mesh_signed_volume(mesh) == Approx(0.08 * 0.16 * 0.06));
  CHECK(closed_and_consistently_oriented(mesh));
  check_textured_everywhere(mesh);
}

TEST_CASE("models/textureless_mug: r 0.04 m, h 0.10 m, handle to x = 0.076 m, plain colour") {
  const Mesh mesh = load_mesh(model("textureless_mug/textureless_mug.obj"));
  CHECK(mesh.triangle_count() == 856);
  check_bounds(mesh, Eigen::Vector3f(-0.04f, -0.05f, -0.04f), Eigen::Vector3f(0.076f, 0.05f, 0.04f));
  CHECK(mesh_signed_volume(mesh) > cylinder_prism_volume(0.04, 0.10, 64));  // body plus the handle
  CHECK(closed_and_consistently_oriented(mesh));
  check_untextured(mesh);
}

TEST_CASE("models/labelled_cylinder: r 0.04 m, h 0.10 m, closed, textured everywhere") {
  const Mesh mesh = load_mesh(model("labelled_cylinder/labelled_cylinder.obj"));
  CHECK(mesh.triangle_count() == 256);
  check_bounds(mesh, Eigen::Vector3f(-0.04f, -0.05f, -0.04f), Eigen::Vector3f(0.04f, 0.05f, 0.04f));
  CHECK(mesh_signed_volume(mesh) == Approx(cylinder_prism_volume(0.04, 0.10, 64)));
  CHECK(closed_and_consistently_oriented(mesh));
  check_textured_everywhere(mesh);
}

TEST_CASE("models/two_region: region meshes share the frame and together make object.obj") {
  const Mesh object = load_mesh(model("two_region/object.obj"));
  const Mesh body = load_mesh(model("two_region/region_body.obj"));
  const Mesh lid = load_mesh(model("two_region/region_lid.obj"));
  check_bounds(object, Eigen::Vector3f(-0.05f, -0.04f, -0.03f), Eigen::Vector3f(0.05f, 0.04f, 0.03f));
  CHECK(object.triangle_count() == 20);
  CHECK(object.parts.size() == 2);
  CHECK(closed_and_consistently_oriented(object));
  CHECK(mesh_signed_volume(object) == Approx(0.10 * 0.08 * 0.06));
  check_untextured(object);

  Mesh regions = body;
  regions.append(lid);
  CHECK(regions.triangle_count() == object.triangle_count());
  CHECK(mesh_surface_area(regions) == Approx(mesh_surface_area(object)));
  CHECK(closed_and_consistently_oriented(regions));
  check_bounds(regions, Eigen::Vector3f(-0.05f, -0.04f, -0.03f), Eigen::Vector3f(0.05f, 0.04f, 0.03f));
  check_bounds(lid, Eigen::Vector3f(-0.05f, 0.015f, -0.03f), Eigen::Vector3f(0.05f, 0.04f, 0.03f));
  REQUIRE(body.parts.size() == 1);
  REQUIRE(lid.parts.size() == 1);
  CHECK(!body.parts[0].material.diffuse_rgb.isApprox(lid.parts[0].material.diffuse_rgb, 0.1f));
}

TEST_CASE("models/labelled_can: a printed side and plain caps as two regions of one cylinder") {
  const Mesh object = load_mesh(model("labelled_can/object.obj"));
  const Mesh label = load_mesh(model("labelled_can/region_label.obj"));
  const Mesh caps = load_mesh(model("labelled_can/region_caps.obj"));
  check_bounds(object, Eigen::Vector3f(-0.04f, -0.05f, -0.04f), Eigen::Vector3f(0.04f, 0.05f, 0.04f));
  CHECK(closed_and_consistently_oriented(object));
  // 64 facets: the inscribed polygon's volume, r² h (n/2) sin(2π/n).
  CHECK(mesh_signed_volume(object) == Approx(0.04 * 0.04 * 0.10 * 32 * std::sin(2 * M_PI / 64)).epsilon(1e-4));
  Mesh regions = label;
  regions.append(caps);
  CHECK(regions.triangle_count() == object.triangle_count());
  CHECK(mesh_surface_area(regions) == Approx(mesh_surface_area(object)));
  CHECK(closed_and_consistently_oriented(regions));
  REQUIRE(label.parts.size() == 1);
  REQUIRE(caps.parts.size() == 1);
  CHECK(!label.parts[0].material.texture_bgr.empty());
  CHECK(label.parts[0].texcoords.size() == label.parts[0].vertices.size());
  CHECK(caps.parts[0].material.texture_bgr.empty());
  CHECK(caps.parts[0].material.diffuse_rgb.isApprox(Eigen::Vector3f(0.85f, 0.10f, 0.12f), 1e-3f));
}

TEST_CASE("models/gripper: mount, palm and two fingers 0.10 m apart, origin on the flange, z towards the tips") {
  const Mesh mesh = load_mesh(model("gripper/gripper.obj"));
  CHECK(mesh.triangle_count() == 48);  // four boxes
  check_bounds(mesh, Eigen::Vector3f(-0.025f, -0.07f, 0.0f), Eigen::Vector3f(0.025f, 0.07f, 0.13f));
  CHECK(closed_and_consistently_oriented(mesh));
  const double mount = 0.04 * 0.04 * 0.02, palm = 0.05 * 0.14 * 0.03, finger = 0.024 * 0.014 * 0.08;
  CHECK(mesh_signed_volume(mesh) == Approx(mount + palm + 2 * finger));
  check_untextured(mesh);
}

TEST_CASE("models/figurine: a closed, non-convex, plain yellow figurine of 5120 triangles, centred") {
  const Mesh mesh = load_mesh(model("figurine/figurine.obj"));
  CHECK(mesh.triangle_count() == 5120);  // an icosphere of four subdivisions
  check_bounds(mesh, Eigen::Vector3f(-0.05745f, -0.083528f, -0.039388f), Eigen::Vector3f(0.05745f, 0.083528f, 0.039388f),
               1e-5f);
  CHECK(closed_and_consistently_oriented(mesh));
  CHECK(mesh_signed_volume(mesh) > 0.0);
  check_untextured(mesh);
  // Not convex: some vertex lies more than 5 mm in front of some face's plane (a convex
  // surface has every vertex behind every face).
  const icgp::MeshPart& part = mesh.parts.front();
  float most_in_front = 0.f;
  for (const Eigen::Vector3i& t : part.triangles) {
    const Eigen::Vector3f a = part.vertices[t[0]];
    const Eigen::Vector3f n = (part.vertices[t[1]] - a).cross(part.vertices[t[2]] - a).normalized();
    for (const Eigen::Vector3f& v : part.vertices) most_in_front = std::max(most_in_front, n.dot(v - a));
  }
  CHECK(most_in_front > 0.005f);
}

TEST_CASE("models/hinged_box: a closed base and a closed lid whose origin is on its hinge edge") {
  const Mesh base = load_mesh(model("hinged_box/base.obj"));
  const Mesh lid = load_mesh(model("hinged_box/lid.obj"));
  CHECK(base.triangle_count() == 12);
  CHECK(lid.triangle_count() == 12);
  check_bounds(base, Eigen::Vector3f(-0.06f, -0.03f, -0.04f), Eigen::Vector3f(0.06f, 0.03f, 0.04f));
  check_bounds(lid, Eigen::Vector3f(-0.06f, 0.0f, 0.0f), Eigen::Vector3f(0.06f, 0.01f, 0.08f));
  CHECK(mesh_signed_volume(base) == Approx(0.12 * 0.06 * 0.08));
  CHECK(mesh_signed_volume(lid) == Approx(0.12 * 0.01 * 0.08));
  CHECK(closed_and_consistently_oriented(base));
  CHECK(closed_and_consistently_oriented(lid));
  check_untextured(base);
  check_untextured(lid);
  // Blue sides with a cream top (seen when the lid opens), an orange lid: region cues tell them apart.
  REQUIRE(base.parts.size() == 2);
  REQUIRE(lid.parts.size() == 1);
  for (const icgp::MeshPart& part : base.parts)
    CHECK(!part.material.diffuse_rgb.isApprox(lid.parts[0].material.diffuse_rgb, 0.1f));
}

TEST_CASE("check_mesh refuses what no view could be made of, naming the mesh and the element") {
  Mesh mesh;
  mesh.source = "hand-made";
  mesh.parts.emplace_back();
  icgp::MeshPart& part = mesh.parts.front();
  part.vertices = {{0, 0, 0}, {0.1f, 0, 0}, {0, 0.1f, 0}};
  CHECK_THAT(message_of<std::invalid_argument>([&] { icgp::check_mesh(mesh); }), Contains("mesh 'hand-made': has no triangle"));
  part.triangles = {{0, 1, 2}};
  CHECK_NOTHROW(icgp::check_mesh(mesh));
  part.vertices[1].y() = std::numeric_limits<float>::quiet_NaN();
  CHECK_THAT(message_of<std::invalid_argument>([&] { icgp::check_mesh(mesh); }),
             Contains("part 0 vertex 1 is (0.100000, nan, 0.000000) (expected finite coordinates within +-10000 m)"));
  part.vertices[1] = {0.1f, 0, 0};
  part.triangles.push_back({0, 2, 3});
  CHECK_THAT(message_of<std::invalid_argument>([&] { icgp::check_mesh(mesh); }),
             Contains("part 0 triangle 1 has index (0, 2, 3) (expected indices 0 to 2)"));
  part.triangles.pop_back();
  part.vertices = {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}};
  CHECK_THAT(message_of<std::invalid_argument>([&] { icgp::check_mesh(mesh); }), Contains("has all its vertices at one point"));
}

TEST_CASE("a mesh file with a vertex beyond the coordinate bound is refused before it is used") {
  TempDir dir("icgp_mesh_loader");
  const std::string far = dir.write("far.obj", "v 0 0 0\nv 1e6 0 0\nv 0 1 0\nf 1 2 3\n");
  CHECK_THAT(message_of<std::invalid_argument>([&] { load_mesh(far); }),
             Contains(far) && Contains("vertex 1 is (1000000.000000, 0.000000, 0.000000)"));
}
