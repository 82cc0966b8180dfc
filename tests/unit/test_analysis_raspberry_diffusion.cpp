// The lag curves of anisodyn-lb-diffusion (analysis/raspberry_diffusion.hpp): the mean squares per
// lag against a brute-force double loop, and a synthetic anisotropic Brownian body with known
// body-frame D_t,i and D_r,i (axisymmetric rotation) whose curves at one lag give them back, the
// single-vector angle ⟨ΔΘ²⟩ = 2[D_∥ sin²α + D_⊥(1 + cos²α)] τ of spec 40 §8.2 and the three-axis
// sum 12 D̄_r τ, each within 4 standard errors over independent bodies.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

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
  const Vec3 dt_body(0.02, 0.05, 0.05), dr_body(4e-4, 1e-3, 1e-3);  // D_t,i and D_r,i (∥ = body x)
  const double alpha = 0.9;                                            // the reference vector's angle from body x
  const Vec3 reference(std::cos(alpha), std::sin(alpha) * std::cos(0.3), std::sin(alpha) * std::sin(0.3));
  const int bodies = 300, intervals = 1500;
  std::mt19937_64 rng(17);
  std::normal_distribution<double> normal;
  std::vector<std::vector<double>> lag1(BodyLagCurves::kCurves);
  for (int b = 0; b < bodies; ++b) {
    std::vector<Vec3> x{Vec3::Zero()};
    std::vector<Quat> q{Quat(Eigen::AngleAxisd(0.37 * b, Vec3(1, 2, 3).normalized()))};
    for (int n = 0; n < intervals; ++n) {
      const Vec3 theta(std::sqrt(2 * dr_body.x()) * normal(rng), std::sqrt(2 * dr_body.y()) * normal(rng), std::sqrt(2 * dr_body.z()) * normal(rng));
      const Vec3 step(std::sqrt(2 * dt_body.x()) * normal(rng), std::sqrt(2 * dt_body.y()) * normal(rng), std::sqrt(2 * dt_body.z()) * normal(rng));
      // The step in the body frame halfway through the turn (the analysis's midpoint convention).
      const Quat mid = (q.back() * Quat(Eigen::AngleAxisd(0.5 * theta.norm(), theta.normalized()))).normalized();
      x.push_back(x.back() + mid.toRotationMatrix() * step);
      q.push_back((q.back() * Quat(Eigen::AngleAxisd(theta.norm(), theta.normalized()))).normalized());
    }
    const std::vector<double> flat = body_lag_curves(x, q, reference, 1).flatten();
    for (std::size_t c = 0; c < BodyLagCurves::kCurves; ++c) lag1[c].push_back(flat[c]);
  }
  const auto check = [&](std::size_t curve, double expected, const char* what) {
    double m = 0, m2 = 0;
    for (double v : lag1[curve]) m += v, m2 += v * v;
    m /= bodies;
    const double se = std::sqrt((m2 / bodies - m * m) / (bodies - 1));
    std::printf("%-28s %.6g +- %.2g (expected %.6g)\n", what, m, se, expected);
    EXPECT_LT(std::abs(m - expected), 4 * se) << what;
  };
  const double mean_dr = dr_body.sum() / 3;
  check(0, 2 * dt_body.sum(), "lab MSD at one lag");
  check(1, 2 * (dr_body.x() * std::sin(alpha) * std::sin(alpha) + dr_body.y() * (1 + std::cos(alpha) * std::cos(alpha))), "reference-vector angle^2");
  check(2, 12 * mean_dr, "three-axis angle^2");
  for (std::size_t i = 0; i < 3; ++i) {
    check(3 + i, 2 * dt_body[static_cast<int>(i)], "body-frame MSD");
    check(6 + i, 2 * dr_body[static_cast<int>(i)], "body-frame angle^2");
  }
}
