// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <cstddef>
#include <string>

namespace icgp {

/// Bounds of a .cao model that icgp hands to ViSP's parser. ViSP's own caps are 100 000
/// records per section; the others keep a hostile file from costing unbounded time.
struct CaoLimits {
  static constexpr std::size_t kMaxRecords = 100000;      ///< per section, as ViSP 3.5
  static constexpr std::size_t kMaxFaceCorners = 4096;    ///< corners of one face
  static constexpr std::size_t kMaxFileBytes = 64 << 20;  ///< one .cao file
  static constexpr std::size_t kMaxFilesLoaded = 256;     ///< files parsed, includes counted each time
  static constexpr std::size_t kMaxLineLength = 255;      ///< after a count's or point's numbers: ViSP skips 256 characters
  static constexpr double kMaxCoordinate = 1e4;           ///< |x|, |y|, |z| and radii, metres
};

/// What a .cao model holds, summed over the file and the files it loads (each load() counts).
struct CaoFileSummary {
  std::size_t files = 0, points = 0, lines = 0, faces = 0, face_corners = 0, cylinders = 0, circles = 0;
};

/// Reads a ViSP .cao file the way ViSP 3.5's vpMbTracker::loadCAOModel does, following its
/// load("...", t=[..], tu=[..]) includes, and throws std::invalid_argument at the first
/// thing that parser would crash on, misread, or throw for: a missing or non-regular file,
/// a malformed number, a count or index out of range, a face with no corner, a point or
/// radius that is not finite or beyond CaoLimits, a degenerate cylinder, an include that is
/// missing, a line too long for ViSP's buffers. The message reads
/// "<file>:<line>: <field>: <value> (expected <range>)". ViSP's parser checks few of these
/// itself (out-of-range indices and empty faces reach memory it does not own), so every
/// .cao file goes through here before it.
CaoFileSummary check_cao_file(const std::string& path);

/// True for a path ending in .cao, in any letter case.
bool is_cao_path(const std::string& path);

}  // namespace icgp
