#pragma once
// The pseudo-hard sphere core: the Mie(n, m) potential cut at its minimum and shifted up by ε, a
// steep, purely repulsive stand-in for hard spheres (spec 30 §4.1 uses n = 50, m = 49):
//
//   U(r) = C ε [(σ/r)ⁿ − (σ/r)ᵐ] + ε  for r < r_min = (n/m)^{1/(n−m)} σ, else 0,
//   C = (n/(n−m)) (n/m)^{m/(n−m)}     (so that the unshifted minimum is −ε).
//
// As n grows at a fixed Barker–Henderson diameter d_BH = ∫₀^∞ (1 − e^{−βU}) dr, the fluid tends to
// hard spheres of diameter d_BH; BD runs at several n extrapolate to the hard limit (docs/bd.md).
// Between spheres of species a and b, σ_ab = (σ_a + σ_b)/2; species with σ = 0 do not interact.
#include <cmath>
#include <cstddef>
#include <vector>

#include "anisodyn/interactions/pair_forces.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

struct MieCore {
  double n = 50.0, m = 49.0;  // repulsive and attractive exponents, n > m > 0
  double epsilon = 1.0;       // energy

  double prefactor() const { return n / (n - m) * std::pow(n / m, m / (n - m)); }
  /// r_min / σ, where the cut, shifted potential reaches 0.
  double cutoff_ratio() const { return std::pow(n / m, 1.0 / (n - m)); }
  /// U(r) for contact parameter σ (0 at and beyond r_min).
  double energy(double r, double sigma) const {
    if (r >= cutoff_ratio() * sigma) return 0.0;
    const double s = sigma / r;
    return prefactor() * epsilon * (std::pow(s, n) - std::pow(s, m)) + epsilon;
  }
  /// −dU/dr (> 0: repulsive) for r < r_min, else 0.
  double force(double r, double sigma) const {
    if (r >= cutoff_ratio() * sigma) return 0.0;
    const double s = sigma / r;
    return prefactor() * epsilon * (n * std::pow(s, n) - m * std::pow(s, m)) / r;
  }
};

/// d_BH / σ = ∫₀^{r_min/σ} (1 − e^{−βU(xσ)}) dx, by composite Simpson on a fine grid (the
/// integrand is 1 below x ≈ 0.8 and smooth up to the cut, where it vanishes with U).
double barker_henderson_ratio(const MieCore& core, double kT);

/// Mie cores between the spheres of the interacting species, as a pair evaluator for
/// accumulate_pair_forces / PairForceField.
struct MiePairs {
  static constexpr int kParts = 1;
  // The term of (j, i) is exactly the negated force and the same energy: d changes sign and r2 does
  // not, so the loop evaluates each pair once (interactions/pair_forces.hpp), with the same sums.
  static constexpr bool kOncePerPair = true;
  MieCore core;
  std::vector<double> sigma;  // per species; 0: not interacting
  std::vector<int> species;   // of each particle, refreshed by prepare()

  double pair_sigma(int a, int b) const {
    const double sa = sigma[static_cast<std::size_t>(a)], sb = sigma[static_cast<std::size_t>(b)];
    return sa > 0.0 && sb > 0.0 ? 0.5 * (sa + sb) : 0.0;
  }
  /// Verlet-list cut-offs: r_min of each interacting species pair, 0 otherwise.
  std::vector<double> cutoffs() const {
    const std::size_t ns = sigma.size();
    std::vector<double> c(ns * ns, 0.0);
    for (std::size_t a = 0; a < ns; ++a)
      for (std::size_t b = 0; b < ns; ++b) c[a * ns + b] = core.cutoff_ratio() * pair_sigma(static_cast<int>(a), static_cast<int>(b));
    return c;
  }
  void prepare(const State& s) { species.assign(s.particles.species.begin(), s.particles.species.end()); }

  PairTerm<1> operator()(std::size_t i, std::size_t j, const Vec3& d, double r2) const {
    PairTerm<1> t;
    const double sig = pair_sigma(species[i], species[j]);
    const double rc = core.cutoff_ratio() * sig;
    if (sig == 0.0 || r2 >= rc * rc) return t;
    const double r = std::sqrt(r2);
    t.interacts = true;
    t.energy = core.energy(r, sig);
    t.force[0] = (-core.force(r, sig) / r) * d;  // d = r_j − r_i: pushed away from j
    return t;
  }
};

}  // namespace anisodyn
