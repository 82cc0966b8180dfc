#pragma once
// Method II of spec 20 §6.2: a constant external torque T_ex on tagged rods, whose axes are kept
// in the plane perpendicular to the torque by a confining potential U_c = (κ_c/2)(û·ê)², ê = T_ex/|T_ex|.
// The confinement's torque is −û × ∂U_c/∂û = −κ_c (û·ê) û × ê. The mean angular velocity of a
// free rod is then D_r |T_ex| / kT (γ_r⟨ω⟩ = T_ex), which the drag measurement inverts.
#include <cstddef>
#include <vector>

#include "anisodyn/integrate/body_forces.hpp"

namespace anisodyn {

struct ExternalTorque {
  std::vector<std::size_t> particles;  // the tagged rods (indices)
  Vec3 torque = Vec3::Zero();          // T_ex, in the run's units (lab frame)
  double confinement = 0.0;            // κ_c, energy
};

/// Adds T_ex and the confinement's torque and energy to the tagged rods (axes = body z).
inline void add_external_torque(const ExternalTorque& ext, const State& s, BodyForces& out) {
  const double magnitude = ext.torque.norm();
  if (magnitude == 0.0) return;
  const Vec3 e = ext.torque / magnitude;
  for (const std::size_t i : ext.particles) {
    const Vec3 u = s.particles.orientation(i) * Vec3::UnitZ();
    const double c = u.dot(e);
    out.torque[i] += ext.torque - ext.confinement * c * u.cross(e);
    out.energy += 0.5 * ext.confinement * c * c;
  }
}

}  // namespace anisodyn
