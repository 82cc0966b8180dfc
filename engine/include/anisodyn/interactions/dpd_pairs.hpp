#pragma once
// The Groot–Warren DPD pair forces between liquid particles (spec 30 §2), as a pair evaluator for
// accumulate_pair_forces / PairForceField. For r = |r_i − r_j| < r_c, r̂ = (r_i − r_j)/r,
// v_ij = v_i − v_j and w = 1 − r/r_c, the force on i is the sum of three parts:
//
//   conservative  F^C = a w r̂                          (pair energy a r_c w²/2)
//   dissipative   F^D = −γ w² (r̂·v_ij) r̂
//   random        F^R = √(2 γ kT) w θ_ij Δt^{−1/2} r̂
//
// θ_ij is a unit normal from the keyed generator (core/keyed_random.hpp), addressed by the noise
// step and the two particles' ids: the same for (i, j) and (j, i), whatever the thread count or the
// order of the pairs. Every part is odd under exchanging i and j to the last bit (d and v_ij change
// sign exactly, r and r̂·v_ij do not), so each pair is evaluated once and Newton's third law holds
// pair by pair: the total momentum changes only by the rounding of the kicks.
//
// The velocities are those in the state when the forces are evaluated: in velocity Verlet the
// half-step ones, which is LAMMPS's scheme and Groot–Warren's with λ = ½ (docs/dpd.md).
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "anisodyn/core/keyed_random.hpp"
#include "anisodyn/interactions/pair_forces.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

/// The liquid's DPD parameters (spec 30 §2 in reduced units: r_c = m = kT = 1).
struct DpdParameters {
  double a = 25.0;      // conservative repulsion
  double gamma = 4.5;   // dissipative friction
  double kT = 1.0;
  double cutoff = 1.0;  // r_c
};

/// Purpose tag of the DPD pair noise in the keyed generator (other noises of a run take others).
inline constexpr std::uint64_t kDpdPairNoise = 0x44504450414952ULL;  // "DPDPAIR"

struct DpdPairs {
  static constexpr int kParts = 3;  // conservative, dissipative, random
  static constexpr bool kOncePerPair = true;

  DpdParameters p;
  double dt = 0.0;
  KeyedRandom noise{0, kDpdPairNoise};
  std::vector<char> liquid;     // per species: 1 if it takes part in the DPD pairs
  std::uint64_t noise_step = 0;  // the counter of the draws; the engine sets it before each evaluation

  // Refreshed by prepare(): views into the state being evaluated.
  const std::int32_t* species = nullptr;
  const std::int64_t* id = nullptr;
  const double *vx = nullptr, *vy = nullptr, *vz = nullptr;

  DpdPairs(DpdParameters params, double time_step, std::uint64_t seed, std::vector<char> liquid_species)
      : p(params), dt(time_step), noise(seed, kDpdPairNoise), liquid(std::move(liquid_species)) {}

  /// Verlet-list cut-offs: r_c between liquid species, 0 otherwise.
  std::vector<double> cutoffs() const {
    const std::size_t ns = liquid.size();
    std::vector<double> c(ns * ns, 0.0);
    for (std::size_t a = 0; a < ns; ++a)
      for (std::size_t b = 0; b < ns; ++b) c[a * ns + b] = liquid[a] && liquid[b] ? p.cutoff : 0.0;
    return c;
  }

  void prepare(const State& s) {
    species = s.particles.species.data();
    id = s.particles.id.data();
    vx = s.particles.vx.data();
    vy = s.particles.vy.data();
    vz = s.particles.vz.data();
  }

  PairTerm<3> operator()(std::size_t i, std::size_t j, const Vec3& d, double r2) const {
    PairTerm<3> t;
    if (r2 >= p.cutoff * p.cutoff || !liquid[static_cast<std::size_t>(species[i])] || !liquid[static_cast<std::size_t>(species[j])])
      return t;
    const double r = std::sqrt(r2);
    const Vec3 rhat = -d / r;  // d = r_j − r_i, so r̂ = (r_i − r_j)/r
    const double w = 1.0 - r / p.cutoff;
    const Vec3 vij(vx[i] - vx[j], vy[i] - vy[j], vz[i] - vz[j]);
    const double theta = noise.pair_normal(noise_step, static_cast<std::uint64_t>(id[i]), static_cast<std::uint64_t>(id[j]));
    t.interacts = true;
    t.energy = 0.5 * p.a * p.cutoff * w * w;
    t.force[0] = (p.a * w) * rhat;
    t.force[1] = (-p.gamma * w * w * rhat.dot(vij)) * rhat;
    t.force[2] = (std::sqrt(2.0 * p.gamma * p.kT / dt) * w * theta) * rhat;
    return t;
  }
};

}  // namespace anisodyn
