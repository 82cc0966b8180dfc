#include "anisodyn/analysis/body_frame_increments.hpp"

#include <cmath>
#include <string>

#include "anisodyn/core/error.hpp"

namespace anisodyn::analysis {

std::vector<Vec3> body_frame_displacements(std::span<const Vec3> centre, std::span<const Quat> orientation) {
  if (centre.size() != orientation.size()) throw InputError("body_frame_displacements: one orientation per position needed");
  std::vector<Vec3> out;
  for (std::size_t n = 1; n < centre.size(); ++n) {
    const Quat mid = orientation[n - 1].slerp(0.5, orientation[n]);
    out.push_back(mid.toRotationMatrix().transpose() * (centre[n] - centre[n - 1]));
  }
  return out;
}

std::vector<Vec3> body_frame_rotation_angles(std::span<const Quat> orientation) {
  std::vector<Vec3> out;
  for (std::size_t n = 1; n < orientation.size(); ++n) {
    const Mat3 before = orientation[n - 1].toRotationMatrix(), after = orientation[n].toRotationMatrix();
    const auto i0 = before.col(0), j0 = before.col(1), k0 = before.col(2);
    const auto i1 = after.col(0), j1 = after.col(1), k1 = after.col(2);
    out.emplace_back(std::atan2(k1.dot(j0), k1.dot(k0)), std::atan2(i1.dot(k0), i1.dot(i0)), std::atan2(j1.dot(i0), j1.dot(j0)));
  }
  return out;
}

std::vector<Vec3> accumulate_path(std::span<const Vec3> increments) {
  std::vector<Vec3> path{Vec3::Zero()};
  for (const Vec3& d : increments) path.push_back(path.back() + d);
  return path;
}

}  // namespace anisodyn::analysis
