#pragma once
// Rigid bodies of beads (raspberries, spec 40 §4) coupled to the LB fluid (§3), as the force field
// and the thermostat hook of RigidBodyNve (integrate/rigid_body_nve.hpp):
// - the force field places each body's beads at r + R(q) d, gives them the rigid-body velocity
//   V + ω × R(q) d (from the velocities and angular momenta the integrator holds while it evaluates
//   forces: the half-step ones), couples them to the fluid (lb/point_coupling.hpp), and reduces the
//   bead forces to each body's force and torque (system/rigid_sites.hpp); the opposite impulses go
//   to the fluid;
// - the hook advances the fluid once every lb_steps MD steps (spec 40: Δt_LB = 2Δt).
//
// The MD side works in its reduced units (spec 40 §1: M0, σ, t0), the fluid in lattice units: a
// node spacing `agrid` and an LB step `lb_time_step` (= lb_steps · Δt), the same mass unit.
#include <cstdint>
#include <vector>

#include "anisodyn/integrate/body_forces.hpp"
#include "anisodyn/lb/lb_fluid.hpp"
#include "anisodyn/lb/point_coupling.hpp"
#include "anisodyn/system/rigid_sites.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn::lb {

struct LbUnits {
  double agrid = 1.0;        ///< node spacing, in MD lengths
  double md_time_step = 0.01;
  int lb_steps = 2;          ///< MD steps per LB step

  double lb_time_step() const { return lb_steps * md_time_step; }
  /// MD velocity → lattice velocity, MD friction → lattice friction, MD energy → lattice energy.
  double velocity_to_lattice() const { return lb_time_step() / agrid; }
  double friction_to_lattice() const { return lb_time_step(); }
  double energy_to_lattice() const { return lb_time_step() * lb_time_step() / (agrid * agrid); }
  /// lattice force (momentum per LB step per LB step) → MD force.
  double force_from_lattice() const { return agrid / (lb_time_step() * lb_time_step()); }
};

class BodyFluidCoupling {
 public:
  /// bodies[s]: the beads of species s (empty: a species that does not couple); moments[s]: the
  /// principal moments of species s (for ω = R I⁻¹ Rᵀ L); friction ξ_bead and k_BT in MD units.
  BodyFluidCoupling(LbFluid& fluid, SiteTable bodies, std::vector<Vec3> moments, double friction, double kT, std::uint64_t seed, LbUnits units,
                    CouplingVelocity velocity = CouplingVelocity::kWithHalfForce);

  /// The force field: adds each coupled body's force and torque (MD units) to out; the opposite
  /// impulses go to the fluid. The bead noise is keyed by the noise step (below) and
  /// (body id · 2¹² + bead); body ids below 2²⁰.
  void operator()(const State& state, BodyForces& out);
  /// The noise step of the next force evaluations: the runner sets the MD step being taken (the
  /// starting forces keep 0), as for the DPD pair noise.
  void set_noise_step(std::uint64_t step) { noise_step_ = step; }
  /// The hook: after MD step state.step + 1, the fluid takes its step when that is a multiple of
  /// lb_steps.
  void after_step(State& state, double dt);

  /// Total momentum of the fluid in MD units: Σ j over the nodes (lattice units: mass per node times
  /// lattice velocity) times agrid/Δt_LB.
  Vec3 fluid_momentum() const;

  static constexpr int kBeadBits = 12;  ///< beads per body below 2¹²

 private:
  Vec3 angular_velocity(const State& s, std::size_t i) const;

  LbFluid& fluid_;
  SiteTable bodies_;
  std::vector<Vec3> moments_;
  LbUnits units_;
  PointCoupling coupling_;
  std::vector<Vec3> r_, v_, f_;
  std::vector<std::uint32_t> id_;
  std::uint64_t noise_step_ = 0;
};

}  // namespace anisodyn::lb
