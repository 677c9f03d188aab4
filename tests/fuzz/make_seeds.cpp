// SPDX-License-Identifier: GPL-2.0-or-later
// Writes the seeds of tests/fuzz/corpus/ that are not plain copies of project files:
// `fuzz_make_seeds CORPUS_DIR MODELS_DIR`. Each is small and valid, so that the fuzzer
// starts from inputs the readers accept and mutates them into the corners.
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "icgp/io/mesh_loader.h"
#include "icgp/model/model_cache.h"
#include "icgp/model/viewpoint_model_generator.h"

namespace {

namespace fs = std::filesystem;

using Bytes = std::vector<std::uint8_t>;

Bytes read_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// `prefix` (the selector byte of targets that take one, or none) followed by `body`.
void write_seed(const fs::path& file, const Bytes& prefix, const Bytes& body) {
  fs::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(prefix.data()), static_cast<std::streamsize>(prefix.size()));
  out.write(reinterpret_cast<const char*>(body.data()), static_cast<std::streamsize>(body.size()));
  if (!out) throw std::runtime_error("cannot write " + file.string());
  std::cout << "wrote " << file.string() << " (" << prefix.size() + body.size() << " bytes)\n";
}

Bytes text(const std::string& s) { return Bytes(s.begin(), s.end()); }

void append_u32(Bytes& b, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void append_f32(Bytes& b, float f) {
  std::uint32_t v;
  std::memcpy(&v, &f, 4);
  append_u32(b, v);
}

// A tetrahedron, the smallest closed mesh, in each format the mesh target selects.
const float kVertices[4][3] = {{0, 0, 0}, {0.05f, 0, 0}, {0, 0.05f, 0}, {0, 0, 0.05f}};
const int kFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

Bytes ply_ascii() {
  std::string s = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 4\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& v : kVertices) s += std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + "\n";
  for (const auto& f : kFaces) s += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + "\n";
  return text(s);
}

Bytes ply_binary() {
  Bytes b = text("ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                 "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n");
  for (const auto& v : kVertices)
    for (float c : v) append_f32(b, c);
  for (const auto& f : kFaces) {
    b.push_back(3);
    for (int i : f) append_u32(b, static_cast<std::uint32_t>(i));
  }
  return b;
}

Bytes stl_binary() {
  Bytes b(80, 0);  // header
  append_u32(b, 4);
  for (const auto& f : kFaces) {
    for (int i = 0; i < 3; ++i) append_f32(b, 0.f);  // normal: recomputed by readers
    for (int i : f)
      for (float c : kVertices[i]) append_f32(b, c);
    b.push_back(0), b.push_back(0);  // attribute byte count
  }
  return b;
}

Bytes stl_ascii() {
  std::string s = "solid tetrahedron\n";
  for (const auto& f : kFaces) {
    s += " facet normal 0 0 0\n  outer loop\n";
    for (int i : f)
      s += "   vertex " + std::to_string(kVertices[i][0]) + " " + std::to_string(kVertices[i][1]) + " " +
           std::to_string(kVertices[i][2]) + "\n";
    s += "  endloop\n endfacet\n";
  }
  return text(s + "endsolid tetrahedron\n");
}

/// An encoded 8 x 6 image (the size the sequence target's folders expect).
Bytes encoded(const std::string& extension, const cv::Mat& image) {
  std::vector<std::uint8_t> buffer;
  if (!cv::imencode(extension, image, buffer)) throw std::runtime_error("cannot encode " + extension);
  return buffer;
}

cv::Mat depth_ramp(int type, double scale) {
  cv::Mat z(6, 8, CV_64F);
  for (int r = 0; r < z.rows; ++r)
    for (int c = 0; c < z.cols; ++c) z.at<double>(r, c) = (0.5 + 0.01 * (r * z.cols + c)) * scale;
  z.setTo(0.0, z == z.at<double>(2, 3));  // one pixel without a measurement
  cv::Mat out;
  z.convertTo(out, type);
  return out;
}

Bytes realsense_bin() {
  const cv::Mat mm = depth_ramp(CV_16U, 1000.0);
  Bytes b;
  append_u32(b, static_cast<std::uint32_t>(mm.rows));
  append_u32(b, static_cast<std::uint32_t>(mm.cols));
  for (int r = 0; r < mm.rows; ++r)
    for (int c = 0; c < mm.cols; ++c) b.push_back(mm.at<std::uint16_t>(r, c) & 0xff), b.push_back(mm.at<std::uint16_t>(r, c) >> 8);
  return b;
}

/// A tiny but real cache file: a coarse model of the textured box, saved as icgp does.
Bytes model_file(icgp::ViewpointModel::Kind kind, const icgp::Mesh& mesh, const fs::path& scratch) {
  icgp::ViewpointModelParams params;
  params.n_divides = 0;  // 12 views
  params.image_size = 64;
  params.image_margin = 4;
  params.n_points = 6;
  params.max_radius_depth_offset = 0.004;  // 2 depth offsets
  icgp::ModelGenerationOptions options;
  options.print_progress = false;
  const fs::path file = scratch / "seed.icgpmodel";
  icgp::save_viewpoint_model(icgp::generate_viewpoint_model(kind, mesh, params, options), file.string());
  return read_file(file);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: fuzz_make_seeds CORPUS_DIR MODELS_DIR\n";
    return 2;
  }
  const fs::path corpus(argv[1]), models(argv[2]);
  setenv("OPENCV_IO_ENABLE_OPENEXR", "1", 1);  // OpenCV 4.6 encodes EXR only when asked to
  try {
    write_seed(corpus / "mesh" / "textured_box.obj", {0}, read_file(models / "textured_box" / "textured_box.obj"));
    write_seed(corpus / "mesh" / "tetrahedron_ascii.ply", {1}, ply_ascii());
    write_seed(corpus / "mesh" / "tetrahedron_binary.ply", {1}, ply_binary());
    write_seed(corpus / "mesh" / "tetrahedron_ascii.stl", {2}, stl_ascii());
    write_seed(corpus / "mesh" / "tetrahedron_binary.stl", {2}, stl_binary());

    write_seed(corpus / "sequence" / "realsense_8x6.bin", {0}, realsense_bin());
    write_seed(corpus / "sequence" / "blender_8x6.exr", {1}, encoded(".exr", depth_ramp(CV_32F, 1.0)));
    write_seed(corpus / "sequence" / "icgp_8x6.png", {2}, encoded(".png", depth_ramp(CV_16U, 1000.0)));

    const icgp::Mesh box = icgp::load_mesh((models / "textured_box" / "textured_box.obj").string());
    const fs::path scratch = fs::temp_directory_path();
    write_seed(corpus / "model_cache" / "textured_box_region.icgpmodel", {},
               model_file(icgp::ViewpointModel::Kind::kRegion, box, scratch));
    write_seed(corpus / "model_cache" / "textured_box_depth.icgpmodel", {},
               model_file(icgp::ViewpointModel::Kind::kDepth, box, scratch));
    fs::remove(scratch / "seed.icgpmodel");
  } catch (const std::exception& e) {
    std::cerr << "fuzz_make_seeds: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
