// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <string>

namespace icgp {

/// Pinhole camera without distortion, in the ViSP/OpenCV pixel convention: the centre of
/// the pixel in column j and row i is at image coordinates (u, v) = (j, i).
/// Camera frame: x right, y down, z forward (ViSP's convention).
struct Intrinsics {
  double fu = 0.0;  ///< focal length in pixels along u (ViSP px)
  double fv = 0.0;  ///< focal length in pixels along v (ViSP py)
  double pu = 0.0;  ///< principal point u (ViSP u0)
  double pv = 0.0;  ///< principal point v (ViSP v0)
  int width = 0;
  int height = 0;

  /// A camera of the given size and focal length with the principal point at the image
  /// centre ((width - 1) / 2, (height - 1) / 2 in the pixel-centre convention).
  static Intrinsics centred(int width, int height, double focal) {
    return {focal, focal, (width - 1) / 2.0, (height - 1) / 2.0, width, height};
  }

  /// Throws std::invalid_argument naming `what` when focal lengths or the image size are
  /// not positive and finite.
  void validate(const std::string& what = "intrinsics") const;

  /// pi(X) = [X fu / Z + pu, Y fv / Z + pv] (ALGORITHMS.md §1). Z must be > 0.
  template <typename T>
  Eigen::Matrix<T, 2, 1> project(const Eigen::Matrix<T, 3, 1>& X) const {
    return {X.x() * T(fu) / X.z() + T(pu), X.y() * T(fv) / X.z() + T(pv)};
  }

  /// The 3D point at depth Z (along the optical axis) seen at image coordinates (u, v).
  template <typename T>
  Eigen::Matrix<T, 3, 1> back_project(T u, T v, T Z) const {
    return {(u - T(pu)) * Z / T(fu), (v - T(pv)) * Z / T(fv), Z};
  }

  /// d pi / d X (2x3) at X.
  template <typename T>
  Eigen::Matrix<T, 2, 3> projection_jacobian(const Eigen::Matrix<T, 3, 1>& X) const {
    const T iz = T(1) / X.z();
    Eigen::Matrix<T, 2, 3> J;
    J << T(fu) * iz, T(0), -T(fu) * X.x() * iz * iz,  //
        T(0), T(fv) * iz, -T(fv) * X.y() * iz * iz;
    return J;
  }

  /// True when (u, v) lies on a pixel of the image (pixel areas extend ±0.5 around centres).
  bool contains(double u, double v) const {
    return u >= -0.5 && v >= -0.5 && u < width - 0.5 && v < height - 0.5;
  }

  /// Intrinsics of a rectangular crop of this image [u_min, u_min + crop_width) x
  /// [v_min, v_min + crop_height) (in pixel-edge coordinates: the crop starts on the edge
  /// of pixel u_min) resampled to out_width x out_height pixels. Used for focused renders.
  Intrinsics cropped(double u_min, double v_min, double crop_width, double crop_height, int out_width,
                     int out_height) const;

  /// Same camera at another image size (scales focal lengths and principal point with the
  /// pixel-centre convention preserved).
  Intrinsics scaled(int out_width, int out_height) const;
};

}  // namespace icgp
