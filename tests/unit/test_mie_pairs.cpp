// The pseudo-hard sphere core (interactions/mie_pairs.hpp): the shifted, cut Mie(n, n−1) against
// its closed form, its force against central differences of its energy, the Barker–Henderson
// diameter against an independent integration, and the force field against an O(N²) sum.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/interactions/mie_pairs.hpp"
#include "anisodyn/interactions/pair_force_field.hpp"

using namespace anisodyn;

TEST(MieCore, Mie50_49IsTheSpecsPseudoHardCore) {
  const MieCore c{50.0, 49.0, 1.0};
  EXPECT_NEAR(c.prefactor(), 134.5527, 5e-5);                // spec 30 §4.1
  EXPECT_NEAR(c.cutoff_ratio(), 50.0 / 49.0, 1e-15);         // r_cut − Δ = 50/49 σ
  EXPECT_NEAR(c.energy(1.0, 1.0), 1.0, 1e-12);               // U(σ) = ε
  EXPECT_EQ(c.energy(c.cutoff_ratio() * 1.0, 1.0), 0.0);     // cut at the minimum
  EXPECT_NEAR(c.energy(c.cutoff_ratio() * (1 - 1e-9), 1.0), 0.0, 1e-12);  // and continuous there
  EXPECT_NEAR(c.force(c.cutoff_ratio() * (1 - 1e-9), 1.0), 0.0, 1e-5);    // with its force
  // spec 30 §4.1: F(r) = 134.5527 ε [50 σ⁵⁰/r⁵¹ − 49 σ⁴⁹/r⁵⁰]
  const double r = 0.99;
  EXPECT_NEAR(c.force(r, 1.0), 134.5527 * (50 * std::pow(r, -51) - 49 * std::pow(r, -50)), 1e-3);
}

TEST(MieCore, ForceIsMinusTheDerivativeOfTheEnergy) {
  for (const double n : {12.0, 24.0, 50.0, 100.0}) {
    const MieCore c{n, n - 1.0, 1.5};
    const double sigma = 1.3, h = 1e-7;
    for (double x = 0.9; x < c.cutoff_ratio(); x += 0.004) {
      const double r = x * sigma;
      const double fd = -(c.energy(r + h, sigma) - c.energy(r - h, sigma)) / (2 * h);
      EXPECT_NEAR(c.force(r, sigma), fd, 1e-6 * std::max(1.0, std::abs(fd))) << "n " << n << " r/σ " << x;
    }
  }
}

TEST(MieCore, BarkerHendersonDiameterAgreesWithAnIndependentIntegration) {
  for (const double n : {24.0, 50.0, 100.0}) {
    for (const double beta_epsilon : {1.0, 1.0 / 1.4737}) {
      const MieCore c{n, n - 1.0, beta_epsilon};
      // trapezoid in long double on a finer grid, written out directly from the closed form
      const long double C = n * std::pow(n / (n - 1.0L), n - 1.0L), xc = n / (n - 1.0L);
      const int steps = 400000;
      long double sum = 0.0L;
      for (int k = 0; k <= steps; ++k) {
        const long double x = xc * k / steps;
        const long double u = x < 0.6L ? 1e30L : C * beta_epsilon * (std::pow(1.0L / x, (long double)n) - std::pow(1.0L / x, n - 1.0L)) + beta_epsilon;
        sum += (k == 0 || k == steps ? 0.5L : 1.0L) * (1.0L - std::exp(-u));
      }
      const double reference = static_cast<double>(sum * xc / steps);
      EXPECT_NEAR(barker_henderson_ratio(c, 1.0), reference, 1e-9) << "n " << n << " βε " << beta_epsilon;
      // the effective diameter lies between the contact region and the cut
      EXPECT_GT(reference, 0.97);
      EXPECT_LT(reference, c.cutoff_ratio());
    }
  }
}

TEST(MiePairs, ForceFieldEqualsTheAllPairsSumOfTheCore) {
  // 400 spheres of two species (d = 1 and 0.6) and 20 of a third that does not interact, box 9
  State s;
  s.species = {Species{"big", Shape::sphere(1.0), 1.0, {}, {}}, Species{"small", Shape::sphere(0.6), 1.0, {}, {}},
               Species{"ghost", Shape::sphere(1.0), 1.0, {}, {}}};
  s.box = Box(Vec3::Constant(9.0));
  Rng rng(5, 0);
  for (int i = 0; i < 420; ++i) s.particles.add(i < 300 ? 0 : i < 400 ? 1 : 2, Vec3(rng.uniform(0, 9), rng.uniform(0, 9), rng.uniform(0, 9)), Quat::Identity(), i);
  MiePairs pairs;
  pairs.core = MieCore{50.0, 49.0, 1.0};
  pairs.sigma = {1.0, 0.6, 0.0};
  PairForceField<MiePairs> field(pairs, pairs.cutoffs(), 3, 0.1);
  BodyForces got;
  got.reset(s.particles.size());
  field(s, got);
  std::vector<Vec3> force(s.particles.size(), Vec3::Zero());
  double energy = 0.0;
  int interacting = 0;
  const double size[3] = {1.0, 0.6, 0.0};
  for (std::size_t i = 0; i < s.particles.size(); ++i)
    for (std::size_t j = i + 1; j < s.particles.size(); ++j) {
      const double si = size[s.particles.species[i]], sj = size[s.particles.species[j]];
      if (si == 0.0 || sj == 0.0) continue;
      const double sigma = 0.5 * (si + sj);
      const Vec3 d = s.box.min_image(s.particles.position(j) - s.particles.position(i));
      const double r = d.norm();
      if (r >= pairs.core.cutoff_ratio() * sigma) continue;
      ++interacting;
      energy += pairs.core.energy(r, sigma);
      const Vec3 f = -pairs.core.force(r, sigma) * d / r;
      force[i] += f;
      force[j] -= f;
    }
  ASSERT_GT(interacting, 50);
  EXPECT_NEAR(got.energy, energy, 1e-9 * std::abs(energy));
  for (std::size_t i = 0; i < s.particles.size(); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(got.force[i][k], force[i][k], 1e-9 * (1 + force[i].norm())) << i;
  for (std::size_t i = 400; i < 420; ++i) EXPECT_EQ(got.force[i].norm(), 0.0);
}
