#pragma once
// The fluid checks of spec 40 §2.5 and §3 as measurements (study D1, `anisodyn-lb-checks`; the
// unit and statistical tests assert on the same functions): each sets up a small lattice, runs it
// and returns what it measured, with the reference it is compared with.
#include <array>
#include <cstdint>
#include <vector>

#include "anisodyn/lb/lb_fluid.hpp"
#include "anisodyn/lb/point_coupling.hpp"

namespace anisodyn::lb::checks {

/// ν from the decay of a shear wave u_x = U sin(k z) on a 1 × 1 × length lattice: the amplitude's
/// logarithm fitted against t (least squares) over steps [t0, t1].
double shear_wave_viscosity(double nu, int length, int t0, int t1);

/// The steady velocity u_z at the fluid nodes y = 1 … h of a channel 1 × (h + 2) × 1 between solid
/// rows y = 0 and y = h + 1 moving along z at `bottom` and `top`, with a body force g along z, run
/// for 20 momentum-diffusion times h²/ν.
std::vector<double> channel_profile(int h, double nu, double bottom, double top, double g);

/// Thermal equilibrium of a cubic periodic lattice of the fluctuating fluid: per mode k the mean
/// square ⟨m_k²⟩ over nodes (mode 0 about ρ_0) and, at index kQ, ⟨u_α²⟩ per component, each as a
/// ratio to its target μ ρ b_k (μ = k_BT/c_s²) or k_BT/ρ, with the factor 1 − 1/N for the
/// conserved modes 0–3 and u (fixed totals over N nodes); errors from blocks.
struct ModeVariances {
  std::vector<double> ratio, standard_error;  ///< kQ + 1 entries: the modes, then ⟨u²⟩
  int blocks = 0;
  long samples = 0;
};
ModeVariances thermal_mode_variances(const LbParameters& p, int edge, int warmup_steps, int blocks, int steps_per_block, int every);

/// Beads point-coupled to the thermal fluid (two MD steps per LB step, free beads of mass m):
/// the largest change of the total momentum (fluid + beads), of the fluid's mass, and the beads'
/// kinetic temperature m⟨v²⟩/k_BT with its block error, against the explicit kick's own bias
/// 1/(1 − ξh/2m).
struct CoupledBeads {
  double momentum_change = 0.0, mass_change = 0.0, initial_mass = 0.0;
  double bead_temperature = 0.0, bead_temperature_se = 0.0, expected_temperature = 0.0;
  double fluid_momentum_change = 0.0;  ///< how far the fluid's own momentum moved (what the beads exchanged)
};
CoupledBeads coupled_bead_run(const LbParameters& p, int edge, std::size_t beads, double mass, double xi, int warmup_steps, int blocks,
                              int steps_per_block);

/// The steady velocity per unit force of one bead of friction ξ pulled by F along x through a
/// deterministic L³ fluid (ρ = 1, ν), relative to the fluid's mean velocity; the fluid is pushed
/// back by −F spread over all nodes, so that the total momentum stays zero. Two MD steps per LB
/// step; the bead's mass m = 2ξh keeps ξh/m at ½. Run for four momentum-diffusion times L²/ν,
/// averaged over the last two.
double pulled_bead_mobility(int L, double nu, double xi, const Vec3& start, CouplingVelocity convention);

/// Ahlrichs and Dünweg's g from a pulled bead's mobility μ: μ = 1/ξ + 1/(g η) − 2.837297/(6π η L).
double ahlrichs_dunweg_g(double mobility, double xi, double eta, double L);

}  // namespace anisodyn::lb::checks
