#pragma once
// The anisodyn-lb configuration (docs/lb.md), in the reduced units of spec 40 §1 (M0, σ = 1 nm,
// ε = k_BT at 298 K, t0):
//   {"seed": 1, "time_step": 0.01, "steps": 20000 | "time": 200,
//    "kT": 1,
//    "fluid": {"agrid": 1, "lb_steps": 2, "density": 6.004, "viscosity": 0.8,
//              "bulk_relaxation": 0, "ghost_relaxation": 0, "thermal": true,
//              "initial_velocity": [0, 0, 0], "warmup_steps": 1000, "body_force": [0, 0, 0]},
//    "raspberries": {"species": ["sphere"], "xi_bead": 1000, "xi_bead_is_nominal": true,
//                    "centre_couples": true, "fixed": false, "coupling_velocity": "with_half_force",
//                    "allow_unstable": false, "layers": "two"},
//    "walls": {"normal": "y", "velocity": [0, 0, 0.013976]},
//    "pore": {"radius": 8.5, "wall_bead_radius": 6.25, "wall_bead_spacing": 5, "epsilon": 1},
//    "frames": {...}, "observe_every": 200}
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "anisodyn/core/types.hpp"
#include "anisodyn/lb/point_coupling.hpp"
#include "anisodyn/lb/pore_walls.hpp"
#include "anisodyn/lb/si_units.hpp"
#include "anisodyn/run/time_step_run.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::lb {

struct LbProtocol : run::TimeStepRun {
  /// The runner checks the box against the lattice and the bodies itself.
  static constexpr bool kChecksOwnRanges = true;
  double kT = 1.0;
  struct Fluid {
    double agrid = 1.0;          ///< node spacing a (σ)
    int lb_steps = 2;            ///< MD steps per LB step (Δt_LB = lb_steps Δt)
    double density = 6.004;      ///< ρ (M0/σ³)
    double viscosity = 0.8;      ///< ν_sim (σ²/t0)
    double bulk_relaxation = 0.0, ghost_relaxation = 0.0;  ///< γ_b, γ_g (spec 40 §2.3: full relaxation)
    bool thermal = true;         ///< the fluctuating fluid and bead noise; false: deterministic (Stokes-flow runs)
    Vec3 initial_velocity = Vec3::Zero();  ///< σ/t0: the fluid's starting velocity on every node
    std::int64_t warmup_steps = 1000;      ///< MD steps' worth of fluid-only LB steps before the run (spec 40 §2.4)
    Vec3 body_force = Vec3::Zero();        ///< M0/(σ² t0²): a force per volume on the fluid at every step (a pressure gradient)
  } fluid;
  struct Raspberries {
    std::vector<std::string> species;  ///< empty: every species of the input
    double xi_bead = 0.0;              ///< bead friction, M0/t0 (nominal when xi_bead_is_nominal)
    ViscosityScaling scaling;          ///< ν_sim is the fluid's
    bool centre_couples = true;        ///< spec 40 §3: the centre bead couples (default yes)
    bool fixed = false;                ///< held in place (Stokes-flow drag, spec 40 §7.2)
    CouplingVelocity velocity = CouplingVelocity::kWithHalfForce;
    bool allow_unstable = false;       ///< run with Δt Σ ξ_sim / m above 1
    bool outer_layer = true;           ///< "layers": "single" drops the outer layer (spec 40 §6's ablation)
  } raspberries;
  /// A moving bounce-back wall: one layer of solid nodes at index 0 along `normal`; with the
  /// periodic box it bounds the fluid on both sides (spec 40 §7.2: the ±y faces).
  struct Walls {
    int normal = 1;                 ///< 0, 1, 2 = x, y, z
    Vec3 velocity = Vec3::Zero();   ///< σ/t0, tangential
  };
  std::optional<Walls> walls;
  /// A cylindrical pore along z through the box's centre (spec 40 §6): solid nodes beyond the
  /// radius, wall beads repelling the raspberries' inner layers; absent: none.
  std::optional<PoreParameters> pore;
};

LbProtocol parse_lb_protocol(tool::ConfigNode& cfg);

}  // namespace anisodyn::lb
