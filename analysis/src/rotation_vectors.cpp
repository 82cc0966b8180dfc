#include "anisodyn/analysis/rotation_vectors.hpp"

#include <algorithm>
#include <cmath>

namespace anisodyn::analysis {

RotationVectorPath rotation_vector_path(const Trajectory& t, int axis) {
  RotationVectorPath out;
  const std::size_t F = t.frames, N = t.particles;
  out.phi.assign(3 * F * N, 0.0);
  const auto it = t.elements.find("rotation_vector");
  if (it != t.elements.end() && it->second.first == 9) {
    out.exact = true;
    for (std::size_t f = 0; f < F; ++f)
      for (std::size_t i = 0; i < N; ++i)
        for (int a = 0; a < 3; ++a) out.phi[3 * (f * N + i) + a] = it->second.second[9 * (f * N + i) + 3 * axis + a];
    return out;
  }
  for (std::size_t f = 1; f < F; ++f)
    for (std::size_t i = 0; i < N; ++i) {
      const Vec3 u0 = t.axis(f - 1, i, axis), u1 = t.axis(f, i, axis);
      const Vec3 c = u0.cross(u1);
      const double s = c.norm();
      const double angle = std::atan2(s, std::clamp(u0.dot(u1), -1.0, 1.0));
      const Vec3 step = s > 0 ? Vec3(c / s * angle) : Vec3::Zero();
      ++out.intervals;
      if (angle > kMaxFrameRotation) ++out.violations;
      for (int a = 0; a < 3; ++a) out.phi[3 * (f * N + i) + a] = out.phi[3 * ((f - 1) * N + i) + a] + step[a];
    }
  return out;
}

}  // namespace anisodyn::analysis
