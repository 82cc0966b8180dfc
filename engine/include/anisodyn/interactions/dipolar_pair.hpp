#pragma once
// The point-dipole pair energy of two equal dipoles along the field Ê (spec 10 §6.1, spec 50 E2):
//   βu(r) = (γ/2) (σ/r)³ (1 − 3 (Ê·r̂)²) = (γ/2) σ³ ψ₀(r),   ψ₀(r) = 1/r³ − 3 (Ê·r)²/r⁵.
//
// Written once, for the engine and the analyses alike: ψ₀ is the bare part of the real-space pair
// function of the DMC engine's Ewald sum (dipolar_ewald.cpp, also its whole pair function in the
// minimum-image smoke mode), and βu is the bond rule of the dipolar chains, the chain mask of the
// cube order and the βu_max of the DBSCAN calibration (analysis/). Two formulas for one energy
// round differently in the last bits, so a bond at the threshold βu_max could be decided one way
// by a stage and the other way by a check against the engine.
//
// The arithmetic is the engine's, operation for operation (1/√r², then powers of it; r² and Ê·r as
// left-to-right sums of the components): the engine's trajectories depend on every bit of it, while
// the analyses only compare βu with a threshold or report it. One source is not quite one rounding:
// GCC fuses a multiply and an add into one FMA where it sees fit (its default -ffp-contract=fast,
// with FMA in -march=native), and it may pick other pairs at each place the function is inlined
// (the engine's ψ and this βu were measured to differ by an ulp now and then). Pinning the fusions
// with std::fma would change the engine's trajectories and cost a library call on CPUs without FMA,
// so the function stays plain and the engine's own loops keep the rounding they had.
#include <cmath>

#include "anisodyn/core/types.hpp"

namespace anisodyn {

/// ψ₀ = 1/r³ − 3 (Ê·r)²/r⁵ from r² and (Ê·r)², Ê a unit vector: (1 − 3cos²θ)/r³ without γ/2.
/// Inline and branch-free, so the engine's loops over all particles still vectorise.
inline double bare_dipolar_psi(double r2, double e_dot_r_squared) {
  const double rinv = 1.0 / std::sqrt(r2);
  const double r3 = rinv * rinv * rinv;
  const double r5 = r3 * rinv * rinv;
  return r3 - 3.0 * e_dot_r_squared * r5;
}

/// βu = (γ/2) σ³ ψ₀ from r² and Ê·r (Ê a unit vector). σ = 1, the engine's unit of length,
/// multiplies by exactly 1.
inline double dipolar_pair_energy(double r2, double e_dot_r, double gamma, double sigma = 1.0) {
  const double sigma3 = sigma * sigma * sigma;
  return 0.5 * gamma * (sigma3 * bare_dipolar_psi(r2, e_dot_r * e_dot_r));
}

/// βu of the pair at separation r (the minimum image, as the caller chooses it); `field` must be a
/// unit vector.
inline double dipolar_pair_energy(const Vec3& r, const Vec3& field, double gamma, double sigma = 1.0) {
  const double r2 = r.x() * r.x() + r.y() * r.y() + r.z() * r.z();
  const double e_dot_r = field.x() * r.x() + field.y() * r.y() + field.z() * r.z();
  return dipolar_pair_energy(r2, e_dot_r, gamma, sigma);
}

}  // namespace anisodyn
