#pragma once
// Fixed-size linear-algebra types used throughout anisodyn (Eigen, double precision).
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace anisodyn {
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Int3 = Eigen::Vector3i;
/// Unit quaternion mapping body to lab frame; stored (w, x, y, z) in files, as H5MD expects.
using Quat = Eigen::Quaterniond;
}  // namespace anisodyn
