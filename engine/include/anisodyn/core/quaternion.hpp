#pragma once
// Rotation helpers. Orientation quaternions map body to lab; the columns of the rotation matrix are
// the body axes in the lab frame (for cuboids: ê_T, ê_W, ê_L).
#include <cmath>

#include "anisodyn/core/types.hpp"

namespace anisodyn {

/// Quaternion of the rotation by |theta| about theta/|theta| (the exponential map).
inline Quat quat_from_rotation_vector(const Vec3& theta) {
  const double angle = theta.norm();
  if (angle < 1e-8) {
    // Second-order Taylor expansion keeps the small-angle map accurate and smooth at zero.
    const Vec3 v = 0.5 * theta;
    Quat q(1.0 - v.squaredNorm() / 2.0, v.x(), v.y(), v.z());
    return q.normalized();
  }
  const double s = std::sin(0.5 * angle) / angle;
  return Quat(std::cos(0.5 * angle), s * theta.x(), s * theta.y(), s * theta.z());
}

/// Rotates q by a rotation vector given in q's body frame: O' = O · exp([theta]_x).
inline Quat rotate_in_body_frame(const Quat& q, const Vec3& theta_body) {
  return (q * quat_from_rotation_vector(theta_body)).normalized();
}

/// Rotates q by a rotation vector given in the lab frame: O' = exp([theta]_x) · O.
inline Quat rotate_in_lab_frame(const Quat& q, const Vec3& theta_lab) {
  return (quat_from_rotation_vector(theta_lab) * q).normalized();
}

/// Uniform random rotation (Shoemake 1992) from three uniforms in [0, 1).
inline Quat uniform_quaternion(double u1, double u2, double u3) {
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const double t1 = 2.0 * M_PI * u2, t2 = 2.0 * M_PI * u3;
  return Quat(b * std::cos(t2), a * std::sin(t1), a * std::cos(t1), b * std::sin(t2));
}

/// Minimal rotation taking unit vector `from` onto unit vector `to`.
inline Quat quat_aligning(const Vec3& from, const Vec3& to) {
  return Quat::FromTwoVectors(from, to);
}

}  // namespace anisodyn
