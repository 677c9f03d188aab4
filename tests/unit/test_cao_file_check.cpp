// SPDX-License-Identifier: GPL-2.0-or-later
// The .cao check that runs before ViSP's parser: it accepts every .cao file ViSP's own data
// and the project ship, counts what they hold, and refuses the inputs that crash or fool
// ViSP's parser with the file, line, field and accepted range.
#include <catch2/catch.hpp>
#include <fstream>

#include "icgp/io/cao_file_check.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "test_temp_dir.h"

using Catch::Matchers::Contains;
using icgp::test::TempDir;

namespace {

// Four corners of a 10 cm square, then the line and face sections.
const std::string kSquarePoints = "V1\n4\n0 0 0\n0.1 0 0\n0.1 0.1 0\n0 0.1 0\n";

std::string refusal(const std::string& path) {
  try {
    icgp::check_cao_file(path);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE("cao check: accepts the shipped ViSP models and counts what they hold") {
  const icgp::CaoFileSummary teabox = icgp::check_cao_file(std::string(ICGP_TEST_DATA_DIR) + "/teabox-blender/teabox.cao");
  CHECK(teabox.files == 1);
  CHECK(teabox.points == 8);
  CHECK(teabox.faces == 6);
  CHECK(teabox.face_corners == 24);
  CHECK(teabox.cylinders == 0);

  // Four includes of one brick, with t= and tu= in deg and rad, and no points of its own.
  const icgp::CaoFileSummary lego =
      icgp::check_cao_file(std::string(ICGP_TEST_DATA_DIR) + "/realsense-cube/models/lego-square/lego-square.cao");
  CHECK(lego.files == 5);
  CHECK(lego.points == 32);
  CHECK(lego.faces == 24);
}

TEST_CASE("cao check: accepts comments, lines, faces from lines, cylinders and circles") {
  const TempDir dir("cao-check");
  const std::string path = dir.write("all.cao", "# a comment before the version\nV1\n# points\n" +
                                                    kSquarePoints.substr(3) +
                                                    "2 # two lines\n0 1 name=\"edge\"\n1 2\n"
                                                    "1\n2 0 1 name=\"from lines\"\n"
                                                    "1\n4 0 1 2 3 # the square\n"
                                                    "1\n0 2 0.01\n"
                                                    "1\n0.02 0 1 3\n");
  const icgp::CaoFileSummary summary = icgp::check_cao_file(path);
  CHECK(summary.lines == 2);
  CHECK(summary.faces == 2);
  CHECK(summary.face_corners == 4 + 4);
  CHECK(summary.cylinders == 1);
  CHECK(summary.circles == 1);
  // ViSP's parser reads it too, and the mesh has the square's two triangles and more.
  CHECK(icgp::load_cao_mesh(path).triangle_count() > 2);
}

TEST_CASE("cao check: refuses what crashes ViSP's parser, naming file, line, field and range") {
  const TempDir dir("cao-check");
  const auto check = [&](const std::string& text, const std::string& expected) {
    const std::string path = dir.write("model.cao", text);
    const std::string message = refusal(path);
    INFO(text);
    CHECK_THAT(message, Contains(path) && Contains(expected));
  };
  check(kSquarePoints + "0\n0\n1\n0\n", ":10: face 0 (face from points) number of points: 0 (expected 2 to 4096)");
  check(kSquarePoints + "0\n0\n1\n4 0 1 2 3\n1\n0 9 0.01\n",
        ":12: cylinder 0 second axis point: 9 (expected an index of the points, 0 to 3)");
  check(kSquarePoints + "0\n0\n1\n4 0 1 2 3\n0\n1\n0.05 0 1 12\n",
        ":13: circle 0 third point: 12 (expected an index of the points, 0 to 3)");
  check(kSquarePoints + "1\n0 7\n1\n2 0 0\n0\n", ":8: line 0 second point: 7 (expected an index of the points, 0 to 3)");
  check(kSquarePoints + "1\n0 1\n1\n2 0 4\n0\n", ":10: face 0 (face from lines) line 1: 4 (expected an index of the lines, 0 to 0)");
  check(kSquarePoints + "0\n0\n1\n4 0 1 2 -3\n", "point 3: '-3' (expected an index of the points, 0 to 3)");
  check(kSquarePoints + "0\n0\n0\n1\n0 0 0.01\n", "cylinder 0 axis: points 0 and 0 coincide");
  check(kSquarePoints + "0\n0\n0\n0\n1\n0.01 0 1 1\n", "circle 0 plane: points 0, 1 and 1 are collinear");
  check(kSquarePoints + "0\n0\n0\n0\n1\n-0.01 0 1 3\n", "circle 0 radius: '-0.01' (expected a decimal number > 0");
  check("V1\n3\n0 0 nan\n1 0 0\n0 1 0\n0\n0\n1\n3 0 1 2\n", ":3: point 0 z: 'nan' (expected a decimal number from -10000");
  check("V1\n3\n0 0 1e999\n1 0 0\n0 1 0\n0\n0\n1\n3 0 1 2\n", "point 0 z: '1e999'");
  check("V1\n100001\n", ":2: number of points: 100001 (expected 1 to 100000)");
  check("V1\n0\n0\n0\n0\n", ":2: number of points: 0 (expected 1 to 100000)");
  check("1\n", ":1: version: '1' (expected 'V1' or 'V2'");
  check(kSquarePoints + "0\n0\n1\n4 0 1 2 3", "face 0 (face from points): the file ends without a line break");
  check(kSquarePoints + "0\n0\n1\n4 0 1 2 3x\n", "face 0 (face from points) point 3: '3x'");
  check(kSquarePoints + "0\n0\n1\n4 0 1 2 3\n0 # " + std::string(300, 'c') + "\n",
        ":11: number of cylinders: the line goes on for 303 characters after its numbers (expected at most 255");
  check(kSquarePoints + "#" + std::string(300, 'c') + "\n0\n0\n0\n", ":7: comment: 301 characters (expected at most 256");
  check(kSquarePoints + "0\n0\n1\n4 0 1 2 3\nrubbish\n", ":11: number of cylinders: 'rubbish' (expected 0 to 100000)");
  check(kSquarePoints + "0\n0\n1\n4 0 1", "face 0 (face from points) point 2: end of file");
  // A '\r' ends a line record in ViSP's parser: "7 9" is line 1, which the face from lines
  // would take its corners from, out of the points array (a crash the fuzzer found).
  check(kSquarePoints + "2\n0 1\r7 9\n1\n1 1\n0\n", ":8: line 1 first point: 7 (expected an index of the points, 0 to 3)");
}

TEST_CASE("cao check: reads line ends as ViSP's parser does: '\\r' ends a record, not a count or a point") {
  const TempDir dir("cao-check");
  // Line 0 ends at the '\r'; the 0 after it is the number of faces from lines, as ViSP reads it.
  const std::string lone_cr = dir.write("lone-cr.cao", kSquarePoints + "1\n0 1\r0\n1\n4 0 1 2 3\n");
  const icgp::CaoFileSummary summary = icgp::check_cao_file(lone_cr);
  CHECK(summary.lines == 1);
  CHECK(summary.faces == 1);
  CHECK(icgp::load_cao_mesh(lone_cr).triangle_count() == 2);

  // A point's line and a count's line are skipped to the '\n': "9 9 9" is no point.
  const std::string skipped = dir.write("skipped.cao", "V1\n4 \r 7\n0 0 0\r9 9 9\n0.1 0 0\n0.1 0.1 0\n0 0.1 0\n0\n0\n1\n4 0 1 2 3\n");
  CHECK(icgp::check_cao_file(skipped).points == 4);
  CHECK(icgp::load_cao_mesh(skipped).triangle_count() == 2);

  // A file saved with Windows line ends reads as the original.
  std::ifstream in(std::string(ICGP_TEST_DATA_DIR) + "/teabox-blender/teabox.cao", std::ios::binary);
  std::string crlf;
  for (char c; in.get(c);) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  const std::string windows = dir.write("teabox-crlf.cao", crlf);
  const icgp::CaoFileSummary teabox = icgp::check_cao_file(windows);
  CHECK(teabox.points == 8);
  CHECK(teabox.faces == 6);
  CHECK(icgp::load_cao_mesh(windows).triangle_count() == 12);
}

TEST_CASE("cao check: load() includes are checked as ViSP resolves them") {
  const TempDir dir("cao-check");
  dir.write("square.cao", kSquarePoints + "0\n0\n1\n4 0 1 2 3\n");
  dir.write("bad.cao", kSquarePoints + "0\n0\n1\n0\n");
  const std::string two = dir.write("two.cao", "V1\nload(\"square.cao\")\nload(\"square.cao\", t=[0.2; 0; 0], tu=[0; 0; 90 deg])\n0\n0\n0\n0\n");
  const icgp::CaoFileSummary summary = icgp::check_cao_file(two);
  CHECK(summary.files == 3);
  CHECK(summary.faces == 2);

  CHECK_THAT(refusal(dir.write("a.cao", "V1\nload(\"bad.cao\")\n0\n0\n0\n0\n")),
             Contains("bad.cao:10: face 0 (face from points) number of points: 0"));
  CHECK_THAT(refusal(dir.write("b.cao", "V1\nload(\"nowhere.cao\")\n0\n0\n0\n0\n")),
             Contains("b.cao:2: load() file: '") && Contains("nowhere.cao' (expected an existing .cao file)"));
  CHECK_THAT(refusal(dir.write("c.cao", "V1\nload(\"d.cao\")\n0\n0\n0\n0\n")), Contains("expected an existing .cao file"));
  dir.write("d.cao", "V1\nload(\"c.cao\")\n0\n0\n0\n0\n");
  CHECK_THAT(refusal(dir.file("c.cao")), Contains("d.cao:2: load() file: 'c.cao' (expected a file that does not load itself"));
  CHECK_THAT(refusal(dir.write("e.cao", "V1\nload(\"square.cao\", t=[0; x; 0])\n0\n0\n0\n0\n")),
             Contains("e.cao:2: load() t: 'x' (expected t=[x; y; z] with three decimal numbers"));
  CHECK_THAT(refusal(dir.write("f.cao", "V1\nload(square.cao)\n0\n0\n0\n0\n")), Contains("f.cao:2: load() file: 'load(square.cao)'"));
}

TEST_CASE("cao check: a model beyond the triangle budget is refused before it is meshed") {
  const TempDir dir("cao-check");
  // 100 000 cylinders of 1024 segments would be 204.8 million triangles.
  std::string text = kSquarePoints + "0\n0\n0\n100000\n";
  for (int i = 0; i < 100000; ++i) text += "0 2 0.01\n";
  const std::string path = dir.write("cylinders.cao", text + "0\n");
  CHECK_THROWS_WITH(icgp::load_cao_mesh(path, icgp::Pose(), icgp::CaoTessellation{1024, 1024}),
                    Contains("would make up to 204800000 triangles (expected at most 10000000)"));
}
