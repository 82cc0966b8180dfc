#include "anisodyn/lb/si_units.hpp"

#include <cmath>

namespace anisodyn::lb {

double SiUnits::time() { return kLength * std::sqrt(kMass / kEnergy); }

nlohmann::json units_record(const ViscosityScaling& scaling, double density) {
  const double s = scaling.friction_scale();
  return {{"mass_kg", SiUnits::kMass},
          {"length_m", SiUnits::kLength},
          {"energy_J", SiUnits::kEnergy},
          {"temperature_K", SiUnits::kTemperature},
          {"time_s", SiUnits::time()},
          {"friction_kg_per_s", SiUnits::friction()},
          {"dynamic_viscosity_Pa_s", SiUnits::dynamic_viscosity()},
          {"diffusion_m2_per_s", SiUnits::diffusion()},
          {"water_kinematic_viscosity", SiUnits::kWaterViscosity},
          {"simulated_kinematic_viscosity", scaling.simulated_viscosity},
          {"simulated_dynamic_viscosity", density * scaling.simulated_viscosity},
          {"xi_bead_is_nominal", scaling.xi_bead_is_nominal},
          {"friction_scale", s},
          {"note", "frictions measured in the run map to water by 1/friction_scale, diffusion coefficients by friction_scale (spec 40 §1.1)"}};
}

}  // namespace anisodyn::lb
