#include "anisodyn/system/lab_extents.hpp"

namespace anisodyn {

std::vector<Vec3> mean_lab_half_extents(const State& state) {
  const Particles& p = state.particles;
  const std::size_t ns = state.species.size();
  std::vector<Vec3> sum(ns, Vec3::Zero());
  std::vector<double> count(ns, 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto s = static_cast<std::size_t>(p.species[i]);
    sum[s] += state.species[s].shape.lab_half_extents(p.orientation(i).toRotationMatrix());
    count[s] += 1.0;
  }
  for (std::size_t s = 0; s < ns; ++s)
    sum[s] = count[s] > 0.0 ? Vec3(sum[s] / count[s]) : Vec3::Constant(state.species[s].shape.circumradius());
  return sum;
}

}  // namespace anisodyn
