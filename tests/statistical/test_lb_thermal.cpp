// The fluctuating D3Q19 fluid (lb/lb_fluid.hpp) at spec 40's parameters (ρ = 6.004, ν = 0.016,
// k_BT = 4×10⁻⁴ in lattice units, γ_b = γ_g = 0) is in thermal equilibrium: every mode k has the
// variance μ ρ b_k (μ = k_BT/c_s²) that the noise is built to give it, and the fluid velocity per
// node and component has ⟨u²⟩ = k_BT/ρ (spec 40 §2.5, test 1). The lattice's total mass and
// momentum are fixed, so the variances of modes 0–3 are short by a factor 1 − 1/N (N nodes).
// Tolerances: 4 standard errors of the mean over 20 blocks of 1000 steps (the blocks are far
// longer than the slowest relaxation, a shear mode of the 8³ box: 1/(ν k²) = 100 steps).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "anisodyn/lb/fluid_checks.hpp"
#include "anisodyn/lb/lb_fluid.hpp"
#include "anisodyn/lb/point_coupling.hpp"

using namespace anisodyn;
using namespace anisodyn::lb;

TEST(LbThermal, EveryModeAndTheVelocityHaveTheirEquilibriumVariance) {
  const LbParameters p{6.004, 0.016, 0.0, 0.0, 4e-4, 2026};
  // spec 40 §2.4's warm-up of 1000 steps, then 20 blocks of 1000 steps sampled every 10th.
  const checks::ModeVariances v = checks::thermal_mode_variances(p, 8, 1000, 20, 1000, 10);
  std::printf("mode  measured/target  SE\n");
  for (int k = 0; k <= kQ; ++k) {
    const auto i = static_cast<std::size_t>(k);
    std::printf("%4s  %.5f          %.5f\n", k == kQ ? "u^2" : std::to_string(k).c_str(), v.ratio[i], v.standard_error[i]);
    EXPECT_LT(std::abs(v.ratio[i] - 1.0), 4.0 * v.standard_error[i]) << "mode " << k;
  }
  EXPECT_LT(std::abs(v.ratio[kQ] - 1.0), 0.01);  // spec 40 §2.5: ⟨u²⟩ within 1%
}

TEST(LbThermal, CoupledBeadsShareTheFluidsTemperature) {
  // Free beads of mass m point-coupled to the thermal fluid (lb/point_coupling.hpp), two MD steps
  // per LB step: equipartition, ⟨m v_α²⟩ = k_BT, up to the explicit step's own bias. A bead kicked
  // by v ← v − a v + (h/m) f_s (a = ξh/m) in fluid at rest has m⟨v²⟩ = k_BT/(1 − a/2): 1.4% hot
  // at a = 0.028, and the target here (measured 2026-11-25: 1.0249 ± 0.0054 of k_BT; at a = 0.14,
  // 1.0822 ± 0.0021 against 1.0753). Spec 40's fluid, ξ = 0.56 (ξ_bead = 200 scaled by
  // s = 0.14095, in lattice units), m = 10.
  const LbParameters p{6.004, 0.016, 0.0, 0.0, 4e-4, 7};
  const checks::CoupledBeads c = checks::coupled_bead_run(p, 8, 16, 10.0, 0.56, 2000, 20, 2000);
  std::printf("beads: <m v^2>/kT = %.4f +- %.4f (target %.4f); largest change of the total momentum %.2e (the fluid's own: %.2e), "
              "of the mass %.2e of %.6g\n",
              c.bead_temperature, c.bead_temperature_se, c.expected_temperature, c.momentum_change, c.fluid_momentum_change, c.mass_change,
              c.initial_mass);
  EXPECT_LT(std::abs(c.bead_temperature - c.expected_temperature), 4.0 * c.bead_temperature_se);
  EXPECT_GT(c.fluid_momentum_change, 1e-3);  // the beads did exchange momentum with the fluid
  // Round-off over 4.2×10⁴ steps of 512 nodes (measured 2026-11-25: momentum 4.8×10⁻¹³, mass 2.3×10⁻¹² of the mass).
  EXPECT_LT(c.momentum_change, 1e-11 * c.initial_mass);
  EXPECT_LT(c.mass_change, 1e-10 * c.initial_mass);
}
