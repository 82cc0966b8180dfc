#pragma once
// The anisodyn-dpd configuration (docs/dpd.md):
//   {"seed": 1, "time_step": 0.005, "steps": 20000 | "time": 100,
//    "kT": 1,
//    "liquid": {"species": ["liquid"], "a": 25, "gamma": 4.5, "cutoff": 1, "skin": 0.3},
//    "velocities": "input" | "maxwell_boltzmann",
//    "frames": {...}, "observe_every": 100,
//    "green_kubo": {"blocks": 10, "max_lag": 20}}
// Reduced units of spec 30 §1: lengths in r_c, energies in kT, masses in m (the species' masses).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "anisodyn/interactions/dpd_pairs.hpp"
#include "anisodyn/run/green_kubo.hpp"
#include "anisodyn/run/time_step_run.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn {

struct DpdProtocol : run::TimeStepRun {
  DpdParameters liquid;
  std::vector<std::string> liquid_species;  // empty: every species of the input
  double skin = 0.3;
  /// Where the starting velocities come from: the input's (it must have them), or Maxwell–Boltzmann
  /// at kT with zero total momentum. Default: the input's when it has them.
  enum class Velocities { Default, Input, MaxwellBoltzmann } velocities = Velocities::Default;
  /// The Green–Kubo record of the stress (run/green_kubo.hpp); absent: none.
  std::optional<run::GreenKuboSettings> green_kubo;
};

DpdProtocol parse_dpd_protocol(tool::ConfigNode& cfg);

}  // namespace anisodyn
