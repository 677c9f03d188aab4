// SPDX-License-Identifier: GPL-2.0-or-later
// NumPy arrays to and from icgp's types: images (without copying when the array already
// has the layout the tracker reads), 4x4 poses and 3x3 camera matrices. Every check names
// the argument and says what was expected, as a Python ValueError or TypeError.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <opencv2/core/mat.hpp>
#include <string>

#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"

namespace icgp::python {

namespace py = pybind11;

/// The channel order of a colour array.
enum class ColorOrder { kBgr, kRgb };
ColorOrder color_order(const std::string& name);

/// A colour image as the tracker reads it (CV_8UC3 BGR or CV_8UC1 grey). A C-contiguous
/// uint8 array of shape (H, W, 3) in BGR order or (H, W) is wrapped without a copy: keep the
/// array alive while the Mat is used. Other layouts, and RGB, are converted.
cv::Mat color_image(const py::array& array, const char* argument, ColorOrder order);
/// A depth image in metres (CV_32FC1; 0, negative, NaN and inf mean no measurement). A
/// C-contiguous float32 (H, W) array is wrapped without a copy; float64 is converted;
/// uint16 is multiplied by `depth_scale` (metres per unit, 0 staying no measurement).
cv::Mat depth_image(const py::array& array, const char* argument, double depth_scale);

/// A 4x4 homogeneous transform (a rotation in its upper-left 3x3 to 1e-6, last row 0 0 0 1).
Pose pose(const py::handle& matrix, const char* argument);
py::array_t<double> matrix(const Pose& pose);

/// A pinhole camera from a 3x3 matrix [[fu, 0, pu], [0, fv, pv], [0, 0, 1]] (no skew) and
/// the size of the image it belongs to.
Intrinsics intrinsics(const py::handle& K, int width, int height, const char* argument);
py::array_t<double> camera_matrix(const Intrinsics& intrinsics);

/// A cv::Mat (8-bit BGR or grey, 16-bit or float depth) as a NumPy array (a copy).
py::array image_array(const cv::Mat& image);

}  // namespace icgp::python
