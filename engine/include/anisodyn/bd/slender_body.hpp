#pragma once
// Free-rod friction of long thin rods without end corrections (spec 20 §2; Tao et al. 2005):
//   γ_∥ = 2π η L / ln(L/D),  γ_⊥ = 2 γ_∥,  γ_r = π η L³ / (3 ln(L/D)),
// so D_∥ = kT/γ_∥, D_⊥ = kT/γ_⊥ and D_r = 3 kT ln(L/D) / (π η L³). The spin about the rod axis is
// ignored (BD does not move it).
#include <cmath>
#include <stdexcept>

#include "anisodyn/bd/bd_integrator.hpp"

namespace anisodyn {

/// The diffusion of a rod of length L and diameter D (L > D > 0) in a solvent of viscosity η at
/// thermal energy kT, all in one consistent unit system.
inline BdDiffusion slender_body_diffusion(double length, double diameter, double viscosity, double kT) {
  if (!(diameter > 0.0) || !(length > diameter) || !(viscosity > 0.0) || !(kT > 0.0))
    throw std::invalid_argument("slender-body friction needs L > D > 0, a positive viscosity and kT");
  const double log_aspect = std::log(length / diameter);
  const double gamma_parallel = 2.0 * M_PI * viscosity * length / log_aspect;
  const double gamma_rotation = M_PI * viscosity * length * length * length / (3.0 * log_aspect);
  return {kT / gamma_parallel, kT / (2.0 * gamma_parallel), kT / gamma_rotation};
}

}  // namespace anisodyn
