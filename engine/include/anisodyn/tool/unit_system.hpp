#pragma once
// The unit system of a run: reduced (kT = 1, lengths and times those of the input) or SI (time in
// s, energy in J, lengths in a stated number of metres). Engines that take a `units` block record
// it in their parameters; analysis stages read it back from there to label what they write, so that
// an SI run's diffusion coefficients say um^2/s rather than length^2/tau.
#include <string>

#include <nlohmann/json.hpp>

namespace anisodyn::tool {

struct UnitSystem {
  bool si = false;
  double length_m = 1.0;       // SI: metres per length unit of the input
  double temperature_K = 0.0;  // SI only
  /// kT in the run's energy unit: 1 (reduced) or k_B T in J (SI).
  double kT() const;
  /// The provenance record of the unit system.
  nlohmann::json to_json() const;
  /// Symbolic unit strings as written by the code ("tau", "length^2/tau", "sigma") in this system:
  /// the words tau, length and sigma become s and the length unit (um, nm, m or "(x m)") in SI.
  std::string express(const std::string& symbolic) const;
};

/// The unit system a run's parameters (its config JSON) declare under "units" ({"system": "SI",
/// "length", "temperature"}); reduced if absent.
UnitSystem unit_system_of_run(const nlohmann::json& run_parameters);

}  // namespace anisodyn::tool
