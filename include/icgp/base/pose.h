// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace icgp {

/// pi to double precision (std::numbers::pi is C++20; M_PI is POSIX, not C++).
constexpr double kPi = 3.14159265358979323846;

/// Degrees to radians, as degrees * pi / 180 (in that order, so results stay bit for bit).
constexpr double deg_to_rad(double degrees) { return degrees * kPi / 180.0; }

/// Skew-symmetric matrix [v]x, so that skew(a) * b == a.cross(b).
template <typename T>
Eigen::Matrix<T, 3, 3> skew(const Eigen::Matrix<T, 3, 1>& v) {
  Eigen::Matrix<T, 3, 3> m;
  m << T(0), -v.z(), v.y(), v.z(), T(0), -v.x(), -v.y(), v.x(), T(0);
  return m;
}

/// Exponential map of so(3) (Rodrigues' formula), with a Taylor expansion near zero.
template <typename T>
Eigen::Matrix<T, 3, 3> exp_so3(const Eigen::Matrix<T, 3, 1>& w) {
  const T angle2 = w.squaredNorm();
  const Eigen::Matrix<T, 3, 3> K = skew(w);
  T a, b;  // sin(t)/t and (1 - cos(t))/t^2
  if (angle2 < T(1e-10)) {
    a = T(1) - angle2 / T(6);
    b = T(0.5) - angle2 / T(24);
  } else {
    const T angle = std::sqrt(angle2);
    a = std::sin(angle) / angle;
    b = (T(1) - std::cos(angle)) / angle2;
  }
  return Eigen::Matrix<T, 3, 3>::Identity() + a * K + b * K * K;
}

/// A rigid transform a_T_b in SE(3): maps points expressed in frame b into frame a,
/// X_a = R X_b + t. Names in the code follow the same convention (camera_T_body, ...).
template <typename T>
class PoseT {
 public:
  using Scalar = T;
  using Vec3 = Eigen::Matrix<T, 3, 1>;
  using Mat3 = Eigen::Matrix<T, 3, 3>;
  using Mat4 = Eigen::Matrix<T, 4, 4>;
  using Vec6 = Eigen::Matrix<T, 6, 1>;

  PoseT() : R_(Mat3::Identity()), t_(Vec3::Zero()) {}
  PoseT(const Mat3& rotation, const Vec3& translation) : R_(rotation), t_(translation) {}
  explicit PoseT(const Mat4& m) : R_(m.template topLeftCorner<3, 3>()), t_(m.template topRightCorner<3, 1>()) {}

  static PoseT identity() { return PoseT(); }
  /// Pose from a rotation vector (theta u, radians) and a translation.
  static PoseT from_rotation_vector(const Vec3& theta_u, const Vec3& translation) {
    return PoseT(exp_so3(theta_u), translation);
  }

  const Mat3& rotation() const { return R_; }
  const Vec3& translation() const { return t_; }
  Mat4 matrix() const {
    Mat4 m = Mat4::Identity();
    m.template topLeftCorner<3, 3>() = R_;
    m.template topRightCorner<3, 1>() = t_;
    return m;
  }

  PoseT inverse() const {
    const Mat3 Rt = R_.transpose();
    return PoseT(Rt, -(Rt * t_));
  }
  PoseT operator*(const PoseT& other) const { return PoseT(R_ * other.R_, R_ * other.t_ + t_); }
  Vec3 operator*(const Vec3& point) const { return R_ * point + t_; }

  /// Applies a small variation theta = [theta_r; theta_t] expressed in the right-hand
  /// (body) frame: this <- this * [exp([theta_r]x), theta_t; 0, 1] (ALGORITHMS.md §1).
  PoseT updated_in_body_frame(const Vec6& theta) const {
    return *this * PoseT(exp_so3<T>(theta.template head<3>()), theta.template tail<3>());
  }

  template <typename U>
  PoseT<U> cast() const {
    return PoseT<U>(R_.template cast<U>(), t_.template cast<U>());
  }

 private:
  Mat3 R_;
  Vec3 t_;
};

using Pose = PoseT<double>;
using Posef = PoseT<float>;

/// Geodesic rotation distance in radians: the angle of a^T b, robust near 0 and 180 deg.
template <typename T>
T rotation_angle_between(const Eigen::Matrix<T, 3, 3>& a, const Eigen::Matrix<T, 3, 3>& b) {
  const Eigen::Matrix<T, 3, 3> d = a.transpose() * b;
  // atan2 of |axis part| and cos part stays accurate at both ends, unlike acos((tr-1)/2).
  const Eigen::Matrix<T, 3, 1> s(d(2, 1) - d(1, 2), d(0, 2) - d(2, 0), d(1, 0) - d(0, 1));
  return std::atan2(T(0.5) * s.norm(), T(0.5) * (d.trace() - T(1)));
}

/// d(camera_X)/d(theta) for a body-frame variation of camera_T_body (ALGORITHMS.md §1):
/// camera_R_body * [ -[body_X]x , I3 ]  (3x6).
template <typename T>
Eigen::Matrix<T, 3, 6> point_jacobian_body_variation(const Eigen::Matrix<T, 3, 3>& camera_R_body,
                                                     const Eigen::Matrix<T, 3, 1>& body_X) {
  Eigen::Matrix<T, 3, 6> J;
  J.template leftCols<3>() = -camera_R_body * skew(body_X);
  J.template rightCols<3>() = camera_R_body;
  return J;
}

/// camera_T_world of a camera at `eye` looking at `target` (ViSP camera frame: z forward,
/// y down), with the image's up direction as close to `up` as the view allows.
/// `up` must not be parallel to the viewing direction.
template <typename T>
PoseT<T> look_at(const Eigen::Matrix<T, 3, 1>& eye, const Eigen::Matrix<T, 3, 1>& target,
                 const Eigen::Matrix<T, 3, 1>& up) {
  const Eigen::Matrix<T, 3, 1> z = (target - eye).normalized();
  const Eigen::Matrix<T, 3, 1> x = z.cross(up).normalized();  // = y × z with y along -up
  const Eigen::Matrix<T, 3, 1> y = z.cross(x);
  Eigen::Matrix<T, 3, 3> world_R_camera;
  world_R_camera << x, y, z;
  return PoseT<T>(world_R_camera, eye).inverse();
}

}  // namespace icgp
