// SPDX-License-Identifier: GPL-2.0-or-later
#include "numpy_conversions.h"

#include <cmath>
#include <cstring>
#include <opencv2/imgproc.hpp>

namespace icgp::python {
namespace {

std::string shape_text(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i) text += (i ? ", " : "") + std::to_string(array.shape(i));
  return text + (array.ndim() == 1 ? ",)" : ")");
}

bool c_contiguous(const py::array& array) { return (array.flags() & py::array::c_style) != 0; }

/// A Mat over the array's memory (C-contiguous arrays only).
cv::Mat wrap(const py::array& array, int type) {
  return cv::Mat(static_cast<int>(array.shape(0)), static_cast<int>(array.shape(1)), type,
                 const_cast<void*>(array.data()));
}

/// The array as doubles of exactly `rows` x `cols`.
Eigen::MatrixXd dense_matrix(const py::handle& object, int rows, int cols, const char* argument) {
  // ensure() converts what NumPy can, and returns null (the Python error cleared) otherwise.
  const auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(object);
  if (!array) throw py::type_error(std::string(argument) + ": expected a " + std::to_string(rows) + "x" +
                                   std::to_string(cols) + " array of numbers");
  if (array.ndim() != 2 || array.shape(0) != rows || array.shape(1) != cols)
    throw py::value_error(std::string(argument) + ": expected shape (" + std::to_string(rows) + ", " +
                          std::to_string(cols) + "), got " + shape_text(array));
  Eigen::MatrixXd m(rows, cols);
  const auto values = array.unchecked<2>();  // shape checked above
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      m(r, c) = values(r, c);
      if (!std::isfinite(m(r, c))) throw py::value_error(std::string(argument) + ": expected finite numbers, got " +
                                                         py::repr(py::float_(m(r, c))).cast<std::string>() + " at [" +
                                                         std::to_string(r) + ", " + std::to_string(c) + "]");
    }
  return m;
}

void check_image_size(const py::array& array, const char* argument) {
  constexpr py::ssize_t kMaxSide = 16384;  // the largest image any camera here delivers
  if (array.shape(0) < 1 || array.shape(1) < 1 || array.shape(0) > kMaxSide || array.shape(1) > kMaxSide)
    throw py::value_error(std::string(argument) + ": expected an image of 1 to 16384 pixels a side, got shape " +
                          shape_text(array));
}

}  // namespace

ColorOrder color_order(const std::string& name) {
  if (name == "bgr") return ColorOrder::kBgr;
  if (name == "rgb") return ColorOrder::kRgb;
  throw py::value_error("color_order: expected 'bgr' or 'rgb', got '" + name + "'");
}

cv::Mat color_image(const py::array& array, const char* argument, ColorOrder order) {
  const bool grey = array.ndim() == 2;
  if (!(grey || (array.ndim() == 3 && array.shape(2) == 3)))
    throw py::value_error(std::string(argument) + ": expected shape (H, W, 3) or (H, W), got " + shape_text(array));
  if (!py::isinstance<py::array_t<std::uint8_t>>(array))
    throw py::value_error(std::string(argument) + ": expected dtype uint8, got " +
                          py::str(array.dtype()).cast<std::string>());
  check_image_size(array, argument);
  const int type = grey ? CV_8UC1 : CV_8UC3;
  cv::Mat image;
  if (c_contiguous(array)) {
    image = wrap(array, type);
  } else {
    const auto copy = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(array);
    wrap(copy, type).copyTo(image);
  }
  if (!grey && order == ColorOrder::kRgb) {
    cv::Mat bgr;
    cv::cvtColor(image, bgr, cv::COLOR_RGB2BGR);
    return bgr;
  }
  return image;
}

cv::Mat depth_image(const py::array& array, const char* argument, double depth_scale) {
  if (array.ndim() != 2) throw py::value_error(std::string(argument) + ": expected shape (H, W), got " + shape_text(array));
  check_image_size(array, argument);
  if (py::isinstance<py::array_t<float>>(array)) {
    if (c_contiguous(array)) return wrap(array, CV_32FC1);
    cv::Mat copy;
    wrap(py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(array), CV_32FC1).copyTo(copy);
    return copy;
  }
  if (py::isinstance<py::array_t<double>>(array)) {
    cv::Mat depth;
    wrap(py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array), CV_64FC1).convertTo(depth, CV_32F);
    return depth;
  }
  if (py::isinstance<py::array_t<std::uint16_t>>(array)) {
    if (!(depth_scale > 0.0 && std::isfinite(depth_scale)))
      throw py::value_error("depth_scale: expected a positive number of metres per depth unit, got " +
                            py::repr(py::float_(depth_scale)).cast<std::string>());
    cv::Mat depth;
    wrap(py::array_t<std::uint16_t, py::array::c_style | py::array::forcecast>::ensure(array), CV_16UC1)
        .convertTo(depth, CV_32F, depth_scale);
    return depth;
  }
  throw py::value_error(std::string(argument) + ": expected dtype float32 or float64 (metres) or uint16 (times depth_scale), got " +
                        py::str(array.dtype()).cast<std::string>());
}

Pose pose(const py::handle& object, const char* argument) {
  const Eigen::Matrix4d T = dense_matrix(object, 4, 4, argument);
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  const bool rotation = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-6 && R.determinant() > 0.0;
  const bool last_row = T.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1), 0.0);
  if (!rotation || !last_row)
    throw py::value_error(std::string(argument) +
                          ": expected a homogeneous transform (a rotation in the upper-left 3x3, last row 0 0 0 1)");
  // Taken as given, as the command line takes a pose file: the same matrix gives the same result.
  return Pose(T);
}

py::array_t<double> matrix(const Pose& pose) {
  py::array_t<double> out({4, 4});
  const Eigen::Matrix4d T = pose.matrix();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out.mutable_at(r, c) = T(r, c);
  return out;
}

Intrinsics intrinsics(const py::handle& object, int width, int height, const char* argument) {
  const Eigen::Matrix3d K = dense_matrix(object, 3, 3, argument);
  if (K(0, 1) != 0.0 || K(1, 0) != 0.0 || K(2, 0) != 0.0 || K(2, 1) != 0.0 || K(2, 2) != 1.0)
    throw py::value_error(std::string(argument) + ": expected a camera matrix [[fu, 0, pu], [0, fv, pv], [0, 0, 1]]");
  Intrinsics k{K(0, 0), K(1, 1), K(0, 2), K(1, 2), width, height};
  try {
    k.validate(argument);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
  return k;
}

py::array_t<double> camera_matrix(const Intrinsics& k) {
  py::array_t<double> out({3, 3});
  const double values[9] = {k.fu, 0.0, k.pu, 0.0, k.fv, k.pv, 0.0, 0.0, 1.0};
  for (int i = 0; i < 9; ++i) out.mutable_at(i / 3, i % 3) = values[i];
  return out;
}

py::array image_array(const cv::Mat& image) {
  std::vector<py::ssize_t> shape{image.rows, image.cols};
  if (image.channels() > 1) shape.push_back(image.channels());
  const cv::Mat dense = image.isContinuous() ? image : image.clone();
  switch (image.depth()) {
    case CV_8U: {
      py::array_t<std::uint8_t> out(shape);
      std::memcpy(out.mutable_data(), dense.data, dense.total() * dense.elemSize());
      return out;
    }
    case CV_16U: {
      py::array_t<std::uint16_t> out(shape);
      std::memcpy(out.mutable_data(), dense.data, dense.total() * dense.elemSize());
      return out;
    }
    case CV_32F: {
      py::array_t<float> out(shape);
      std::memcpy(out.mutable_data(), dense.data, dense.total() * dense.elemSize());
      return out;
    }
    default:
      throw std::logic_error("image_array: an image of OpenCV depth " + std::to_string(image.depth()));
  }
}

}  // namespace icgp::python
