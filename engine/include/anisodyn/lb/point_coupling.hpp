#pragma once
// Point coupling of beads to the LB fluid (Ahlrichs and Dünweg, J. Chem. Phys. 111, 8225, 1999;
// spec 40 §3), in lattice units (a = Δt_LB = 1; an MD step is h = Δt/Δt_LB of an LB step):
//
//   F = −ξ [v − u(r)] + f_s,   ⟨f_s,α f_s,β⟩ = 2 k_BT ξ δ_αβ / h,
//
// u(r) the fluid velocity interpolated trilinearly from the eight node centres around r, f_s a
// Gaussian keyed by (seed, MD step, bead id) so that it does not depend on the thread count. The
// opposite impulse −F h goes to the same eight nodes with the same weights, as force density for
// the fluid's next collision, so bead and fluid momentum together are conserved.
#include <array>
#include <cstdint>
#include <vector>

#include "anisodyn/core/keyed_random.hpp"
#include "anisodyn/core/types.hpp"
#include "anisodyn/lb/lb_fluid.hpp"

namespace anisodyn::lb {

/// The eight nodes around a point and their trilinear weights (summing to 1).
struct Stencil {
  std::array<std::size_t, 8> node;
  std::array<double, 8> weight;
};

/// The stencil of r (lattice units, any image: wrapped into the periodic box).
Stencil trilinear_stencil(const LbFluid& fluid, const Vec3& r);

/// Which fluid velocity a bead is coupled to: spec 40 §2.3's u = (j + f/2)/ρ with the force
/// density pending for the next collision (the default), or j/ρ alone.
enum class CouplingVelocity { kWithHalfForce, kMomentumOnly };

/// Σ w_n u_n over a stencil's nodes (u_n: LbFluid::velocity, with or without the half force).
Vec3 interpolated_velocity(const LbFluid& fluid, const Stencil& stencil, CouplingVelocity velocity = CouplingVelocity::kWithHalfForce);
/// u(r) over the stencil of r.
Vec3 interpolated_velocity(const LbFluid& fluid, const Vec3& r);

class PointCoupling {
 public:
  /// friction ξ > 0, h = Δt_MD/Δt_LB in (0, 1], k_BT ≥ 0 (0: no noise), seed of the bead noise.
  PointCoupling(double friction, double md_step_fraction, double kT, std::uint64_t seed,
                CouplingVelocity velocity = CouplingVelocity::kWithHalfForce);

  double friction() const { return friction_; }

  /// The coupling force on each bead at MD step `md_step` into force[b]; the opposite impulses
  /// are added to the fluid's force density for its next step.
  void couple(LbFluid& fluid, const std::vector<Vec3>& position, const std::vector<Vec3>& velocity, const std::vector<std::uint32_t>& id,
              std::uint64_t md_step, std::vector<Vec3>& force) const;

 private:
  double friction_, h_, noise_amplitude_;
  KeyedRandom noise_;
  CouplingVelocity velocity_;
};

}  // namespace anisodyn::lb
