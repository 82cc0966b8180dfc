#pragma once
// Overdamped Brownian dynamics of rods and spheres, Itô, exactly as spec 20 §3 (Tao et al. 2005):
//
//   r(t+Δt) = r + μ·F Δt + Δr,        μ = (D_∥ ûû + D_⊥ (I − ûû)) / kT,
//   û(t+Δt) = (û + (D_r/kT) (T × û) Δt + Δû) / |…|,
//
// with F, T the systematic force and torque at the start of the step (after the caps), Δr one
// Gaussian along û with variance 2D_∥Δt and two across it with 2D_⊥Δt, Δû two Gaussians across û
// with 2D_rΔt. No explicit Itô drift: the renormalisation gives the −2D_rΔt û that the unit sphere
// needs. Rods are along their body z axis (L); the quaternion follows û by the smallest rotation,
// so the spin about the axis stays fixed (spec 20 §2 ignores it). Spheres (D_∥ = D_⊥, D_r = 0)
// translate only.
//
// The noise of particle i at step n is the five normals of KeyedRandom(seed, kBdNoise) at counter
// (n, i, replica): the run gives the same numbers for any thread count and restarts bit for bit from a
// state (the step counter is State::step).
#include <cstdint>
#include <optional>
#include <vector>

#include "anisodyn/integrate/body_forces.hpp"
#include "anisodyn/integrate/integrator.hpp"

namespace anisodyn {

/// Diffusion of one species in its body frame, in the run's units (length²/time, 1/time).
struct BdDiffusion {
  double parallel = 0.0;       // along the rod axis û
  double perpendicular = 0.0;  // across it
  double rotation = 0.0;       // of the axis û; 0: the orientation stays fixed
};

struct BdSettings {
  double time_step = 0.0;
  double kT = 1.0;
  std::uint64_t seed = 1;
  std::uint64_t replica = 0;  // independent noise streams of one seed
  std::vector<BdDiffusion> diffusion;  // per species
  /// Caps on the norm of each particle's total systematic force and torque (spec 20 §4.5); never on the noise.
  std::optional<double> force_cap, torque_cap;
};

class BdIntegrator final : public Integrator {
 public:
  /// `forces` may be empty (free particles). Throws std::invalid_argument for a non-positive time
  /// step or kT, or negative diffusion coefficients.
  BdIntegrator(BdSettings settings, ForceField forces);

  /// One step of Δt; returns Δt.
  double step(State& state) override;

  /// The systematic forces and torques of the last step, before the caps (spec 20 §6.3 uses them).
  const BodyForces& systematic() const { return forces_; }
  /// How many particle-steps had their force (torque) capped so far.
  std::int64_t capped_forces() const { return capped_forces_; }
  std::int64_t capped_torques() const { return capped_torques_; }
  /// For checkpoints: the counters, restored as they were.
  void restore_counters(std::int64_t capped_forces, std::int64_t capped_torques);
  const BdSettings& settings() const { return settings_; }

 private:
  BdSettings settings_;
  ForceField field_;
  BodyForces forces_;
  std::int64_t capped_forces_ = 0, capped_torques_ = 0;
};

/// Two unit vectors that make (e1, e2, u) a right-handed orthonormal basis; a fixed function of u,
/// so that the noise directions of a rod are reproducible.
void perpendicular_basis(const Vec3& u, Vec3& e1, Vec3& e2);

}  // namespace anisodyn
