#pragma once
// Rotne–Prager–Yamakawa mobility of two equal beads of radius a in a fluid of viscosity η, with
// the Rotne–Prager correction for overlapping beads (r < 2a), which keeps the 3N×3N mobility
// positive definite for any bead configuration (spec 10 §8.4 step 2):
//   r ≥ 2a: μ = (1/(8πηr)) [(1 + 2a²/(3r²)) I + (1 − 2a²/r²) r̂r̂]
//   r < 2a: μ = (1/(6πηa)) [(1 − 9r/(32a)) I + (3r/(32a)) r̂r̂]
// At r = 0 the overlap branch gives the self mobility I/(6πηa), so a bead paired with itself
// (for instance with its own mirror image when it lies on a mirror plane) needs no special case.
#include <cmath>

#include "anisodyn/core/types.hpp"

namespace anisodyn::hydro {

/// μ = iso·I + dyad·r̂r̂ for the separation r (length |r|).
struct RpyCoefficients {
  double iso;
  double dyad_over_r2;  // dyad/r², so that μ = iso·I + dyad_over_r2·r rᵀ needs no normalisation
};

inline RpyCoefficients rpy_coefficients(double r2, double a, double eta = 1.0) {
  const double r = std::sqrt(r2);
  if (r >= 2.0 * a) {
    const double pre = 1.0 / (8.0 * M_PI * eta * r);
    const double a2_r2 = a * a / r2;
    return {pre * (1.0 + 2.0 * a2_r2 / 3.0), pre * (1.0 - 2.0 * a2_r2) / r2};
  }
  const double pre = 1.0 / (6.0 * M_PI * eta * a);
  const double dyad_over_r2 = r > 0.0 ? pre * 3.0 / (32.0 * a * r) : 0.0;  // (3r/32a)/r²
  return {pre * (1.0 - 9.0 * r / (32.0 * a)), dyad_over_r2};
}

inline Mat3 rpy_mobility(const Vec3& r, double a, double eta = 1.0) {
  const RpyCoefficients c = rpy_coefficients(r.squaredNorm(), a, eta);
  return c.iso * Mat3::Identity() + c.dyad_over_r2 * (r * r.transpose());
}

}  // namespace anisodyn::hydro
