#pragma once
// The reduced units of spec 40 §1 and their SI values, and the viscosity scaling of §1.1:
// - mass M0 = 100 amu, length σ = 1 nm, energy ε = k_B · 298 K (k_BT = 1), time t0 = σ √(M0/ε);
// - water's kinematic viscosity is 5.6757 σ²/t0; a run at another ν_sim (0.8 in the paper) with
//   nominal (water-equivalent) bead frictions simulates them scaled by s = ν_sim/ν_water, and every
//   friction it measures maps back to water by 1/s (diffusion coefficients by s).
#include <nlohmann/json.hpp>

namespace anisodyn::lb {

struct SiUnits {
  static constexpr double kAmu = 1.66053906660e-27;      ///< kg
  static constexpr double kBoltzmann = 1.380649e-23;     ///< J/K
  static constexpr double kMass = 100.0 * kAmu;          ///< M0 in kg
  static constexpr double kLength = 1e-9;                ///< σ in m
  static constexpr double kTemperature = 298.0;          ///< K
  static constexpr double kEnergy = kBoltzmann * kTemperature;  ///< ε in J
  static constexpr double kWaterViscosity = 5.6757;      ///< ν of water in σ²/t0 (spec 40 §1)

  /// t0 = σ √(M0/ε) in s.
  static double time();
  /// The SI value of one unit of friction (M0/t0, kg/s), of dynamic viscosity (M0/(σ t0), Pa s),
  /// of velocity (σ/t0, m/s) and of diffusion coefficient (σ²/t0, m²/s).
  static double friction() { return kMass / time(); }
  static double dynamic_viscosity() { return kMass / (kLength * time()); }
  static double velocity() { return kLength / time(); }
  static double diffusion() { return kLength * kLength / time(); }
};

/// The viscosity scaling of a run (spec 40 §1.1): s = ν_sim/ν_water when the bead frictions are
/// nominal (water-equivalent), else 1.
struct ViscosityScaling {
  double simulated_viscosity = 0.8;  ///< ν_sim, σ²/t0
  bool xi_bead_is_nominal = true;

  double friction_scale() const { return xi_bead_is_nominal ? simulated_viscosity / SiUnits::kWaterViscosity : 1.0; }
  /// A friction measured in the run, in water units (ξ/s); a diffusion coefficient, likewise (D s).
  double friction_to_water(double xi) const { return xi / friction_scale(); }
  double diffusion_to_water(double d) const { return d * friction_scale(); }
};

/// What every anisodyn-lb output records of its units: the SI value of each reduced unit, the
/// scaling and the simulated fluid's η = ρ ν.
nlohmann::json units_record(const ViscosityScaling& scaling, double density);

}  // namespace anisodyn::lb
