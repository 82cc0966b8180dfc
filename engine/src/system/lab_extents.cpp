#include "anisodyn/system/lab_extents.hpp"

namespace anisodyn {

namespace {

template <class Rotation>
std::vector<Vec3> species_means(const State& state, const Rotation& rotation) {
  const Particles& p = state.particles;
  const std::size_t ns = state.species.size();
  std::vector<Vec3> sum(ns, Vec3::Zero());
  std::vector<double> count(ns, 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto s = static_cast<std::size_t>(p.species[i]);
    sum[s] += state.species[s].shape.lab_half_extents(rotation(i));
    count[s] += 1.0;
  }
  for (std::size_t s = 0; s < ns; ++s)
    sum[s] = count[s] > 0.0 ? Vec3(sum[s] / count[s]) : Vec3::Constant(state.species[s].shape.circumradius());
  return sum;
}

}  // namespace

std::vector<Vec3> mean_lab_half_extents(const State& state) {
  return species_means(state, [&](std::size_t i) { return Mat3(state.particles.orientation(i).toRotationMatrix()); });
}

std::vector<Vec3> mean_lab_half_extents(const State& state, const std::vector<Mat3>& rotations) {
  return species_means(state, [&](std::size_t i) -> const Mat3& { return rotations[i]; });
}

}  // namespace anisodyn
