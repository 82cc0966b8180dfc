#include "anisodyn/system/order.hpp"

#include <Eigen/Eigenvalues>

#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/core/rng.hpp"

namespace anisodyn {

Mat3 q_tensor(const std::vector<Vec3>& axes) {
  Mat3 q = Mat3::Zero();
  for (const Vec3& e : axes) q += 3.0 * e * e.transpose() - Mat3::Identity();
  return axes.empty() ? q : q / (2.0 * static_cast<double>(axes.size()));
}

UniaxialOrder uniaxial_order(const Mat3& q) {
  Eigen::SelfAdjointEigenSolver<Mat3> solver(q);
  UniaxialOrder out;
  out.eigenvalues = solver.eigenvalues();
  out.order = out.eigenvalues[2];
  out.director = solver.eigenvectors().col(2);
  return out;
}

std::array<UniaxialOrder, 3> body_axis_order(const State& state, int species) {
  std::array<std::vector<Vec3>, 3> axes;
  const Particles& p = state.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.species[i] != species) continue;
    const Mat3 r = p.orientation(i).toRotationMatrix();
    for (int k = 0; k < 3; ++k) axes[static_cast<std::size_t>(k)].push_back(r.col(k));
  }
  std::array<UniaxialOrder, 3> out;
  for (std::size_t k = 0; k < 3; ++k) out[k] = uniaxial_order(q_tensor(axes[k]));
  return out;
}

double isotropic_order_baseline(std::size_t n, int samples) {
  Rng rng(0x15070, n);
  double sum = 0.0;
  std::vector<Vec3> axes(n);
  for (int s = 0; s < samples; ++s) {
    for (auto& e : axes) e = uniform_quaternion(rng.uniform(), rng.uniform(), rng.uniform()).toRotationMatrix().col(2);
    sum += uniaxial_order(q_tensor(axes)).order;
  }
  return sum / samples;
}

}  // namespace anisodyn
