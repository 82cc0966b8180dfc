#pragma once
// The anisodyn-dpd configuration (docs/dpd.md):
//   {"seed": 1, "time_step": 0.005, "steps": 20000 | "time": 100,
//    "kT": 1,
//    "liquid": {"species": ["liquid"], "a": 25, "gamma": 4.5, "cutoff": 1, "skin": 0.3},
//    "velocities": "input" | "maxwell_boltzmann",
//    "frames": {...}, "observe_every": 100,
//    "green_kubo": {"blocks": 10, "max_lag": 20},
//    "colloids": {"species": ["rod"], "gamma_surface": 6.667, "shell": 0.5, "shell_noise": "vector3d",
//                 "mass_density": 3, "site_spacing": 0.5},
//    "frame_species": ["rod"],
//    "walls": {"type": "flat_mie", "height": 8, "gamma_surface": [3.333, 0], "shell": 0.5, "shell_noise": "vector3d"},
//    "drive": {"force": [0.01, 0, 0], "z_min": 6}  (or a list of such slabs),
//    "profiles": {"z_bin": 0.1, "radial_bin": 0.1, "radial_max": 4, "midplane_half_width": 0.25}}
// Reduced units of spec 30 §1: lengths in r_c, energies in kT, masses in m (the species' masses).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "anisodyn/interactions/dpd_pairs.hpp"
#include "anisodyn/interactions/flat_walls.hpp"
#include "anisodyn/interactions/site_liquid.hpp"
#include "anisodyn/run/green_kubo.hpp"
#include "anisodyn/run/time_step_run.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn {

struct DpdProtocol : run::TimeStepRun {
  /// The runner checks its own interaction ranges against the box (not the shapes' hard-body rule).
  static constexpr bool kChecksOwnRanges = true;
  DpdParameters liquid;
  std::vector<std::string> liquid_species;  // empty: every species of the input
  double skin = 0.3;
  /// Groot–Warren's λ: the forces of a step see the predicted velocities v(t) + λ Δt F(t)/m
  /// (integrate/rigid_body_nve.hpp); ½ is LAMMPS's scheme (spec 30 §2, Decision 3).
  double velocity_lambda = 0.5;
  /// Where the starting velocities come from: the input's (it must have them), or Maxwell–Boltzmann
  /// at kT with zero total momentum. Default: the input's when it has them.
  enum class Velocities { Default, Input, MaxwellBoltzmann } velocities = Velocities::Default;
  /// The Green–Kubo record of the stress (run/green_kubo.hpp); absent: none.
  std::optional<run::GreenKuboSettings> green_kubo;
  /// Rigid colloids in the liquid (spec 30 §3–§4); absent: a pure liquid.
  struct Colloids {
    std::vector<std::string> species;  // required, at least one
    SiteLiquidParameters shell;        // gamma_surface, shell, shell_noise (kT is the run's)
    double mass_density = 3.0;         // ρ of the density-matched masses (§3.1–§3.2)
    double site_spacing = 0.5;         // Δl of a rod's spheres
    bool fixed = false;                // held in place (spec 30 §8)
  };
  std::optional<Colloids> colloids;
  /// The species whose particles the frames hold (all particles of the others are left out);
  /// empty: every particle.
  std::vector<std::string> frame_species;
  /// Flat walls at z = 0 and z = height (spec 30 §6); absent: periodic in z.
  std::optional<FlatWallParameters> walls;
  /// A constant force on the liquid particles with z_min ≤ z < z_max (z wrapped into the box);
  /// several slabs add up (two opposite ones make the periodic Poiseuille flow); none: no drive.
  struct Drive {
    Vec3 force = Vec3::Zero();
    double z_min = -INFINITY, z_max = INFINITY;
  };
  std::vector<Drive> drives;
  /// Profiles of the liquid accumulated every step, written per observation row; absent: none.
  struct Profiles {
    double z_bin = 0.0;                     // > 0: number and Σ v_x per slab of this width along z
    double radial_bin = 0.0;                // > 0: around the first colloid, number per shell and …
    double radial_max = 0.0;                // … out to this distance (default: half the shortest edge), and …
    double midplane_half_width = 0.25;      // … Σ v_x and number in the slab |x − x_c| < this, per shell
  };
  std::optional<Profiles> profiles;
};

DpdProtocol parse_dpd_protocol(tool::ConfigNode& cfg);

}  // namespace anisodyn
