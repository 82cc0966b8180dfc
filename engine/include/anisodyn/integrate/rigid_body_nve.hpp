#pragma once
// Rigid-body molecular dynamics in the microcanonical ensemble: velocity Verlet for the centres
// and the NO_SQUISH symplectic splitting for the orientations (Miller, Eleftheriou, Pattnaik,
// Ndirango, Newns & Martyna, J. Chem. Phys. 116, 8649 (2002)). The time stepping of the MD-type
// engines: DPD colloids and liquid particles (spec 30 §2–§3), LB raspberries (spec 40 §4).
//
// One step of length δt, per body, with force F and torque τ (lab frame, about the centre):
//   1. half kick:   v += (δt/2) F/m;  L += (δt/2) τ
//   2. drift:       r += δt v, wrapped into the box with the image counters kept
//   3. free rotation of (q, p), p = 2 S(q) (0, L_body) the momentum conjugate to q:
//                   R3(δt/2) R2(δt/2) R1(δt) R2(δt/2) R3(δt/2), where R_k(t) is the exact flow of
//                   the rotor about body axis k alone: ζ = t (pᵀ P_k q) / (4 I_k),
//                   q ← cos ζ q + sin ζ P_k q,  p ← cos ζ p + sin ζ P_k p
//   4. forces at the new positions and orientations (with the half-step v and L in the state)
//   5. half kick with the new forces, as in 1
//   6. the thermostat hook, if any.
// With a velocity prediction λ ≠ ½ (set_velocity_prediction; Groot & Warren, J. Chem. Phys. 107,
// 4423 (1997), their modified velocity Verlet), step 4 sees v + (λ − ½) δt F/m and
// L + (λ − ½) δt τ in place of the half-step v and L, that is v(t) + λ δt F(t)/m: the prediction of
// velocity-dependent forces (DPD's dissipative force). The half-step v and L are kept and put back
// before step 5, so the scheme differs from the plain one only in the forces of velocity-dependent
// fields; for λ = ½ it is the plain scheme, bit for bit.
// The kick of the paper, p += (δt/2) 2 S(q) (0, τ_body), is the lab-frame kick L += (δt/2) τ at
// fixed q (S(q) is orthogonal), which is how it is done here. Each R_k keeps the lab-frame angular
// momentum exactly (its Hamiltonian is invariant under rotations of the lab), so step 3 changes
// only q and L is not converted back from p; only the kicks change L, and a free body keeps it to
// the last bit. NO_SQUISH keeps |q| = 1 (each R_k is a rotation in the plane of q and P_k q); q is
// renormalised after step 3 only to remove round-off.
//
// The state is authoritative: Particles' lab-frame velocity (vx…) and angular momentum about the
// centre (lx…) are read at the start of each step and written at its end; p exists only inside
// step 3. What the integrator carries between steps is the forces of the last configuration
// (evaluated once per step); forces() and restore_forces() let a checkpoint keep them, which
// velocity- or noise-dependent force fields need for an exact restart. Force fields that depend
// only on positions and orientations restart exactly from the state alone: a fresh integrator
// evaluates the same forces.
//
// Body axes are the principal axes (q maps them to the lab). A principal moment of 0 means no
// rotation about that axis: the angular momentum's component along it is dropped after every kick
// and rotation, and R_k is skipped; a point particle (all moments 0) never rotates. A linear rotor
// (one moment 0, the other two equal: a rod of sites on a body axis, spec 30 §3.2) keeps L ⊥ û
// and takes the exact free flow instead of the splitting: û turns about L by |L| δt / I⊥.
#include <functional>
#include <vector>

#include "anisodyn/core/types.hpp"
#include "anisodyn/integrate/body_forces.hpp"
#include "anisodyn/integrate/integrator.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

/// Mass and principal moments of inertia (about body x, y, z) of the bodies of one species.
struct BodyInertia {
  double mass;
  Vec3 principal_moments;
  /// Held in place: neither kicked nor moved (a colloid fixed in a flow, spec 30 §8); its velocity
  /// and angular momentum stay as they are (zero for a body at rest).
  bool fixed = false;
};

/// Called at the end of every step with the step length: where a thermostat acts on the velocities
/// and angular momenta (a Langevin friction and noise, the LB bead coupling and fluid update).
using ThermostatHook = std::function<void(State&, double dt)>;

class RigidBodyNve : public Integrator {
 public:
  /// inertia[s] is for species index s; masses must be positive, moments zero or positive.
  RigidBodyNve(double dt, std::vector<BodyInertia> inertia, ForceField force_field, ThermostatHook thermostat = {});

  /// One step (above). A state without velocities is given them, at rest; one without angular
  /// momenta too, unless every species is a point body (all moments 0), which never rotates.
  /// The step counter and time of the state are left to the caller. Returns dt.
  double step(State& state) override;

  double dt() const { return dt_; }
  /// The forces carried into the next step: those of the state as the last step left it (empty
  /// before the first step).
  const BodyForces& forces() const { return forces_; }
  /// Carries `forces` into the next step instead of evaluating them (a restart from a checkpoint).
  void restore_forces(BodyForces forces);
  /// Makes the next step evaluate the forces first (after the state was changed outside step()).
  void invalidate_forces() { have_forces_ = false; }
  /// Groot–Warren's λ (above): the forces of a step see v(t) + λ δt F(t)/m; ½ by default.
  void set_velocity_prediction(double lambda) { lambda_ = lambda; }

 private:
  void evaluate_forces(const State& state);
  /// Evaluates the forces with the predicted v and L in the state (λ ≠ ½), then puts back the
  /// half-step ones.
  void evaluate_forces_predicted(State& state);
  void check_species(const Particles& p) const;
  bool any_rotating_species() const;

  double dt_;
  std::vector<BodyInertia> inertia_;
  ForceField force_field_;
  ThermostatHook thermostat_;
  BodyForces forces_;
  bool have_forces_ = false;
  double lambda_ = 0.5;
  std::vector<Vec3> half_step_v_, half_step_l_;  // kept while the forces see the predicted ones
};

}  // namespace anisodyn
