// The lag curves of anisodyn-lb-diffusion (analysis/raspberry_diffusion.hpp): the mean squares per
// lag against a brute-force double loop, and a synthetic anisotropic Brownian body with known
// body-frame D_t,i and D_r,i (axisymmetric rotation) whose curves at one lag give them back, the
// single-vector angle ⟨ΔΘ²⟩ = 2[D_∥ sin²α + D_⊥(1 + cos²α)] τ of spec 40 §8.2 and the three-axis
// sum 12 D̄_r τ, each within 4 standard errors over independent bodies.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "anisodyn/analysis/lb_analytic_checks.hpp"
#include "anisodyn/analysis/raspberry_diffusion.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

TEST(RaspberryDiffusion, MeanSquaresPerLagMatchADoubleLoop) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  std::vector<Vec3> path{Vec3::Zero()};
  for (int n = 0; n < 57; ++n) path.push_back(path.back() + Vec3(normal(rng), normal(rng), 2 * normal(rng)));
  const auto m = component_mean_squares(path, 11);
  ASSERT_EQ(m.size(), 11u);
  for (std::size_t k = 1; k <= 11; ++k) {
    Vec3 sum = Vec3::Zero();
    int count = 0;
    for (std::size_t a = 0; a < path.size(); ++a)
      for (std::size_t b = a + 1; b < path.size(); ++b)
        if (b - a == k) sum += (path[b] - path[a]).cwiseAbs2(), ++count;
    EXPECT_LT((m[k - 1] - sum / count).norm(), 1e-12 * sum.norm()) << k;
  }
}

TEST(RaspberryDiffusion, ASyntheticBodyGivesBackItsDiffusionCoefficients) {
  // D_t,i and D_r,i (∥ = body x), the reference vector 0.9 rad from body x; 300 bodies of 1500 intervals.
  const checks::SyntheticBody b = checks::synthetic_body(Vec3(0.02, 0.05, 0.05), Vec3(4e-4, 1e-3, 1e-3), 0.9, 300, 1500, 17);
  const auto check = [](const checks::Recovered& r, const char* what) {
    std::printf("%-28s %.6g +- %.2g (expected %.6g)\n", what, r.value, r.error, r.expected);
    EXPECT_LT(std::abs(r.pull()), 4.0) << what;
  };
  check(b.lab_msd, "lab MSD at one lag");
  check(b.reference_angle, "reference-vector angle^2");
  check(b.three_axis, "three-axis angle^2");
  for (std::size_t i = 0; i < 3; ++i) {
    check(b.body_msd[i], "body-frame MSD");
    check(b.body_angle[i], "body-frame angle^2");
  }
}
