// SPDX-License-Identifier: GPL-2.0-or-later
// What the sequence layouts, their depth codecs and Sequence share to find, check and read
// a sequence's files. Every failure throws std::runtime_error "<file>: <what>".
#pragma once

#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "icgp/base/pose.h"

namespace icgp {

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& what);

/// "640x480".
std::string size_text(int width, int height);

std::string read_text_file(const std::filesystem::path& path);

/// Fails "missing <what>" unless `path` is a regular file.
void require_file(const std::filesystem::path& path, const std::string& what);

/// "prefix" + index zero-padded to `digits` + "suffix", e.g. ("Image", 7, 4, ".exr").
std::string numbered(const std::string& prefix, int index, int digits, const std::string& suffix);

/// Number of frames named prefix + %0<digits>d + suffix in `folder`, numbered contiguously
/// from `first`. A gap would silently shorten the sequence, so it is an error naming the
/// first missing file.
int count_numbered_files(const std::filesystem::path& folder, const std::string& prefix, int digits,
                         const std::string& suffix, int first);

/// Parses whitespace-separated numbers of one line, requiring exactly `expected` of them.
std::vector<double> parse_numbers(const std::string& line, std::size_t expected, const std::filesystem::path& file,
                                  int line_no);

bool is_blank(const std::string& line);

/// A rigid transform from 16 row-major numbers; `where` prefixes the messages ("line 3: ").
Pose pose_from_row_major(const std::vector<double>& v, const std::filesystem::path& file, const std::string& where);

/// A colour image (BGR), refusing a JPEG cut short.
cv::Mat read_color_image(const std::filesystem::path& path);

}  // namespace icgp
