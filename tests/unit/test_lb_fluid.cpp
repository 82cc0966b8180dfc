// The D3Q19 fluid (lb/d3q19.hpp, lb/lb_fluid.hpp) against exact references: the mode basis's
// orthogonality in integers, the equilibrium's modes in closed form, conservation of mass and
// momentum to round-off (with noise, forces and walls), the decay of a shear wave against
// exp(−ν k² t), Couette, plug and Poiseuille flow between bounce-back walls against their closed
// forms, the same bits on one and two threads, and the refusal of bad parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "anisodyn/core/error.hpp"
#include "anisodyn/lb/fluid_checks.hpp"
#include "anisodyn/lb/lb_fluid.hpp"
#include "thread_count.hpp"

using namespace anisodyn;
using namespace anisodyn::lb;
using anisodyn::lb::checks::channel_profile;
using anisodyn::lb::checks::shear_wave_viscosity;

TEST(D3Q19, TheModeBasisIsOrthogonalWithTheSpecsNorms) {
  // 36 w_i is 12, 2 or 1, and 36 b_k an integer: Σ_i 36 w_i e_ki e_li = 36 b_k δ_kl in integers.
  for (int k = 0; k < kQ; ++k)
    for (int l = 0; l < kQ; ++l) {
      long sum = 0;
      for (int i = 0; i < kQ; ++i) sum += std::lround(36.0 * kW[i]) * kE[k][i] * kE[l][i];
      ASSERT_EQ(sum, k == l ? std::lround(36.0 * kB[k]) : 0) << k << " " << l;
    }
}

TEST(D3Q19, VelocitiesAndWeightsHaveTheLatticeMoments) {
  double w = 0.0;
  for (int i = 0; i < kQ; ++i) {
    w += kW[i];
    EXPECT_EQ(opposite(opposite(i)), i);
    for (int a = 0; a < 3; ++a) EXPECT_EQ(kC[opposite(i)][a], -kC[i][a]) << i;
  }
  EXPECT_DOUBLE_EQ(w, 1.0);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      double second = 0.0;
      for (int i = 0; i < kQ; ++i) second += kW[i] * kC[i][a] * kC[i][b];
      EXPECT_NEAR(second, a == b ? kCs2 : 0.0, 1e-15);
    }
}

TEST(LbFluid, EquilibriumPopulationsHaveTheSpecsModes) {
  LbFluid fluid({2, 2, 2}, LbParameters{});
  const double rho = 1.3;
  const Vec3 u(0.05, -0.02, 0.03), j = rho * u;
  fluid.set_equilibrium(3, rho, u);
  const auto m = fluid.modes(3);
  const double expected[10] = {rho,
                               j.x(),
                               j.y(),
                               j.z(),
                               j.squaredNorm() / rho,
                               (2 * j.x() * j.x() - j.y() * j.y() - j.z() * j.z()) / rho,
                               (j.y() * j.y() - j.z() * j.z()) / rho,
                               j.x() * j.y() / rho,
                               j.y() * j.z() / rho,
                               j.z() * j.x() / rho};
  for (int k = 0; k < 10; ++k) EXPECT_NEAR(m[static_cast<std::size_t>(k)], expected[k], 1e-15) << k;
  for (int k = kFirstGhostMode; k < kQ; ++k) EXPECT_NEAR(m[static_cast<std::size_t>(k)], 0.0, 1e-15) << k;
}

TEST(LbFluid, AUniformFlowIsAFixedPoint) {
  LbFluid fluid({4, 3, 5}, LbParameters{1.0, 0.016, 0.0, 0.0, 0.0, 1});
  for (std::size_t n = 0; n < fluid.nodes(); ++n) fluid.set_equilibrium(n, 1.2, Vec3(0.04, 0.01, -0.03));
  const std::vector<double> before = fluid.populations();
  for (int s = 0; s < 10; ++s) fluid.step();
  for (std::size_t k = 0; k < before.size(); ++k) ASSERT_NEAR(fluid.populations()[k], before[k], 1e-15) << k;
}

namespace {

/// A fluid of random populations near rest (so every mode is excited), noise on, with walls; the
/// large one has enough nodes (4096) to be stepped on several threads.
LbFluid noisy_fluid(bool walls, bool large = false) {
  LbParameters p{6.004, 0.016, 0.1, -0.2, 4e-4, 77};
  LbFluid fluid(large ? std::array<int, 3>{16, 16, 16} : std::array<int, 3>{6, 5, 7}, p);
  std::uint64_t state = 12345;
  auto uniform = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  for (std::size_t n = 0; n < fluid.nodes(); ++n)
    fluid.set_equilibrium(n, p.density * (1.0 + 0.01 * (uniform() - 0.5)), Vec3(uniform() - 0.5, uniform() - 0.5, uniform() - 0.5) * 0.02);
  if (walls)
    for (int z = 0; z < fluid.dims()[2]; ++z)
      for (int x = 0; x < fluid.dims()[0]; ++x) fluid.set_solid(fluid.node(x, 0, z));
  return fluid;
}

}  // namespace

TEST(LbFluid, MassAndMomentumAreConservedToRoundOff) {
  LbFluid fluid = noisy_fluid(false);
  const double mass = fluid.total_mass();
  const Vec3 momentum = fluid.total_momentum();
  for (int s = 0; s < 200; ++s) fluid.step();
  EXPECT_NEAR(fluid.total_mass(), mass, 1e-12 * mass);
  EXPECT_LT((fluid.total_momentum() - momentum).norm(), 1e-12 * mass);
  // A force adds its impulse, exactly: forces on three nodes and a body force on all.
  const Vec3 before = fluid.total_momentum();
  fluid.add_force(0, Vec3(1e-3, 0, 0));
  fluid.add_force(17, Vec3(0, -2e-3, 5e-4));
  fluid.add_force(17, Vec3(1e-4, 0, 0));
  fluid.set_body_force(Vec3(0, 0, 1e-5));
  fluid.step();
  const Vec3 impulse = Vec3(1.1e-3, -2e-3, 5e-4) + static_cast<double>(fluid.nodes()) * Vec3(0, 0, 1e-5);
  EXPECT_LT((fluid.total_momentum() - before - impulse).norm(), 1e-12 * mass);
  EXPECT_NEAR(fluid.total_mass(), mass, 1e-12 * mass);
}

TEST(LbFluid, BounceBackWallsConserveMass) {
  LbFluid fluid = noisy_fluid(true);
  const double mass = fluid.total_mass();
  for (int s = 0; s < 200; ++s) fluid.step();
  EXPECT_NEAR(fluid.total_mass(), mass, 1e-12 * mass);
}

TEST(LbFluid, OneAndTwoThreadsGiveTheSameBits) {
#ifdef _OPENMP
  auto run = [](int threads) {
    return testing_support::with_threads(threads, [] {
      LbFluid fluid = noisy_fluid(true, true);
      for (int s = 0; s < 30; ++s) {
        fluid.add_force(fluid.node(2, 3, 4), Vec3(1e-3, 2e-3, -1e-3));
        fluid.step();
      }
      return fluid.populations();
    });
  };
  const auto one = run(1);
  EXPECT_EQ(one, run(2));
  EXPECT_EQ(one, run(3));
#else
  GTEST_SKIP() << "built without OpenMP";
#endif
}


TEST(LbFluid, AShearWaveDecaysWithTheViscosity) {
  // Spec 40's ν = 0.016 (τ = 0.548), ν = 1/6 (τ = 1) and ν = 0.5; about one e-fold each, after a
  // start-up of 20 steps (the initial populations carry no viscous stress). The lattice's
  // dispersion adds O(k²) to ν away from τ = 1: 1.3% at ν = 0.5 with 32 nodes per wavelength.
  for (const double nu : {0.016, 1.0 / 6.0, 0.5}) {
    const int length = 64;
    const double k = 2.0 * M_PI / length;
    const int t1 = static_cast<int>(1.0 / (nu * k * k));
    const double measured = shear_wave_viscosity(nu, length, 20, t1);
    std::printf("nu = %.4f: shear-wave nu = %.6f (relative error %.2e)\n", nu, measured, measured / nu - 1.0);
    EXPECT_NEAR(measured / nu, 1.0, 0.01) << nu;
  }
}


TEST(LbFluid, CouetteFlowIsLinearBetweenHalfwayWalls) {
  // Walls at y = 1 and y = h + 1 moving at −U and +U: u(y) = U (2 (y − 1)/h − 1) at the node
  // centres y + ½, exact for halfway bounce-back in the linear regime (at U = 10⁻³ the nodes next
  // to the walls are off by 5×10⁻⁹ U, a term of second order in U; at 10⁻⁴ it is below 10⁻⁹ U).
  const int h = 10;
  const double U = 1e-4;
  const auto u = channel_profile(h, 0.1, -U, U, 0.0);
  for (int y = 1; y <= h; ++y) EXPECT_NEAR(u[static_cast<std::size_t>(y - 1)], U * (2.0 * (y + 0.5 - 1.0) / h - 1.0), 1e-9 * U) << y;
}

TEST(LbFluid, WallsMovingTogetherGivePlugFlow) {
  const double U = 2.8e-4;  // spec 40 §7.2's wall speed in lattice units
  for (double u : channel_profile(12, 0.016 * 10, U, U, 0.0)) EXPECT_NEAR(u, U, 1e-9 * U);
}

TEST(LbFluid, PoiseuilleFlowHasTheParabolicProfile) {
  // u(y) = g/(2ρν) (y − 1)(h + 1 − y) at the node centres. Halfway bounce-back puts the wall
  // exactly halfway when (τ_s − ½)(τ_g − ½) = 3/16 (the odd ghost modes relax fully: τ_g = 1,
  // so ν = 1/8); at other ν the wall is off by a viscosity-dependent slip, measured here too.
  const int h = 16;
  const double g = 1e-6;
  auto worst_relative_error = [&](double nu) {
    const auto u = channel_profile(h, nu, 0.0, 0.0, g);
    const double peak = g / (2.0 * nu) * (h / 2.0) * (h / 2.0);
    double worst = 0.0;
    for (int y = 1; y <= h; ++y) {
      const double yc = y + 0.5;
      worst = std::max(worst, std::abs(u[static_cast<std::size_t>(y - 1)] - g / (2.0 * nu) * (yc - 1.0) * (h + 1.0 - yc)) / peak);
    }
    return worst;
  };
  const double exact = worst_relative_error(0.125);
  std::printf("Poiseuille, largest error relative to the peak: %.2e (nu = 1/8), %.2e (nu = 0.5)\n", exact, worst_relative_error(0.5));
  EXPECT_LT(exact, 1e-8);
  EXPECT_LT(worst_relative_error(0.5), 0.05);
}

TEST(LbFluid, BadParametersAreRefused) {
  EXPECT_THROW(LbFluid({4, 4, 4}, LbParameters{1.0, 0.0, 0.0, 0.0, 0.0, 1}), InputError);   // τ = ½
  EXPECT_THROW(LbFluid({4, 4, 4}, LbParameters{1.0, -0.1, 0.0, 0.0, 0.0, 1}), InputError);  // τ < ½
  EXPECT_THROW(LbFluid({4, 4, 4}, LbParameters{1.0, 0.1, 1.5, 0.0, 0.0, 1}), InputError);
  EXPECT_THROW(LbFluid({4, 4, 4}, LbParameters{1.0, 0.1, 0.0, -1.0, 0.0, 1}), InputError);
  EXPECT_THROW(LbFluid({4, 4, 4}, LbParameters{1.0, 0.1, 0.0, 0.0, -1e-4, 1}), InputError);
  EXPECT_THROW(LbFluid({4, 0, 4}, LbParameters{}), InputError);
  EXPECT_THROW(LbFluid({4, 4, 4}, LbParameters{0.0, 0.1, 0.0, 0.0, 0.0, 1}), InputError);
}

namespace {

/// One deterministic step written the textbook way, node by node in population space: ρ, j from
/// the populations, u = (j + f/2)/ρ, the second-order equilibrium w_i ρ (1 + c·u/c_s² + (c·u)²/2c_s⁴
/// − u²/2c_s²), Guo's forcing population w_i [(c − u)/c_s² + (c·u) c/c_s⁴]·f, both projected on the
/// modes, each mode relaxed as s_k = m_k^eq + γ_k (m_k − m_k^eq) + (1 + γ_k)/2 F_k (γ = 1 for the
/// conserved ones), back by n_i = w_i Σ_k e_ki s_k / b_k and pushed to x + c_i periodically.
std::vector<double> reference_step(const std::array<int, 3>& dims, const std::vector<double>& n, const std::vector<Vec3>& force, const LbParameters& p) {
  const std::size_t nodes = static_cast<std::size_t>(dims[0] * dims[1] * dims[2]);
  std::vector<double> next(n.size());
  double gamma[kQ];
  for (int k = 0; k < kQ; ++k)
    gamma[k] = k < kFirstStressMode ? 1.0 : k == kFirstStressMode ? p.bulk_relaxation : k < kFirstGhostMode ? p.shear_relaxation() : p.ghost_relaxation;
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x) {
        const std::size_t at = static_cast<std::size_t>(x + dims[0] * (y + dims[1] * z));
        double rho = 0.0;
        Vec3 j = Vec3::Zero();
        for (int i = 0; i < kQ; ++i) {
          rho += n[i * nodes + at];
          j += n[i * nodes + at] * Vec3(kC[i][0], kC[i][1], kC[i][2]);
        }
        const Vec3 f = force[at], u = (j + 0.5 * f) / rho;
        double s[kQ];
        for (int k = 0; k < kQ; ++k) {
          double m = 0.0, m_eq = 0.0, f_k = 0.0;
          for (int i = 0; i < kQ; ++i) {
            const Vec3 c(kC[i][0], kC[i][1], kC[i][2]);
            const double cu = c.dot(u);
            const double eq = kW[i] * rho * (1.0 + cu / kCs2 + cu * cu / (2.0 * kCs2 * kCs2) - u.squaredNorm() / (2.0 * kCs2));
            const double guo = kW[i] * ((c - u) / kCs2 + cu * c / (kCs2 * kCs2)).dot(f);
            m += kE[k][i] * n[i * nodes + at], m_eq += kE[k][i] * eq, f_k += kE[k][i] * guo;
          }
          s[k] = m_eq + gamma[k] * (m - m_eq) + 0.5 * (1.0 + gamma[k]) * f_k;
        }
        for (int i = 0; i < kQ; ++i) {
          double post = 0.0;
          for (int k = 0; k < kQ; ++k) post += kE[k][i] * s[k] / kB[k];
          const int tx = (x + kC[i][0] + dims[0]) % dims[0], ty = (y + kC[i][1] + dims[1]) % dims[1], tz = (z + kC[i][2] + dims[2]) % dims[2];
          next[i * nodes + static_cast<std::size_t>(tx + dims[0] * (ty + dims[1] * tz))] = kW[i] * post;
        }
      }
  return next;
}

}  // namespace

TEST(LbFluid, AStepEqualsTheTextbookCollisionInPopulationSpace) {
  // Every compiled collision (bulk and ghosts relaxed fully or not), on a row of whole vectors
  // (16, written with streaming stores) and a ragged one (11), with random populations that excite
  // every mode and a force on every node.
  for (const std::array<int, 3> dims : {std::array<int, 3>{16, 3, 4}, std::array<int, 3>{11, 4, 3}})
    for (const double bulk : {0.0, 0.3})
      for (const double ghost : {0.0, -0.4}) {
        const LbParameters p{6.004, 0.016, bulk, ghost, 0.0, 1};
        LbFluid fluid(dims, p);
        fluid.use_streaming_stores(dims[0] % 8 == 0);
        std::uint64_t state = 99;
        auto uniform = [&state] {
          state = state * 6364136223846793005ULL + 1442695040888963407ULL;
          return static_cast<double>(state >> 11) * 0x1.0p-53;
        };
        std::vector<double> n(kQ * fluid.nodes());
        for (int i = 0; i < kQ; ++i)
          for (std::size_t at = 0; at < fluid.nodes(); ++at) n[i * fluid.nodes() + at] = kW[i] * p.density * (1.0 + 0.1 * (uniform() - 0.5));
        std::vector<Vec3> force(fluid.nodes());
        for (std::size_t at = 0; at < fluid.nodes(); ++at) {
          force[at] = 1e-3 * Vec3(uniform() - 0.5, uniform() - 0.5, uniform() - 0.5);
          fluid.add_force(at, force[at]);
        }
        fluid.restore(n, 0);
        fluid.step();
        const auto expected = reference_step(dims, n, force, p);
        const auto got = fluid.populations();
        double worst = 0.0;
        for (std::size_t k = 0; k < got.size(); ++k) worst = std::max(worst, std::abs(got[k] - expected[k]) / expected[k]);
        EXPECT_LT(worst, 1e-13) << dims[0] << " nodes a row, bulk " << bulk << ", ghost " << ghost;
      }
}

TEST(LbFluid, StreamingStoresGiveTheSameBits) {
  auto run = [](bool streaming) {
    LbFluid fluid = noisy_fluid(true, true);
    fluid.use_streaming_stores(streaming);
    for (int s = 0; s < 20; ++s) {
      fluid.add_force(fluid.node(2, 3, 4), Vec3(1e-3, 2e-3, -1e-3));
      fluid.step();
    }
    return fluid.populations();
  };
  const auto streamed = run(true);
  EXPECT_EQ(streamed, run(false));
  EXPECT_THROW(noisy_fluid(false).use_streaming_stores(true), InputError);  // 6 nodes a row
}
