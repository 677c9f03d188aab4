// SPDX-License-Identifier: GPL-2.0-or-later
// The sequence readers' depth paths (icgp::Sequence::open and load(0)) on arbitrary bytes.
// The first input byte picks the layout whose depth file of frame 0 the rest becomes:
//   0: visp-realsense depth_image_0000.bin (the header-and-uint16 reader),
//   1: visp-blender depth/Image0001.exr (OpenEXR through OpenCV),
//   2: icgp depth/000000.png (16-bit PNG through OpenCV).
// Everything else of each layout is a tiny valid folder made once. The intrinsics come
// from a fixed callback: the ViSP XML reader is not what is fuzzed here.
#include <opencv2/imgcodecs.hpp>

#include "fuzz_support.h"
#include "icgp/eval/sequence.h"

namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 8, kHeight = 6;  // the colour images (the seeds' depth images too)

const char* const kIdentity = "1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n";

struct LayoutFolder {
  fs::path dir;
  fs::path depth_file;
};

void write_color_image(const fs::path& file) {
  fs::create_directories(file.parent_path());
  if (!cv::imwrite(file.string(), cv::Mat(kHeight, kWidth, CV_8UC3, cv::Scalar(40, 120, 200))))
    throw std::runtime_error("fuzz harness: cannot write " + file.string());
}

/// What both ViSP layouts need besides images: an XML pair (read by the fixed callback) and
/// depth_M_color.txt.
void write_visp_calibration(const fs::path& dir) {
  icgp::fuzz::write_file(dir / "camera.xml", "");
  icgp::fuzz::write_file(dir / "camera_depth.xml", "");
  icgp::fuzz::write_file(dir / "depth_M_color.txt", kIdentity);
}

LayoutFolder make_realsense_folder(const fs::path& dir) {
  write_color_image(dir / "color_image_0000.jpg");
  write_visp_calibration(dir);
  return {dir, dir / "depth_image_0000.bin"};
}

LayoutFolder make_blender_folder(const fs::path& dir) {
  write_color_image(dir / "images" / "0001.jpg");
  fs::create_directories(dir / "depth");
  write_visp_calibration(dir);
  return {dir, dir / "depth" / "Image0001.exr"};
}

LayoutFolder make_icgp_folder(const fs::path& dir) {
  write_color_image(dir / "color" / "000000.png");
  fs::create_directories(dir / "depth");
  const std::string camera = "{fu: 10, fv: 10, pu: 3.5, pv: 2.5, width: 8, height: 6}";
  icgp::fuzz::write_file(dir / "sequence.yaml",
                         "format: icgp-sequence\nversion: 1\nframe_count: 1\nframe_rate: 30\ndepth_scale: 0.001\n"
                         "color_camera: " + camera + "\ndepth_camera: " + camera +
                             "\ndepth_T_color: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]\n");
  return {dir, dir / "depth" / "000000.png"};
}

icgp::SequenceOptions fixed_intrinsics() {
  icgp::SequenceOptions options;
  options.read_camera_xml = [](const std::string&) { return icgp::Intrinsics{10.0, 10.0, 3.5, 2.5, 0, 0}; };
  return options;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const fs::path root = icgp::fuzz::scratch_dir();
  static const LayoutFolder kLayouts[] = {make_realsense_folder(root / "realsense"),
                                          make_blender_folder(root / "blender"), make_icgp_folder(root / "icgp")};
  static const icgp::SequenceOptions options = fixed_intrinsics();
  const LayoutFolder& layout = kLayouts[data[0] % 3];
  icgp::fuzz::write_file(layout.depth_file, data + 1, size - 1);
  icgp::fuzz::refusing_like_a_loader([&] { icgp::Sequence::open(layout.dir.string(), options).load(0); });
  return 0;
}
