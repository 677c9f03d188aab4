// SPDX-License-Identifier: GPL-2.0-or-later
// The sequence layout registry: a layout defined in this test only, registered at run
// time, is detected, named and read by Sequence like the built-in ones.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>

#include "icgp/eval/sequence.h"
#include "icgp/eval/sequence_layout.h"
#include "test_temp_dir.h"

using namespace icgp;
using Catch::Matchers::Contains;
using icgp::test::TempDir;
namespace fs = std::filesystem;

namespace {

const char* const kLayout = "test-frames-txt";
constexpr int kWidth = 8, kHeight = 6, kFrames = 2;
constexpr double kMaxDepth = 2.0;  // metres; the test writes depth beyond it too

/// The test's layout: frames.txt holds the frame count; frame i is color_<i>.png and
/// depth_<i>.png (uint16 millimetres). The cameras are given in code.
class FramesTxtLayout : public SequenceLayout {
 public:
  explicit FramesTxtLayout(fs::path dir) : dir_(std::move(dir)) {}
  fs::path color_file(int i) const override { return dir_ / ("color_" + std::to_string(i) + ".png"); }
  fs::path depth_file(int i) const override { return dir_ / ("depth_" + std::to_string(i) + ".png"); }
  cv::Mat read_depth(int i) const override {
    cv::Mat z;
    cv::imread(depth_file(i).string(), cv::IMREAD_UNCHANGED).convertTo(z, CV_32F, 0.001);
    return z;
  }
  std::map<std::string, Pose> read_ground_truth(int) const override { return {}; }
  std::string size_origin() const override { return "the test's camera"; }

 private:
  fs::path dir_;
};

Intrinsics test_camera() {
  Intrinsics k;
  k.fu = k.fv = 10.0;
  k.pu = 3.5;
  k.pv = 2.5;
  k.width = kWidth;
  k.height = kHeight;
  return k;
}

SequenceLayoutEntry frames_txt_entry() {
  return {kLayout, "frames.txt", [](const fs::path& dir) { return fs::is_regular_file(dir / "frames.txt"); },
          [](const fs::path& dir, const SequenceOptions&) {
            SequenceDescription d;
            std::ifstream(dir / "frames.txt") >> d.frame_count;
            d.frame_rate = 15.0;
            d.color_intrinsics = d.depth_intrinsics = test_camera();
            return SequenceLayoutEntry::Opened{d, std::make_shared<FramesTxtLayout>(dir)};
          }};
}

/// Once per process: ctest runs each test case in a process of its own, a plain run of the
/// executable runs them all in one.
void register_test_layout() {
  static const bool registered = [] {
    SequenceLayouts::instance().add(frames_txt_entry());
    return true;
  }();
  (void)registered;
}

cv::Vec3b color_at(int frame, int row, int col) {
  return {static_cast<uchar>(20 * frame + col), static_cast<uchar>(10 * row), 200};
}

std::uint16_t depth_mm_at(int frame, int row, int col) {
  if (row == 0 && col == 0) return 2500;  // beyond kMaxDepth: Sequence clears it
  return static_cast<std::uint16_t>(500 + 100 * frame + 10 * row + col);
}

/// A sequence of the test's layout, written with pixels known per frame, row and column.
void write_frames_txt_sequence(const fs::path& dir) {
  std::ofstream(dir / "frames.txt") << kFrames << "\n";
  for (int i = 0; i < kFrames; ++i) {
    cv::Mat color(kHeight, kWidth, CV_8UC3), depth(kHeight, kWidth, CV_16UC1);
    for (int r = 0; r < kHeight; ++r)
      for (int c = 0; c < kWidth; ++c) {
        color.at<cv::Vec3b>(r, c) = color_at(i, r, c);
        depth.at<std::uint16_t>(r, c) = depth_mm_at(i, r, c);
      }
    REQUIRE(cv::imwrite((dir / ("color_" + std::to_string(i) + ".png")).string(), color));
    REQUIRE(cv::imwrite((dir / ("depth_" + std::to_string(i) + ".png")).string(), depth));
  }
}

}  // namespace

TEST_CASE("sequence layouts: a registered layout is detected, named and read") {
  register_test_layout();
  TempDir dir("icgp_test_sequence_layouts");
  write_frames_txt_sequence(dir.path());
  SequenceOptions options;
  options.max_depth = kMaxDepth;

  const Sequence seq = Sequence::open(dir.path().string(), options);
  CHECK(seq.layout() == kLayout);
  REQUIRE(seq.size() == kFrames);
  CHECK(seq.frame_rate() == 15.0);
  CHECK(seq.color_intrinsics().fu == 10.0);
  CHECK_FALSE(seq.has_ground_truth());

  for (int i = 0; i < kFrames; ++i) {
    const Frame frame = seq.load(i);
    REQUIRE(frame.colors.size() == 1);
    REQUIRE(frame.depths.size() == 1);
    const cv::Mat& color = frame.colors[0].image;
    const cv::Mat& depth = frame.depths[0].depth;
    REQUIRE(color.type() == CV_8UC3);
    REQUIRE(depth.type() == CV_32FC1);
    for (int r = 0; r < kHeight; ++r)
      for (int c = 0; c < kWidth; ++c) {
        CHECK(color.at<cv::Vec3b>(r, c) == color_at(i, r, c));
        const double expected = r == 0 && c == 0 ? 0.0 : depth_mm_at(i, r, c) * 0.001;
        CHECK(depth.at<float>(r, c) == Approx(expected));
      }
  }
}

TEST_CASE("sequence layouts: a taken name is refused, naming it") {
  register_test_layout();
  const std::size_t n = SequenceLayouts::instance().entries().size();
  REQUIRE_THROWS_MATCHES(SequenceLayouts::instance().add(frames_txt_entry()), std::invalid_argument,
                         Catch::Message("sequence layouts: a layout named 'test-frames-txt' is registered already"));
  SequenceLayoutEntry icgp = frames_txt_entry();
  icgp.name = "icgp";
  REQUIRE_THROWS_WITH(SequenceLayouts::instance().add(icgp), Contains("'icgp'"));
  CHECK(SequenceLayouts::instance().entries().size() == n);
}

TEST_CASE("sequence layouts: a folder of no layout is refused, listing every layout") {
  register_test_layout();
  TempDir dir("icgp_test_sequence_layouts_unknown");
  REQUIRE_THROWS_WITH(Sequence::open(dir.path().string()),
                      Contains(dir.path().string() + ": unknown sequence layout: looked for sequence.yaml (icgp), "
                               "images/ + depth/ folders (visp-blender), color_image_0000.jpg (visp-realsense) "
                               "and frames.txt (test-frames-txt)"));
}
