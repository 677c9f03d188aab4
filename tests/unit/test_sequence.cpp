// SPDX-License-Identifier: GPL-2.0-or-later
// Sequence reading (the two ViSP tutorial sets, their XML cameras read by ViSP's parser, and
// bad inputs) and the synthetic sequence writer read back through the same reader.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <opencv2/imgcodecs.hpp>

#include "icgp/base/standard_stream_capture.h"
#include "icgp/eval/sequence.h"
#include "icgp/eval/sequence_writer.h"
#include "icgp/visp/visp_camera_xml.h"
#include "test_meshes.h"
#include "test_temp_dir.h"

using namespace icgp;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;
using icgp::test::files_under;
using icgp::test::read_bytes;
using icgp::test::TempDir;

namespace {

const fs::path kData = ICGP_TEST_DATA_DIR;
const fs::path kBlender = kData / "teabox-blender";
const fs::path kRealsense = kData / "realsense-cube";

/// Copies file contents only: the vendored data is read-only and copies must be editable.
void copy_contents(const fs::path& from, const fs::path& to) {
  fs::create_directories(to.parent_path());
  std::ifstream in(from, std::ios::binary);
  std::ofstream out(to, std::ios::binary);
  out << in.rdbuf();
}

void copy_tree(const fs::path& from, const fs::path& to) {
  for (const auto& entry : fs::recursive_directory_iterator(from))
    if (entry.is_regular_file()) copy_contents(entry.path(), to / fs::relative(entry.path(), from));
}

/// The first `frames` frames of teabox-blender with its calibration and model.
void copy_blender_frames(const fs::path& to, int frames) {
  for (const char* name : {"teabox.cao", "teabox.xml", "teabox_depth.xml", "depth_M_color.txt"})
    copy_contents(kBlender / name, to / name);
  char name[64];
  for (int n = 1; n <= frames; ++n) {
    std::snprintf(name, sizeof name, "images/%04d.jpg", n);
    copy_contents(kBlender / name, to / name);
    std::snprintf(name, sizeof name, "depth/Image%04d.exr", n);
    copy_contents(kBlender / name, to / name);
    std::snprintf(name, sizeof name, "camera_poses/Camera_%03d.txt", n);
    copy_contents(kBlender / name, to / name);
  }
}

SequenceOptions cube_intrinsics() {
  SequenceOptions options = visp_sequence_options();
  options.color_intrinsics_file = "models/cube/cube.xml";  // relative to the sequence folder
  options.depth_intrinsics_file = "models/cube/cube_depth.xml";
  return options;
}

}  // namespace

TEST_CASE("teabox-blender: layout, calibration, ground truth and depth of all frames") {
  const Sequence seq = Sequence::open(kBlender.string(), visp_sequence_options());
  CHECK(seq.layout() == "visp-blender");
  REQUIRE(seq.size() == 100);
  REQUIRE(seq.has_ground_truth());
  REQUIRE(seq.objects().size() == 1);
  CHECK(seq.objects()[0].name == "teabox");

  // The XML's principal point (320, 240) is Blender's sensor centre, which in ViSP's
  // pixel-centre convention is (319.5, 239.5); test_blender_convention checks it on the data.
  const Intrinsics& c = seq.color_intrinsics();
  CHECK(c.fu == 700.0);
  CHECK(c.fv == 700.0);
  CHECK(c.pu == 320.0);  // exactly as teabox.xml writes it
  CHECK(c.pv == 240.0);
  CHECK(c.width == 640);
  CHECK(c.height == 480);
  const Intrinsics& d = seq.depth_intrinsics();
  CHECK(d.fu == 600.0);
  CHECK(d.fv == 600.0);
  CHECK(d.pu == 320.0);
  CHECK(d.pv == 240.0);
  SequenceOptions corrected = visp_sequence_options();
  corrected.blender_principal_point = true;
  CHECK(Sequence::open(kBlender.string(), corrected).color_intrinsics().pu == 319.5);
  CHECK(Sequence::open(kBlender.string(), corrected).depth_intrinsics().pv == 239.5);
  CHECK(seq.depth_T_color().translation().isApprox(Eigen::Vector3d(-0.1, 0.0, 0.0)));
  CHECK(seq.depth_T_color().rotation().isIdentity());

  for (int i = 0; i < seq.size(); ++i) {
    const Frame frame = seq.load(i);
    INFO("frame " << i);
    CHECK(frame.index == i);
    REQUIRE(frame.colors.size() == 1);
    REQUIRE(frame.depths.size() == 1);
    CHECK(frame.colors[0].camera == "Camera1");
    CHECK(frame.colors[0].image.type() == CV_8UC3);
    CHECK(frame.colors[0].image.size() == cv::Size(640, 480));
    const DepthImage& depth = frame.depths[0];
    CHECK(depth.camera == "Camera2");
    CHECK(depth.camera_T_reference.translation().isApprox(Eigen::Vector3d(-0.1, 0.0, 0.0)));
    REQUIRE(depth.depth.type() == CV_32FC1);
    REQUIRE(frame.truth("teabox") != nullptr);

    // Every stored value is 0 or a finite positive depth; the corner is background.
    int valid = 0;
    for (auto it = depth.depth.begin<float>(); it != depth.depth.end<float>(); ++it) {
      REQUIRE(std::isfinite(*it));
      REQUIRE(*it >= 0.f);
      if (*it > 0.f) {
        ++valid;
        REQUIRE(*it < 2.f);
      }
    }
    CHECK(valid > 1000);
    CHECK(depth.depth.at<float>(0, 0) == 0.f);

    // The box centre seen by the depth camera lies within half a box diagonal of its
    // ground-truth depth.
    const Pose depth_T_object = depth.camera_T_reference * *frame.truth("teabox");
    const Eigen::Vector2d px = d.project(depth_T_object.translation());
    REQUIRE(d.contains(px.x(), px.y()));
    const float z = depth.depth.at<float>(int(std::lround(px.y())), int(std::lround(px.x())));
    CHECK(z > 0.f);
    CHECK(std::abs(z - depth_T_object.translation().z()) < 0.15);
  }

  const Frame first = seq.load(0);  // images/0001.jpg, camera_poses/Camera_001.txt
  Eigen::Matrix4d expected;
  expected << -0.4226182997226715, -2.4714811530657244e-08, 0.9063078165054321, -0.10589859634637833,  //
      0.5825634002685547, 0.7660443782806396, 0.2716538608074188, -0.07994276285171509,                 //
      -0.6942720413208008, 0.6427875757217407, -0.32374438643455505, 0.7175615429878235,                //
      0.0, 0.0, 0.0, 1.0;
  CHECK(first.truth("teabox")->matrix() == expected);
  CHECK(first.truth()->matrix() == expected);
}

TEST_CASE("realsense-cube: explicit intrinsics files, raw uint16 depth in metres") {
  const Sequence seq = Sequence::open(kRealsense.string(), cube_intrinsics());
  CHECK(seq.layout() == "visp-realsense");
  REQUIRE(seq.size() == 10);
  CHECK_FALSE(seq.has_ground_truth());
  REQUIRE(seq.objects().size() == 1);
  CHECK(seq.objects()[0].name == "cube");  // the model beside the chosen intrinsics
  CHECK(seq.color_intrinsics().fu == Approx(614.9616699219));
  CHECK(seq.color_intrinsics().pv == Approx(241.4553680420));
  CHECK(seq.depth_intrinsics().fu == Approx(383.9700012207));
  CHECK(seq.depth_T_color().translation().x() == Approx(-0.01484097075));

  for (int i = 0; i < seq.size(); ++i) {
    const Frame frame = seq.load(i);
    CHECK(frame.ground_truth.empty());
    CHECK(frame.colors[0].image.size() == cv::Size(640, 480));
    CHECK(frame.depths[0].depth.size() == cv::Size(640, 480));
  }

  // Decode frame 3's .bin independently: header, then row-major little-endian uint16 mm.
  const std::string raw = read_bytes(kRealsense / "depth_image_0003.bin");
  const auto u16 = [&](std::size_t offset) {
    return unsigned(static_cast<unsigned char>(raw[offset])) | unsigned(static_cast<unsigned char>(raw[offset + 1])) << 8;
  };
  const int width = int(u16(4));
  REQUIRE(width == 640);
  const cv::Mat depth = seq.load(3).depths[0].depth;
  int checked = 0, beyond_max_depth = 0;
  for (int pixel = 0; pixel < 640 * 480; pixel += 997) {
    const double metres = u16(8 + 2 * std::size_t(pixel)) * 0.001;
    const float z = depth.at<float>(pixel / width, pixel % width);
    if (metres > SequenceOptions().max_depth) {
      ++beyond_max_depth;
      CHECK(z == 0.f);
    } else {
      CHECK(z == Approx(metres).epsilon(1e-6));
      checked += metres > 0.0;
    }
  }
  CHECK(checked > 200);
  CHECK(beyond_max_depth < 10);
}

TEST_CASE("realsense-cube: intrinsics auto-detection refuses to guess among models") {
  REQUIRE_THROWS_WITH(Sequence::open(kRealsense.string(), visp_sequence_options()),
                      Contains("ambiguous") && Contains("models/cube/cube.xml") &&
                          Contains("models/teabox/teabox.xml") && Contains("color_intrinsics_file"));
}

TEST_CASE("sequence errors name the file and what was expected") {
  SECTION("missing folder") {
    REQUIRE_THROWS_WITH(Sequence::open("/nonexistent/icgp-seq"),
                        Contains("/nonexistent/icgp-seq") && Contains("does not exist"));
  }
  SECTION("empty folder") {
    TempDir dir("icgp_test_sequence_empty");
    REQUIRE_THROWS_WITH(Sequence::open(dir.path().string()),
                        Contains(dir.path().string()) && Contains("unknown sequence layout") &&
                            Contains("sequence.yaml") && Contains("color_image_0000.jpg"));
  }
  SECTION("truncated RealSense depth file") {
    TempDir dir("icgp_test_sequence_truncated");
    copy_tree(kRealsense, dir.path());
    const fs::path bin = dir.path() / "depth_image_0002.bin";
    fs::resize_file(bin, fs::file_size(bin) / 2);
    const Sequence seq = Sequence::open(dir.path().string(), cube_intrinsics());
    CHECK_NOTHROW(seq.load(1));
    REQUIRE_THROWS_WITH(seq.load(2), Contains("depth_image_0002.bin") && Contains("truncated"));
  }
  SECTION("depth image of another size") {
    TempDir dir("icgp_test_sequence_depth_size");
    copy_tree(kRealsense, dir.path());
    const std::uint32_t header[2] = {80, 100};  // height, width (little-endian host assumed)
    std::ofstream out(dir.path() / "depth_image_0003.bin", std::ios::binary);
    out.write(reinterpret_cast<const char*>(header), sizeof header);
    out << std::string(2 * 80 * 100, '\0');
    out.close();
    const Sequence seq = Sequence::open(dir.path().string(), cube_intrinsics());
    REQUIRE_THROWS_WITH(seq.load(3), Contains("depth_image_0003.bin") && Contains("100x80") && Contains("640x480"));
  }
  SECTION("depth frames of half the size the depth intrinsics were calibrated for") {
    TempDir dir("icgp_test_sequence_half_depth");
    copy_tree(kRealsense, dir.path());
    for (const auto& entry : fs::directory_iterator(dir.path())) {
      if (entry.path().extension() != ".bin") continue;
      const std::uint32_t header[2] = {240, 320};  // height, width (little-endian host assumed)
      std::ofstream out(entry.path(), std::ios::binary | std::ios::trunc);
      out.write(reinterpret_cast<const char*>(header), sizeof header);
      out << std::string(2 * 240 * 320, '\x01');
    }
    REQUIRE_THROWS_WITH(Sequence::open(dir.path().string(), cube_intrinsics()),
                        Contains("depth intrinsics put the principal point at") && Contains("outside the 320x240 depth"));
  }
  SECTION("a colour JPEG cut short is refused, not tracked with grey rows") {
    TempDir dir("icgp_test_sequence_cut_jpeg");
    copy_blender_frames(dir.path(), 3);
    const fs::path jpeg = dir.path() / "images/0002.jpg";
    fs::resize_file(jpeg, fs::file_size(jpeg) / 2);
    const Sequence seq = Sequence::open(dir.path().string(), visp_sequence_options());
    CHECK_NOTHROW(seq.load(0));
    REQUIRE_THROWS_WITH(seq.load(1), Contains("0002.jpg") && Contains("cut short"));
  }
  SECTION("malformed ground-truth pose") {
    TempDir dir("icgp_test_sequence_pose");
    copy_blender_frames(dir.path(), 3);
    dir.write("camera_poses/Camera_002.txt", "1 0 0 0\n0 1 zero 0\n0 0 1 0.5\n0 0 0 1\n");
    const Sequence seq = Sequence::open(dir.path().string(), visp_sequence_options());
    REQUIRE(seq.size() == 3);
    CHECK_NOTHROW(seq.load(0));
    REQUIRE_THROWS_WITH(seq.load(1), Contains("Camera_002.txt") && Contains("line 2") && Contains("'zero'"));
  }
  SECTION("missing depth frame") {
    TempDir dir("icgp_test_sequence_missing_frame");
    copy_blender_frames(dir.path(), 3);
    fs::remove(dir.path() / "depth/Image0002.exr");
    REQUIRE_THROWS_WITH(Sequence::open(dir.path().string(), visp_sequence_options()),
                        Contains("Image0002.exr") && Contains("missing"));
  }
  SECTION("gap in the colour images") {
    TempDir dir("icgp_test_sequence_gap");
    copy_blender_frames(dir.path(), 3);
    fs::remove(dir.path() / "images/0002.jpg");
    REQUIRE_THROWS_WITH(Sequence::open(dir.path().string(), visp_sequence_options()),
                        Contains("0002.jpg") && Contains("missing frame"));
  }
  SECTION("intrinsics XML without <px>") {
    TempDir dir("icgp_test_sequence_xml");
    copy_blender_frames(dir.path(), 1);
    dir.write("teabox.xml", "<conf><camera><py>700</py><u0>320</u0><v0>240</v0></camera></conf>");
    REQUIRE_THROWS_WITH(Sequence::open(dir.path().string(), visp_sequence_options()),
                        Contains("teabox.xml") && Contains("<px>"));
  }
  SECTION("frame index out of range") {
    const Sequence seq = Sequence::open(kRealsense.string(), cube_intrinsics());
    REQUIRE_THROWS_AS(seq.load(10), std::out_of_range);
  }
  SECTION("a ViSP layout without an XML reader: the core library says what to pass") {
    REQUIRE_THROWS_WITH(Sequence::open(kBlender.string()),
                        Contains(kBlender.string()) && Contains("visp-blender") &&
                            Contains("SequenceOptions::read_camera_xml") && Contains("read_visp_camera_xml"));
    SequenceOptions explicit_files = cube_intrinsics();
    explicit_files.read_camera_xml = nullptr;
    REQUIRE_THROWS_WITH(Sequence::open(kRealsense.string(), explicit_files),
                        Contains("visp-realsense") && Contains("SequenceOptions::read_camera_xml"));
  }
  SECTION("the injected reader reads the XML files") {
    SequenceOptions options;
    std::vector<std::string> read;
    options.read_camera_xml = [&](const std::string& path) {
      read.push_back(fs::path(path).filename().string());
      return Intrinsics::centred(1, 1, 500.0);
    };
    const Sequence seq = Sequence::open(kBlender.string(), options);
    CHECK(read == std::vector<std::string>{"teabox.xml", "teabox_depth.xml"});
    CHECK(seq.color_intrinsics().fu == 500.0);
    CHECK(seq.color_intrinsics().width == 640);  // the image size is the first image's
  }
}

TEST_CASE("ViSP camera XML: ViSP's parser gives the numbers the files write") {
  const Intrinsics teabox = read_visp_camera_xml((kBlender / "teabox.xml").string());
  CHECK((teabox.fu == 700.0 && teabox.fv == 700.0 && teabox.pu == 320.0 && teabox.pv == 240.0));
  CHECK((teabox.width == 0 && teabox.height == 0));
  const Intrinsics teabox_depth = read_visp_camera_xml((kBlender / "teabox_depth.xml").string());
  CHECK((teabox_depth.fu == 600.0 && teabox_depth.fv == 600.0 && teabox_depth.pu == 320.0 && teabox_depth.pv == 240.0));
  // Exactly the decimal numbers of the files (what strtod makes of them).
  const Intrinsics cube = read_visp_camera_xml((kRealsense / "models/cube/cube.xml").string());
  CHECK(cube.fu == 614.9616699219);
  CHECK(cube.fv == 614.9281005859);
  CHECK(cube.pu == 320.1971435547);
  CHECK(cube.pv == 241.455368042);
  const Intrinsics cube_depth = read_visp_camera_xml((kRealsense / "models/cube/cube_depth.xml").string());
  CHECK(cube_depth.fu == 383.9700012207);
  CHECK(cube_depth.fv == 383.9700012207);
  CHECK(cube_depth.pu == 320.5035095215);
  CHECK(cube_depth.pv == 235.6029510498);
}

TEST_CASE("ViSP camera XML: errors name the file and the field, ViSP's parser stays quiet") {
  TempDir dir("icgp_test_visp_camera_xml");
  const auto error = [&](const std::string& xml) {
    const std::string path = dir.write("camera.xml", xml);
    std::string message, said;
    {
      const StandardStreamCapture out(std::cout);
      try {
        read_visp_camera_xml(path);
      } catch (const std::runtime_error& e) {
        message = e.what();
      }
      said = out.text();
    }
    CHECK(said.empty());
    return message;
  };
  const std::string file = (dir.path() / "camera.xml").string();
  const std::string missing = (dir.path() / "missing.xml").string();
  CHECK_THROWS_WITH(read_visp_camera_xml(missing), missing + ": no such file");
  CHECK_THROWS_WITH(read_visp_camera_xml(dir.path().string()), dir.path().string() + ": cannot read the file");
  CHECK(error("<conf><face><angle_appear>70</angle_appear></face></conf>") ==
        file + ": no <camera> block with <px>, <py>, <u0> and <v0>");
  // A block in a comment is no block.
  CHECK(error("<conf><!-- <camera><px>1</px><py>1</py><u0>1</u0><v0>1</v0></camera> --></conf>") ==
        file + ": no <camera> block with <px>, <py>, <u0> and <v0>");
  CHECK(error("<conf><camera><px>700</px><py>700</py><u0>320</u0></camera></conf>") ==
        file + ": <camera> block has no <v0>");
  CHECK(error("<conf><camera><px>abc</px><py>700</py><u0>320</u0><v0>240</v0></camera></conf>") ==
        file + ": <camera> <px>: 'abc' (expected a finite number)");
  // ViSP's parser would read 3 and drop the x.
  CHECK(error("<conf><camera><px>700</px><py>700</py><u0>3x</u0><v0>240</v0></camera></conf>") ==
        file + ": <camera> <u0>: '3x' (expected a finite number)");
  CHECK(error("<conf><camera><px>700</px><py>-700</py><u0>320</u0><v0>240</v0></camera></conf>") ==
        file + ": <camera> <py> must be a finite positive number, got -700");
  CHECK(error("<conf><camera><px>700</px><py>700</py><u0>inf</u0><v0>240</v0></camera></conf>") ==
        file + ": <camera> <u0>: 'inf' (expected a finite number)");
  CHECK_THAT(error("<conf><camera><px>700</px>"), Contains(file + ": not an XML file"));
}

namespace {

Intrinsics small_camera(double focal) {
  Intrinsics k;
  k.fu = focal;
  k.fv = focal * 1.01;
  k.pu = 80.3;
  k.pv = 59.2;
  k.width = 160;
  k.height = 120;
  return k;
}

constexpr double kBoxSide = 0.15;

Pose box_world_pose() {
  return Pose::from_rotation_vector(Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d(0.01, -0.01, 0.02));
}

Pose depth_T_color() {
  return Pose::from_rotation_vector(Eigen::Vector3d(0.0, 0.01, 0.0), Eigen::Vector3d(-0.02, 0.0, 0.0));
}

/// 5 frames of a red box; the depth camera has other intrinsics and sits 2 cm aside.
SequenceWriter box_sequence_writer(std::uint64_t seed, const SensorNoise& noise = {}, double gain_variation = 0.0) {
  SequenceWriterOptions options;
  options.frame_count = 5;
  options.seed = seed;
  options.color_intrinsics = small_camera(200.0);
  options.depth_intrinsics = small_camera(170.0);
  options.depth_T_color = depth_T_color();
  options.motion.look_at_wander = 0.01;
  options.motion.speed = 3.0;
  options.noise = noise;
  options.gain_variation = gain_variation;
  options.progress = false;
  SequenceWriter writer(options);
  Mesh box = test::make_box(kBoxSide, kBoxSide, kBoxSide);
  box.parts[0].material.diffuse_rgb = Eigen::Vector3f(1.f, 0.f, 0.f);
  writer.add_object("box", box, box_world_pose());
  return writer;
}

/// Z of the first hit of the ray through pixel (u, v) with the box at camera_T_box, 0 on
/// a miss (slab method in the box frame; the ray direction has Z = 1 so t is Z).
double ray_box_depth(const Intrinsics& k, double u, double v, const Pose& camera_T_box) {
  const Pose box_T_camera = camera_T_box.inverse();
  const Eigen::Vector3d origin = box_T_camera.translation();
  const Eigen::Vector3d direction = box_T_camera.rotation() * Eigen::Vector3d((u - k.pu) / k.fu, (v - k.pv) / k.fv, 1.0);
  double t_near = -1e9, t_far = 1e9;
  for (int a = 0; a < 3; ++a) {
    const double t1 = (-kBoxSide / 2 - origin[a]) / direction[a], t2 = (kBoxSide / 2 - origin[a]) / direction[a];
    t_near = std::max(t_near, std::min(t1, t2));
    t_far = std::min(t_far, std::max(t1, t2));
  }
  return t_near <= t_far && t_near > 0.0 ? t_near : 0.0;
}

}  // namespace

TEST_CASE("sequence writer: exact ground truth, depth and colour read back through Sequence") {
  TempDir dir("icgp_test_sequence_writer");
  const SequenceWriter writer = box_sequence_writer(42);
  writer.write(dir.path().string());

  const Sequence seq = Sequence::open(dir.path().string());
  CHECK(seq.layout() == "icgp");
  REQUIRE(seq.size() == 5);
  REQUIRE(seq.has_ground_truth());
  REQUIRE(seq.objects().size() == 1);
  CHECK(seq.objects()[0].name == "box");
  CHECK(seq.color_intrinsics().fv == small_camera(200.0).fv);
  CHECK(seq.color_intrinsics().pu == 80.3);
  CHECK(seq.depth_intrinsics().fu == 170.0);
  CHECK(seq.depth_intrinsics().width == 160);
  CHECK(seq.depth_T_color().matrix() == depth_T_color().matrix());

  for (int i = 0; i < seq.size(); ++i) {
    INFO("frame " << i);
    const Frame frame = seq.load(i);
    CHECK(frame.timestamp == Approx(i / 30.0));
    const Pose* truth = frame.truth("box");
    REQUIRE(truth != nullptr);
    const Pose expected = writer.color_T_world(i) * box_world_pose();
    CHECK((truth->matrix() - expected.matrix()).cwiseAbs().maxCoeff() <= 1e-12);

    // Depth at the centre pixel: the analytic ray-box distance within the 0.1 mm
    // quantisation (plus float rendering error).
    const DepthImage& depth = frame.depths[0];
    const Intrinsics& k = depth.intrinsics;
    const double z_true = ray_box_depth(k, 80, 60, depth.camera_T_reference * *truth);
    REQUIRE(z_true > 0.0);
    CHECK(std::abs(depth.depth.at<float>(60, 80) - z_true) <= 0.5e-4 + 1e-5);
    // Behind the box, the background plane: valid and farther away.
    CHECK(depth.depth.at<float>(0, 0) > z_true);

    // The box is red where the colour camera sees its centre; the background is not.
    const ColorImage& color = frame.colors[0];
    const Eigen::Vector2d centre = color.intrinsics.project(truth->translation());
    const cv::Vec3b on_box = color.image.at<cv::Vec3b>(int(std::lround(centre.y())), int(std::lround(centre.x())));
    CHECK(on_box[2] > 60);
    CHECK(on_box[1] == 0);
    CHECK(on_box[0] == 0);
  }
}

TEST_CASE("sequence writer: the same seed gives identical files, noise keeps the ground truth") {
  SensorNoise noise;
  noise.color_sigma = 4.0;
  noise.depth_sigma_at_1m = 0.002;
  noise.depth_dropout = 0.05;
  TempDir a("icgp_test_sequence_seed_a"), b("icgp_test_sequence_seed_b"), clean("icgp_test_sequence_seed_clean");
  box_sequence_writer(7, noise).write(a.path().string());
  box_sequence_writer(7, noise).write(b.path().string());
  box_sequence_writer(7).write(clean.path().string());

  const std::vector<fs::path> files = files_under(a.path());
  REQUIRE(files == files_under(b.path()));
  CHECK(files.size() == 1 + 5 + 5 + 1);  // sequence.yaml, colour, depth, poses/box.txt
  for (const fs::path& file : files) {
    INFO(file);
    CHECK(read_bytes(a.path() / file) == read_bytes(b.path() / file));
  }
  CHECK(read_bytes(a.path() / "poses/box.txt") == read_bytes(clean.path() / "poses/box.txt"));
  CHECK(read_bytes(a.path() / "depth/000000.png") != read_bytes(clean.path() / "depth/000000.png"));
  CHECK(box_sequence_writer(8).color_T_world(0).translation() != box_sequence_writer(7).color_T_world(0).translation());
}

TEST_CASE("sequence writer: a hunting auto-exposure scales the colour and nothing else") {
  TempDir steady("icgp_test_sequence_gain_steady"), hunting("icgp_test_sequence_gain_hunting");
  box_sequence_writer(7).write(steady.path().string());
  box_sequence_writer(7, {}, 0.3).write(hunting.path().string());

  CHECK(read_bytes(steady.path() / "poses/box.txt") == read_bytes(hunting.path() / "poses/box.txt"));
  const Sequence a = Sequence::open(steady.path().string()), b = Sequence::open(hunting.path().string());
  std::vector<double> gains;
  for (int i = 0; i < a.size(); ++i) {
    INFO("frame " << i);
    const Frame fa = a.load(i), fb = b.load(i);
    CHECK(cv::norm(fa.depths[0].depth, fb.depths[0].depth, cv::NORM_INF) == 0.0);
    // Unsaturated pixels scale by the frame's gain, one gain for the whole image.
    cv::Mat steady_f, hunting_f;
    fa.colors[0].image.convertTo(steady_f, CV_64F);
    fb.colors[0].image.convertTo(hunting_f, CV_64F);
    cv::Mat usable;
    cv::Mat(fa.colors[0].image > 40 & fb.colors[0].image < 250).convertTo(usable, CV_64F, 1.0 / 255);
    const double gain = cv::sum(hunting_f.mul(usable)).dot(cv::Scalar::all(1)) / cv::sum(steady_f.mul(usable)).dot(cv::Scalar::all(1));
    CHECK(gain >= 0.7 - 0.01);
    CHECK(gain <= 1.3 + 0.01);
    gains.push_back(gain);
  }
  // Five frames at 30 Hz cover a sixth of a 0.4 Hz cycle: the gain changes, but smoothly.
  const auto [lowest, highest] = std::minmax_element(gains.begin(), gains.end());
  CHECK(*highest - *lowest > 0.005);
  for (std::size_t i = 1; i < gains.size(); ++i) CHECK(std::abs(gains[i] - gains[i - 1]) < 0.05);
}

TEST_CASE("sequence writer: refuses a non-empty folder that is not a sequence") {
  TempDir dir("icgp_test_sequence_writer_refuse");
  dir.write("notes.txt", "keep me");
  REQUIRE_THROWS_WITH(box_sequence_writer(1).write(dir.path().string()),
                      Contains(dir.path().string()) && Contains("refusing"));
  CHECK(fs::exists(dir.path() / "notes.txt"));
}

TEST_CASE("icgp layout errors name the file and what was expected") {
  TempDir dir("icgp_test_sequence_icgp_errors");
  box_sequence_writer(3).write(dir.path().string());
  SECTION("malformed pose line") {
    std::string poses = read_bytes(dir.path() / "poses/box.txt");
    const std::size_t third_line = poses.find('\n', poses.find('\n') + 1) + 1;
    poses.insert(third_line, "1 2 3 ");
    dir.write("poses/box.txt", poses);
    REQUIRE_THROWS_WITH(Sequence::open(dir.path().string()),
                        Contains("box.txt") && Contains("line 3") && Contains("expected 16 numbers"));
  }
  SECTION("missing depth image") {
    fs::remove(dir.path() / "depth/000002.png");
    REQUIRE_THROWS_WITH(Sequence::open(dir.path().string()), Contains("000002.png") && Contains("missing"));
  }
  SECTION("depth image of another size") {
    cv::imwrite((dir.path() / "depth/000001.png").string(), cv::Mat(60, 80, CV_16UC1, cv::Scalar(5000)));
    const Sequence seq = Sequence::open(dir.path().string());
    REQUIRE_THROWS_WITH(seq.load(1), Contains("000001.png") && Contains("80x60") && Contains("sequence.yaml"));
  }
  SECTION("missing intrinsics key") {
    std::string yaml = read_bytes(dir.path() / "sequence.yaml");
    yaml.replace(yaml.find("fu: 170"), 7, "f: 170");
    dir.write("sequence.yaml", yaml);
    REQUIRE_THROWS_WITH(Sequence::open(dir.path().string()),
                        Contains("sequence.yaml") && Contains("depth_camera.fu"));
  }
}

TEST_CASE("sequence writer: a spinning object turns at its rate in the ground truth and the depth") {
  TempDir dir("icgp_test_sequence_spin");
  SequenceWriterOptions options;
  options.frame_count = 4;
  options.color_intrinsics = options.depth_intrinsics = small_camera(200.0);
  options.progress = false;
  SequenceWriter writer(options);
  const Eigen::Vector3d spin(0.0, 3.0, 0.0);  // rad/s about the object's y axis
  writer.add_object("box", test::make_box(kBoxSide, kBoxSide, kBoxSide), box_world_pose(), "", spin);
  writer.write(dir.path().string());

  const Sequence sequence = Sequence::open(dir.path().string());
  for (int i = 0; i < sequence.size(); ++i) {
    const Frame frame = sequence.load(i);
    const Pose world_T_box = writer.color_T_world(i).inverse() * *frame.truth("box");
    const Pose expected = box_world_pose() * Pose::from_rotation_vector(spin * i / options.frame_rate, Eigen::Vector3d::Zero());
    CHECK((world_T_box.matrix() - expected.matrix()).norm() < 1e-9);
    // The rendered depth follows the turning box.
    const Intrinsics& k = frame.depths[0].intrinsics;
    const double truth = ray_box_depth(k, k.width / 2, k.height / 2, *frame.truth("box"));
    if (truth > 0.0) CHECK(frame.depths[0].depth.at<float>(k.height / 2, k.width / 2) == Approx(truth).margin(1e-4));
  }
}
