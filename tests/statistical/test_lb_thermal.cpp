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

#include "anisodyn/lb/lb_fluid.hpp"
#include "anisodyn/lb/point_coupling.hpp"

using namespace anisodyn;
using namespace anisodyn::lb;

TEST(LbThermal, EveryModeAndTheVelocityHaveTheirEquilibriumVariance) {
  const LbParameters p{6.004, 0.016, 0.0, 0.0, 4e-4, 2026};
  const int edge = 8;
  LbFluid fluid({edge, edge, edge}, p);
  const double n = static_cast<double>(fluid.nodes());
  for (int s = 0; s < 1000; ++s) fluid.step();  // spec 40 §2.4's warm-up

  constexpr int kBlocks = 20, kStepsPerBlock = 1000, kEvery = 10;
  constexpr int kU = kQ;  // the last column: ⟨u²⟩ per component
  std::vector<std::vector<double>> block(kBlocks, std::vector<double>(kQ + 1, 0.0));
  for (int b = 0; b < kBlocks; ++b) {
    int samples = 0;
    for (int s = 0; s < kStepsPerBlock; ++s) {
      fluid.step();
      if (s % kEvery != 0) continue;
      ++samples;
      for (std::size_t node = 0; node < fluid.nodes(); ++node) {
        const auto m = fluid.modes(node);
        for (int k = 0; k < kQ; ++k) {
          const double d = k == 0 ? m[0] - p.density : m[static_cast<std::size_t>(k)];
          block[b][static_cast<std::size_t>(k)] += d * d / n;
        }
        block[b][kU] += fluid.velocity(node).squaredNorm() / (3.0 * n);
      }
    }
    for (double& v : block[b]) v /= samples;
  }

  const double mu = p.kT / kCs2;
  std::printf("mode  measured/target  SE\n");
  for (int k = 0; k <= kQ; ++k) {
    double mean = 0.0, var = 0.0;
    for (const auto& v : block) mean += v[static_cast<std::size_t>(k)] / kBlocks;
    for (const auto& v : block) var += std::pow(v[static_cast<std::size_t>(k)] - mean, 2) / (kBlocks - 1);
    const double se = std::sqrt(var / kBlocks);
    const double conserved = k < kFirstStressMode || k == kU ? 1.0 - 1.0 / n : 1.0;
    const double target = (k == kU ? p.kT / p.density : mu * p.density * kB[k]) * conserved;
    std::printf("%4s  %.5f          %.5f\n", k == kU ? "u^2" : std::to_string(k).c_str(), mean / target, se / target);
    EXPECT_LT(std::abs(mean - target), 4.0 * se) << "mode " << k;
    if (k == kU) {
      EXPECT_LT(std::abs(mean / target - 1.0), 0.01);  // spec 40 §2.5: within 1%
    }
  }
}

TEST(LbThermal, CoupledBeadsShareTheFluidsTemperature) {
  // Free beads of mass m point-coupled to the thermal fluid (lb/point_coupling.hpp), two MD steps
  // per LB step: equipartition, ⟨m v_α²⟩ = k_BT, up to the explicit step's own bias. A bead kicked
  // by v ← v − a v + (h/m) f_s (a = ξh/m) in fluid at rest has m⟨v²⟩ = k_BT/(1 − a/2): 1.4% hot
  // at a = 0.028, and the target here (measured 2026-11-25: 1.0222 ± 0.0051 of k_BT; at a = 0.14,
  // 1.0822 ± 0.0021 against 1.0753). Spec 40's fluid, ξ = 0.56 (ξ_bead = 200 scaled by
  // s = 0.14095, in lattice units), m = 10.
  const LbParameters p{6.004, 0.016, 0.0, 0.0, 4e-4, 7};
  LbFluid fluid({8, 8, 8}, p);
  const double h = 0.5, mass = 10.0, xi = 0.56;
  const PointCoupling coupling(xi, h, p.kT, 11);
  const std::size_t beads = 16;
  std::vector<Vec3> r, v(beads, Vec3::Zero()), force;
  std::vector<std::uint32_t> id;
  for (std::size_t b = 0; b < beads; ++b) {
    r.emplace_back(0.5 + 0.37 * b, 1.3 + 0.91 * b, 7.7 - 0.45 * b);
    id.push_back(static_cast<std::uint32_t>(b));
  }
  constexpr int kBlocks = 20, kStepsPerBlock = 2000;
  std::vector<double> block(kBlocks, 0.0);
  std::uint64_t md = 0;
  auto lb_step = [&] {
    for (int sub = 0; sub < 2; ++sub) {
      coupling.couple(fluid, r, v, id, md++, force);
      for (std::size_t b = 0; b < beads; ++b) {
        v[b] += (h / mass) * force[b];
        r[b] += h * v[b];
      }
    }
    fluid.step();
  };
  for (int s = 0; s < 2000; ++s) lb_step();
  for (int blk = 0; blk < kBlocks; ++blk) {
    for (int s = 0; s < kStepsPerBlock; ++s) {
      lb_step();
      for (const Vec3& u : v) block[static_cast<std::size_t>(blk)] += mass * u.squaredNorm() / (3.0 * beads * kStepsPerBlock);
    }
  }
  double mean = 0.0, var = 0.0;
  for (double x : block) mean += x / kBlocks;
  for (double x : block) var += (x - mean) * (x - mean) / (kBlocks - 1);
  const double se = std::sqrt(var / kBlocks);
  const double target = p.kT / (1.0 - 0.5 * xi * h / mass);
  std::printf("beads: <m v^2>/kT = %.4f +- %.4f (target %.4f)\n", mean / p.kT, se / p.kT, target / p.kT);
  EXPECT_LT(std::abs(mean - target), 4.0 * se);
}
