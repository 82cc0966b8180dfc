#pragma once
// Weeks–Chandler–Andersen pair repulsion: U = 4ε[(σ/r)¹² − (σ/r)⁶] + ε for r < 2^{1/6} σ, else 0.
// The excluded volume between raspberry inner-layer beads and pore wall beads (spec 40 §6).
#include <cmath>

#include "anisodyn/interactions/pair_forces.hpp"

namespace anisodyn {

struct Wca {
  static constexpr int kParts = 1;
  double epsilon = 1.0, sigma = 1.0;

  double cutoff() const { return std::pow(2.0, 1.0 / 6.0) * sigma; }

  PairTerm<1> operator()(std::size_t, std::size_t, const Vec3& d, double r2) const {
    PairTerm<1> t;
    const double rc = cutoff();
    if (r2 >= rc * rc) return t;
    const double s2 = sigma * sigma / r2, s6 = s2 * s2 * s2, s12 = s6 * s6;
    t.interacts = true;
    t.energy = 4.0 * epsilon * (s12 - s6) + epsilon;
    // F_i = −∂U/∂r_i = U'(r) d/r with U'(r) = −24ε(2 s¹² − s⁶)/r: away from j.
    t.force[0] = (-24.0 * epsilon * (2.0 * s12 - s6) / r2) * d;
    return t;
  }
};

}  // namespace anisodyn
