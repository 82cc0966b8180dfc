// Microrheology stages on data with known answers (spec 50 §6):
//   - a tracer in a viscous fluid (Gaussian walks with D = k_BT/(6πηa)): G″ = ηω, G′ = 0 by both the
//     Mason GSER and the Evans compliance method, through the trajectory pipeline;
//   - the exact MSD of a probe in a Maxwell fluid, J(t) = 1/G0 + t/η: Evans against the exact moduli,
//     Mason against the closed form of the GSER for that MSD, and Mason against the exact moduli (the
//     GSER's own error near ωλ ≈ 1, measured and printed), and the second-order GSER against Evans
//     (the 5 % agreement of spec 50 §6) and against its own closed form;
//   - a pulled tracer alone (drift D_s βF plus diffusion): γ_eff/γ_0 = 1; the tracer_position observable;
//   - density maps of an ideal bath (= 1), of a bath with a known empty cylinder behind the tracer
//     (on-axis profile and wake length), and the local order of an aligned bath (U = 1);
//   - bad input at the library level.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <random>

#include "anisodyn/analysis/active_microrheology.hpp"
#include "anisodyn/analysis/fitting.hpp"
#include "anisodyn/analysis/passive_microrheology.hpp"
#include "anisodyn/core/box.hpp"
#include "anisodyn/core/error.hpp"
#include "scratch_dir.hpp"
#include "synthetic_trajectory.hpp"
#include "time_window.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;
using anisodyn::testing_support::gaussian_walks;
using anisodyn::testing_support::linear_times;
using anisodyn::testing_support::SyntheticTrajectory;

namespace {

constexpr double kPi = std::numbers::pi;

class MicrorheologyTest : public anisodyn::testing_support::ScratchDirTest {
 protected:
  MicrorheologyTest() : ScratchDirTest("microrheology") {}
};

TrajectoryNeeds positions_and_observables() {
  TrajectoryNeeds needs;
  needs.positions = true;
  needs.orientations = true;
  needs.observables = {"tracer_position"};
  return needs;
}

// ---------------------------------------------------------------------------------------------
// Passive: viscous fluid through the trajectory pipeline

TEST_F(MicrorheologyTest, ViscousFluidGivesLossModulusEtaOmegaAndNoStorageModulusByBothMethods) {
  const double kT = 1.0, eta = 2.0, a = 0.5;  // a from the species' sphere of diameter 1
  const double D = kT / (6 * kPi * eta * a);
  std::vector<std::string> paths;
  for (unsigned r = 0; r < 16; ++r) {
    paths.push_back(file("viscous" + std::to_string(r) + ".h5"));
    gaussian_walks(40, linear_times(301, 0.05), Vec3(D, D, D), 500 + r).write(paths.back());
  }
  PassiveMicrorheologySettings s;
  s.species = "A";
  s.radius = resolve_tracer_radius(s, SyntheticTrajectory{}.table, "cfg.json");
  ASSERT_DOUBLE_EQ(s.radius, a);
  PassiveMicrorheology p(s, paths.size());
  for_each_replica(paths, positions_and_observables(), [&](const Trajectory& t, std::size_t) { p.accumulate(t); });
  const PassiveResult r = p.compute();
  ASSERT_GT(r.time.size(), 20u);
  EXPECT_EQ(r.samples, 16u);
  EXPECT_NEAR(r.d_long.value, D, 4 * r.d_long.error);
  EXPECT_NEAR(r.evans_t_max, r.fit_t_max, 1e-9);  // the Evans sum stops at the end of the D_long window
  // A handful of frequencies across the grid (every one would be many correlated 4σ comparisons).
  const std::size_t n = r.time.size();
  for (std::size_t k : {std::size_t{3}, n / 5, 2 * n / 5, 3 * n / 5, 4 * n / 5}) {
    const double w = r.mason.omega[k];
    std::printf("viscous: omega %7.3f  G''/(eta omega): Mason %.4f ± %.4f, Evans %.4f ± %.4f;  G'/(eta omega): Mason %+.4f ± %.4f, Evans %+.4f ± %.4f\n",
                w, r.mason.loss[k] / (eta * w), r.mason_error.loss[k] / (eta * w), r.evans.loss[k] / (eta * w), r.evans_error.loss[k] / (eta * w),
                r.mason.storage[k] / (eta * w), r.mason_error.storage[k] / (eta * w), r.evans.storage[k] / (eta * w),
                r.evans_error.storage[k] / (eta * w));
    ASSERT_FALSE(std::isnan(r.mason.loss[k])) << "t=" << r.time[k];
    EXPECT_NEAR(r.mason.loss[k], eta * w, 4 * r.mason_error.loss[k]) << "Mason G'' at omega=" << w;
    EXPECT_NEAR(r.mason.storage[k], 0.0, 4 * r.mason_error.storage[k]) << "Mason G' at omega=" << w;
    EXPECT_NEAR(r.mason.alpha[k], 1.0, 4 * r.mason_error.alpha[k]) << "alpha at omega=" << w;
    EXPECT_NEAR(r.mason2.loss[k], eta * w, 4 * r.mason2_error.loss[k]) << "second-order GSER G'' at omega=" << w;
    EXPECT_NEAR(r.mason2.storage[k], 0.0, 4 * r.mason2_error.storage[k]) << "second-order GSER G' at omega=" << w;
    EXPECT_NEAR(r.mason2.curvature[k], 0.0, 4 * r.mason2_error.curvature[k]) << "curvature at omega=" << w;
    EXPECT_NEAR(r.evans.loss[k], eta * w, 4 * r.evans_error.loss[k]) << "Evans G'' at omega=" << w;
    EXPECT_NEAR(r.evans.storage[k], 0.0, 4 * r.evans_error.storage[k]) << "Evans G' at omega=" << w;
    // the errors are real errors, positive and small enough for the 4 SE comparisons to bite
    EXPECT_GT(r.mason_error.loss[k], 0.0);
    EXPECT_LT(r.mason_error.loss[k], 0.2 * eta * w);
  }
  // the shortest lags have fewer than 4 points within ±0.25 decade: no Mason value there
  EXPECT_TRUE(std::isnan(r.mason.loss[0]));
}

// ---------------------------------------------------------------------------------------------
// Passive: exact Maxwell-fluid MSD fed to the closed-form functions

struct MaxwellFluid {
  double kT = 1.0, a = 0.5, G0 = 2.0, eta = 3.0;
  double lambda() const { return eta / G0; }
  double msd(double t) const { return kT / (kPi * a) * (1.0 / G0 + t / eta); }
  double storage(double w) const { const double x = w * lambda(); return G0 * x * x / (1 + x * x); }
  double loss(double w) const { const double x = w * lambda(); return G0 * x / (1 + x * x); }
  double d_long() const { return kT / (kPi * a * eta) / 6.0; }  // MSD slope / 6
};

/// t_k = t_min 10^(k/per_decade), the log grid of a DMC-style MSD.
std::vector<double> log_grid(double t_min, double t_max, double per_decade) {
  std::vector<double> t;
  for (int k = 0;; ++k) {
    const double v = t_min * std::pow(10.0, k / per_decade);
    if (v > t_max * (1 + 1e-9)) break;
    t.push_back(v);
  }
  return t;
}

TEST(MaxwellFluid, EvansMatchesTheExactModuliOverTheWellSampledRange) {
  const MaxwellFluid m;
  const auto t = log_grid(1e-4 * m.lambda(), 1e4 * m.lambda(), 10);
  std::vector<double> msd, omega;
  for (double v : t) { msd.push_back(m.msd(v)); omega.push_back(1.0 / v); }
  const Moduli e = evans_moduli(t, msd, m.a, m.kT, m.d_long(), omega);
  // Well-sampled range: 10/t_max ≤ ω ≤ 0.1/t_min. With J(0) = 0 the elastic jump J(0+) = 1/G0 becomes
  // a ramp over [0, t_1]; it adds ≈ (ωt_1/2)|G*| to G″ (derived: (1 − e^{−iωt_1})/t_1 = iω(1 − iωt_1/2 + …)),
  // which is ≤ 5 % of |G*| in the range but exceeds 5 % of G″ itself once ω²t_1λ/2 > 0.05.
  const double w_lo = 10.0 / t.back(), w_hi = 0.1 / t.front(), w_loss = std::sqrt(0.1 / (t.front() * m.lambda()));
  double worst_gp = 0, worst_gpp_own = 0, worst_gpp_modulus = 0;
  int points = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double w = omega[k];
    if (w < w_lo * (1 - 1e-9) || w > w_hi * (1 + 1e-9)) continue;
    const double gp = m.storage(w), gpp = m.loss(w), modulus = std::hypot(gp, gpp);
    worst_gp = std::max(worst_gp, std::abs(e.storage[k] / gp - 1));
    worst_gpp_modulus = std::max(worst_gpp_modulus, std::abs(e.loss[k] - gpp) / modulus);
    if (w <= w_loss) worst_gpp_own = std::max(worst_gpp_own, std::abs(e.loss[k] / gpp - 1));
    ++points;
  }
  std::printf("Evans vs exact Maxwell, omega*lambda in [%g, %g] (%d points): worst |dG'/G'| = %.4f, worst |dG''|/|G*| = %.4f, "
              "worst |dG''/G''| for omega*lambda <= %.3g: %.4f\n",
              w_lo * m.lambda(), w_hi * m.lambda(), points, worst_gp, worst_gpp_modulus, w_loss * m.lambda(), worst_gpp_own);
  EXPECT_EQ(points, 61);
  // The implementation against the compliance formula summed in closed form for this J: the slopes
  // beyond t_1 are all 1/η, so the sum telescopes to iω/G* = (1 − e^{−iωt_1}) J_1/t_1 + e^{−iωt_1}/η.
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double w = omega[k], t1 = t.front(), j1 = kPi * m.a / m.kT * msd.front();
    const std::complex<double> ph = std::exp(std::complex<double>(0, -w * t1));
    const std::complex<double> g = std::complex<double>(0, w) / ((1.0 - ph) * j1 / t1 + ph / m.eta);
    EXPECT_NEAR(e.storage[k], g.real(), 1e-9 * std::abs(g)) << "omega=" << w;
    EXPECT_NEAR(e.loss[k], g.imag(), 1e-9 * std::abs(g)) << "omega=" << w;
  }
  EXPECT_LT(worst_gp, 0.05);
  EXPECT_LT(worst_gpp_modulus, 0.05);
  EXPECT_LT(worst_gpp_own, 0.05);
}

TEST(MaxwellFluid, MasonFollowsTheGserClosedFormAndItsErrorAgainstEvansIsMeasured) {
  const MaxwellFluid m;
  const auto t = log_grid(1e-4 * m.lambda(), 1e4 * m.lambda(), 10);
  std::vector<double> msd;
  for (double v : t) msd.push_back(m.msd(v));
  const Moduli g = mason_moduli(t, msd, m.a, m.kT);
  const Moduli e = evans_moduli(t, msd, m.a, m.kT, m.d_long(), g.omega);
  const double w_lo = 10.0 / t.back(), w_hi = 0.1 / t.front();
  // The GSER applied to this MSD in closed form: α = d ln J/d ln t at t = 1/ω is 1/(1 + ωλ), so
  // |G*| = 1/(J(1/ω) Γ(1 + α)) = G0 ωλ / ((1 + ωλ) Γ(1 + α)). The implementation must reproduce it up
  // to the ±0.25-decade quadratic fit of ln MSD (measured below).
  double worst_alpha = 0, worst_closed = 0;
  double worst_gp_dominant = 0, worst_gpp_dominant = 0, worst_near_crossover = 0, worst_vs_evans = 0, worst_vs_evans_w = 0;
  std::printf("  omega*lambda   Mason/exact G'  G''   Evans/exact G'  G''   Mason/Evans G'  G''\n");
  int row = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double w = g.omega[k], x = w * m.lambda();
    if (w < w_lo * (1 - 1e-9) || w > w_hi * (1 + 1e-9)) continue;
    const double alpha = 1.0 / (1.0 + x);
    const double modulus = m.G0 * x / ((1.0 + x) * std::tgamma(1.0 + alpha));
    worst_alpha = std::max(worst_alpha, std::abs(g.alpha[k] - alpha));
    worst_closed = std::max({worst_closed, std::abs(g.storage[k] / (modulus * std::cos(kPi * alpha / 2)) - 1),
                             std::abs(g.loss[k] / (modulus * std::sin(kPi * alpha / 2)) - 1)});
    const double dgp = g.storage[k] / m.storage(w) - 1, dgpp = g.loss[k] / m.loss(w) - 1;
    if (x >= 10) worst_gp_dominant = std::max(worst_gp_dominant, std::abs(dgp));
    if (x <= 0.05) worst_gpp_dominant = std::max(worst_gpp_dominant, std::abs(dgpp));
    if (x >= 0.3 && x <= 3) worst_near_crossover = std::max({worst_near_crossover, std::abs(dgp), std::abs(dgpp)});
    const double me = std::max(std::abs(g.storage[k] / e.storage[k] - 1), std::abs(g.loss[k] / e.loss[k] - 1));
    if (me > worst_vs_evans) { worst_vs_evans = me; worst_vs_evans_w = x; }
    if (row++ % 5 == 0)
      std::printf("  %10.3g   %+8.3f %+8.3f      %+8.3f %+8.3f      %+8.3f %+8.3f\n", x, dgp, dgpp, e.storage[k] / m.storage(w) - 1,
                  e.loss[k] / m.loss(w) - 1, g.storage[k] / e.storage[k] - 1, g.loss[k] / e.loss[k] - 1);
  }
  std::printf("Mason vs its closed form: worst |d alpha| = %.4f, worst relative modulus deviation = %.4f\n", worst_alpha, worst_closed);
  std::printf("Mason vs exact: dominant modulus worst %.4f (G', omega*lambda >= 10), %.4f (G'', omega*lambda <= 0.05); "
              "worst %.4f for 0.3 <= omega*lambda <= 3; worst Mason/Evans disagreement %.4f at omega*lambda = %.3g\n",
              worst_gp_dominant, worst_gpp_dominant, worst_near_crossover, worst_vs_evans, worst_vs_evans_w);
  EXPECT_LT(worst_alpha, 0.01);
  EXPECT_LT(worst_closed, 0.05);
  // Where one modulus dominates, the GSER gives it within 5 %.
  EXPECT_LT(worst_gp_dominant, 0.05);
  EXPECT_LT(worst_gpp_dominant, 0.05);
  // Near the crossover the GSER itself is ~20 % low (α changes quickly there): it is the method, not
  // the implementation (the closed-form check above), so the spec's 5 % Mason–Evans agreement does
  // not hold at ωλ ≈ 1. Pin the measured size so that a change shows.
  // at ωλ = 1: α = 1/2, |G*| = G0/(2Γ(3/2)), G′ = |G*| cos(π/4), 20.2 % below the exact G0/2
  const double gser = m.G0 / (2.0 * std::tgamma(1.5)) * std::cos(kPi / 4);
  EXPECT_NEAR(g.storage[t.size() / 2] / gser - 1.0, 0.0, 1e-3);  // t_40 = λ: ωλ = 1 on the grid
  EXPECT_GT(worst_near_crossover, 0.15);
}

TEST(MaxwellFluid, SecondOrderGserAgreesWithEvansWithinFivePercentOverTheWellSampledRange) {
  const MaxwellFluid m;
  const auto t = log_grid(1e-4 * m.lambda(), 1e4 * m.lambda(), 10);
  std::vector<double> msd;
  for (double v : t) msd.push_back(m.msd(v));
  const Moduli g = mason_moduli(t, msd, m.a, m.kT, kMasonHalfWidthDecades, GserOrder::Second);
  const Moduli e = evans_moduli(t, msd, m.a, m.kT, m.d_long(), g.omega);
  const double w_lo = 10.0 / t.back(), w_hi = 0.1 / t.front();
  // Closed form for this MSD: α = x'/(1 + x') with x' = t/λ at t = 1/ω, i.e. α = 1/(1 + ωλ), and
  // β = dα/d ln t = α(1 − α). The reference transform factor Γ(1 + α)e^{−iπα/2}(1 + (β/2)F''/F) takes
  // F''(α) = ∂²_α[Γ(1 + α) e^{−iπα/2}] by finite differences of std::tgamma, independent of the
  // digamma/trigamma route of the implementation.
  auto reference = [&](double w) {
    const double alpha = 1.0 / (1.0 + w * m.lambda()), beta = alpha * (1 - alpha), h = 1e-4;
    auto F = [](double a) { return std::tgamma(1.0 + a) * std::exp(std::complex<double>(0.0, -kPi * a / 2)); };
    const std::complex<double> f2 = (F(alpha + h) - 2.0 * F(alpha) + F(alpha - h)) / (h * h);
    return std::complex<double>(m.kT / (kPi * m.a * m.msd(1.0 / w))) / (F(alpha) + 0.5 * beta * f2);
  };
  double worst_curvature = 0, worst_closed = 0, worst_modulus = 0, worst_own = 0, worst_vs_exact = 0;
  double worst_modulus_all = 0, worst_modulus_all_at = 0, worst_modulus_all_at_value = 0;
  double own_lo = 0, own_hi = 0;
  int points = 0;
  std::printf("  omega*lambda   Mason2/Evans G'  G''   Mason2/exact G'  G''\n");
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double w = g.omega[k], x = w * m.lambda();
    if (w < w_lo * (1 - 1e-9) || w > w_hi * (1 + 1e-9)) continue;
    ++points;
    const double alpha = 1.0 / (1.0 + x);
    worst_curvature = std::max(worst_curvature, std::abs(g.curvature[k] - alpha * (1 - alpha)));
    const std::complex<double> ref = reference(w);
    worst_closed = std::max(worst_closed, std::abs(std::complex<double>(g.storage[k], g.loss[k]) - ref) / std::abs(ref));
    // Mason against Evans: each modulus relative to |G*| everywhere, and relative to itself
    const double modulus = std::hypot(e.storage[k], e.loss[k]);
    const double dgp = g.storage[k] - e.storage[k], dgpp = g.loss[k] - e.loss[k];
    const double relative_to_modulus = std::max(std::abs(dgp), std::abs(dgpp)) / modulus;
    worst_modulus_all = std::max(worst_modulus_all, relative_to_modulus);
    if (relative_to_modulus > worst_modulus_all_at_value) { worst_modulus_all_at_value = relative_to_modulus; worst_modulus_all_at = x; }
    // Evans's own error from the ramp J(0) = 0 → J_1 is ≈ (ωt_1/2)|G*| (previous test): the comparison
    // holds Evans to half the budget, ωt_1 ≤ 0.05.
    if (w * t.front() <= 0.05 * (1 + 1e-9)) worst_modulus = std::max(worst_modulus, relative_to_modulus);
    const double own = std::max(std::abs(dgp / e.storage[k]), std::abs(dgpp / e.loss[k]));
    if (x >= 0.15 && x <= 3) worst_own = std::max(worst_own, own);
    if (own < 0.05 && (own_lo == 0 || x < own_lo)) own_lo = x;
    if (own < 0.05) own_hi = std::max(own_hi, x);
    worst_vs_exact = std::max({worst_vs_exact, std::abs(g.storage[k] - m.storage(w)) / std::hypot(m.storage(w), m.loss(w)),
                               std::abs(g.loss[k] - m.loss(w)) / std::hypot(m.storage(w), m.loss(w))});
    if (points % 5 == 1)
      std::printf("  %10.3g   %+8.3f %+8.3f      %+8.3f %+8.3f\n", x, g.storage[k] / e.storage[k] - 1, g.loss[k] / e.loss[k] - 1,
                  g.storage[k] / m.storage(w) - 1, g.loss[k] / m.loss(w) - 1);
  }
  std::printf("second-order GSER, omega*lambda in [%g, %g] (%d points): worst |d curvature| = %.4f, worst vs its closed form = %.4f; "
              "Mason2 vs Evans worst |dG|/|G*| = %.4f for omega*t_1 <= 0.05 (omega*lambda <= %.3g), %.4f over the whole range (at omega*lambda = %.3g); "
              "worst |dG/G| for 0.15 <= omega*lambda <= 3 = %.4f; "
              "both moduli within 5%% of Evans at omega*lambda from %.3g to %.3g; Mason2 vs exact worst |dG|/|G*| = %.4f\n",
              w_lo * m.lambda(), w_hi * m.lambda(), points, worst_curvature, worst_closed, worst_modulus, 0.05 / t.front() * m.lambda(), worst_modulus_all, worst_modulus_all_at, worst_own,
              own_lo, own_hi,
              worst_vs_exact);
  EXPECT_EQ(points, 61);
  EXPECT_LT(worst_curvature, 0.01);
  EXPECT_LT(worst_closed, 0.01);
  EXPECT_LT(worst_modulus, 0.05);
  EXPECT_LT(worst_own, 0.05);
  EXPECT_LT(worst_vs_exact, 0.05);
}

TEST(MaxwellFluid, SecondOrderGserReducesToTheFirstOrderForAPowerLaw) {
  // MSD ∝ t^0.6 has zero log curvature: both orders give |G*| = k_BT/(π a MSD Γ(1.6)), phase 0.3π.
  std::vector<double> t = log_grid(1e-3, 1e3, 10), msd;
  for (double v : t) msd.push_back(0.7 * std::pow(v, 0.6));
  const Moduli a = mason_moduli(t, msd, 0.5, 1.0, kMasonHalfWidthDecades, GserOrder::First);
  const Moduli b = mason_moduli(t, msd, 0.5, 1.0, kMasonHalfWidthDecades, GserOrder::Second);
  int compared = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (std::isnan(a.storage[k])) continue;
    ++compared;
    const double modulus = 1.0 / (kPi * 0.5 * msd[k] * std::tgamma(1.6));
    EXPECT_NEAR(b.curvature[k], 0.0, 1e-9);
    EXPECT_NEAR(b.storage[k], a.storage[k], 1e-9 * modulus);
    EXPECT_NEAR(b.loss[k], a.loss[k], 1e-9 * modulus);
    EXPECT_NEAR(a.storage[k], modulus * std::cos(0.3 * kPi), 1e-9 * modulus);
  }
  EXPECT_GT(compared, 50);
}

// ---------------------------------------------------------------------------------------------
// Active: effective friction of a free tracer

/// One pulled tracer alone: z gains v dt plus N(0, 2 D dt) per frame, x and y diffuse.
SyntheticTrajectory pulled_tracer(std::size_t frames, double dt, double D, double v, unsigned seed, const Vec3& box = Vec3(10, 10, 30)) {
  SyntheticTrajectory t;
  t.box = box;
  t.time = linear_times(frames, dt);
  t.table = {Species{"tracer", Shape::sphere(1.0), 1.0, Vec3(D, D, D), Vec3::Zero()}};
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  t.position.assign(frames, std::vector<Vec3>(1, Vec3(5, 5, 5)));
  for (std::size_t f = 1; f < frames; ++f)
    for (int a = 0; a < 3; ++a)
      t.position[f][0][a] = t.position[f - 1][0][a] + (a == 2 ? v * dt : 0.0) + std::sqrt(2 * D * dt) * g(rng);
  return t;
}

TEST_F(MicrorheologyTest, FreePulledTracerHasFrictionRatioOne) {
  const double D = 1.0 / (3.0 * kPi), beta_force = 10.0, v = D * beta_force;
  std::vector<std::string> paths;
  for (unsigned r = 0; r < 30; ++r) {
    paths.push_back(file("free" + std::to_string(r) + ".h5"));
    pulled_tracer(401, 0.025, D, v, 40 + r).write(paths.back());
  }
  ActiveMicrorheologySettings s;
  s.species = "tracer";
  nlohmann::json details;
  s.peclet = beta_force * 0.5;  // βF = Pe / a with a = 0.5 from the sphere; D_s from the species table
  resolve_active_defaults(s, pulled_tracer(2, 1.0, D, 0.0, 1).table, nlohmann::json::object(), "cfg.json", details);
  ASSERT_DOUBLE_EQ(s.beta_force, beta_force);
  ASSERT_DOUBLE_EQ(s.D_s, D);
  ActiveMicrorheology a(s, paths.size());
  std::vector<Trajectory> kept;
  for_each_replica(paths, positions_and_observables(), [&](const Trajectory& t, std::size_t) {
    a.accumulate(t);
    if (kept.size() < 3) kept.push_back(t);
  });
  const ActiveResult r = a.compute();
  ASSERT_EQ(r.replicas.size(), 30u);
  EXPECT_FALSE(r.has_map);  // no bath
  EXPECT_EQ(r.path_source, "frames (unwrapped tracer position)");
  EXPECT_NEAR(r.velocity.value, v, 4 * r.velocity.error);
  EXPECT_NEAR(r.gamma_ratio.value, 1.0, 4 * r.gamma_ratio.error);
  EXPECT_LT(r.gamma_ratio.error, 0.05);
  std::printf("free tracer: gamma_eff/gamma_0 = %.4f ± %.4f, <v> = %.4f ± %.4f (D_s beta F = %.4f)\n", r.gamma_ratio.value, r.gamma_ratio.error,
              r.velocity.value, r.velocity.error, v);
  // The steady part starts at the first frame where the tracer has moved 2σ along the force.
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const auto& p = r.replicas[k];
    const std::size_t f = p.first;
    ASSERT_GT(f, 0u);
    EXPECT_GE(kept[k].pos(f, 0).z() - kept[k].pos(0, 0).z(), 2.0);
    for (std::size_t e = 0; e < f; ++e) EXPECT_LT(kept[k].pos(e, 0).z() - kept[k].pos(0, 0).z(), 2.0);
    EXPECT_EQ(p.points, 401 - f);
  }
}

TEST(SteadyVelocity, EndToEndDriftIsUnbiasedWithTheBrownianVarianceAndBeatsTheLeastSquaresSlope) {
  // 400 independent drifting walks (D = 0.1, v = 0.5) sampled at 201 points over t in [0, 20]:
  // the end-to-end drift has variance 2D/T, the least-squares slope of the same path 6/5 of that.
  const double D = 0.1, v = 0.5, dt = 0.1;
  const std::size_t walks = 400, points = 201;
  std::vector<double> drift, fitted, reported_error;
  for (unsigned w = 0; w < walks; ++w) {
    const SyntheticTrajectory t = pulled_tracer(points, dt, D, v, 7000 + w);
    std::vector<double> time = t.time, z;
    for (const auto& frame : t.position) z.push_back(frame[0].z() - t.position[0][0].z());
    const SteadyVelocity s = steady_velocity(time, z, 1.0, 0.0);  // from t = 0
    ASSERT_EQ(s.first, 0u);
    ASSERT_EQ(s.points, points);
    EXPECT_DOUBLE_EQ(s.velocity, (z.back() - z.front()) / (time.back() - time.front()));
    drift.push_back(s.velocity);
    reported_error.push_back(s.velocity_error);
    fitted.push_back(fit_line(time, z).slope);
  }
  const double T = dt * static_cast<double>(points - 1), expected_sd = std::sqrt(2 * D / T);
  const Estimate m = mean_and_error(drift);
  EXPECT_NEAR(m.value, v, 4 * m.error);
  const double sd = m.error * std::sqrt(static_cast<double>(walks));
  // The sample sd of n Gaussian values has relative SE 1/√(2(n − 1)) ≈ 3.5% here: 4 SE.
  EXPECT_NEAR(sd, expected_sd, 4 * expected_sd / std::sqrt(2.0 * (walks - 1)));
  const double fitted_sd = mean_and_error(fitted).error * std::sqrt(static_cast<double>(walks));
  EXPECT_NEAR(fitted_sd, std::sqrt(1.2) * expected_sd, 4 * std::sqrt(1.2) * expected_sd / std::sqrt(2.0 * (walks - 1)));
  EXPECT_LT(sd, fitted_sd);
  // The per-path error, from the path's own increments, is σ/√T on average.
  const Estimate per_path = mean_and_error(reported_error);
  EXPECT_LT(per_path.error, 0.01 * expected_sd);  // 200 increments per path: σ² to ~5%, the mean of 400 to ~0.2%
  EXPECT_NEAR(per_path.value, expected_sd, 4 * per_path.error + 0.001 * expected_sd);  // + the O(1/n) bias of a square root
}

TEST_F(MicrorheologyTest, ZeroForceIsAPassiveReferenceWithNoFrictionRatio) {
  const double D = 1.0 / (3.0 * kPi);
  std::vector<std::string> paths;
  for (unsigned r = 0; r < 20; ++r) {
    paths.push_back(file("pe0_" + std::to_string(r) + ".h5"));
    pulled_tracer(201, 0.05, D, 0.0, 300 + r).write(paths.back());
  }
  nlohmann::json j = {{"species", "tracer"}, {"pe", 0.0}};
  tool::ConfigNode cfg(j, "cfg.json");
  ActiveMicrorheologySettings s = parse_active_microrheology_settings(cfg);
  cfg.finish();
  nlohmann::json details;
  resolve_active_defaults(s, pulled_tracer(2, 1.0, D, 0.0, 1).table, nlohmann::json::object(), "cfg.json", details);
  ASSERT_EQ(s.beta_force, 0.0);
  ASSERT_TRUE(s.steady_from.has_value());  // no transient: the whole run
  EXPECT_EQ(*s.steady_from, 0.0);
  ActiveMicrorheology a(s, paths.size(), "cfg.json");
  for_each_replica(paths, positions_and_observables(), [&](const Trajectory& t, std::size_t) { a.accumulate(t); });
  const ActiveResult r = a.compute();
  EXPECT_NEAR(r.velocity.value, 0.0, 4 * r.velocity.error);
  EXPECT_LT(r.velocity.error, 0.1);  // √(2D/T)/√20 = 0.024 expected
  EXPECT_TRUE(std::isnan(r.gamma_ratio.value));
  // steady_distance cannot mean anything without a drift
  nlohmann::json bad = {{"species", "tracer"}, {"pe", 0.0}, {"steady_distance", 1.0}};
  tool::ConfigNode bad_cfg(bad, "cfg.json");
  ActiveMicrorheologySettings b = parse_active_microrheology_settings(bad_cfg);
  try {
    resolve_active_defaults(b, pulled_tracer(2, 1.0, D, 0.0, 1).table, nlohmann::json::object(), "cfg.json", details);
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "steady_distance");
  }
}

/// The pulled tracer "tracer" with free diffusion D and drift velocity v = D βF.
ActiveMicrorheologySettings tracer_settings(double D, double v) {
  ActiveMicrorheologySettings s;
  s.species = "tracer";
  s.beta_force = v / D;
  s.D_s = D;
  return s;
}

/// `frames` with the tracer path of `path` (its particle 0) recorded as the tracer_position observable.
SyntheticTrajectory with_observed_path(SyntheticTrajectory frames, const SyntheticTrajectory& path) {
  std::vector<std::pair<double, std::vector<double>>> rows;
  for (std::size_t f = 0; f < path.time.size(); ++f) rows.push_back({path.time[f], {path.position[f][0].x(), path.position[f][0].y(), path.position[f][0].z()}});
  frames.observables.push_back({"tracer_position", rows});
  return frames;
}

TEST_F(MicrorheologyTest, SingleReplicaUsesTimeBlocksAndTheTracerPositionObservableWins) {
  const double D = 0.1, v = 2.0;
  // The frames hold a tracer that does not move; the observable (recorded more often) holds the pulled path.
  SyntheticTrajectory t = with_observed_path(pulled_tracer(21, 1.0, D, 0.0, 3), pulled_tracer(2001, 0.01, D, v, 4));
  for (auto& frame : t.position) frame[0] = Vec3(5, 5, 5);
  const std::string p = file("obs.h5");
  t.write(p);
  ActiveMicrorheologySettings s = tracer_settings(D, v);
  ActiveMicrorheology a(s, 1);
  for_each_replica({p}, positions_and_observables(), [&](const Trajectory& tr, std::size_t) { a.accumulate(tr); });
  const ActiveResult r = a.compute();
  EXPECT_EQ(r.path_source, "observable tracer_position");
  EXPECT_EQ(r.velocity_samples, 10u);
  ASSERT_FALSE(std::isnan(r.gamma_ratio.error));
  EXPECT_NEAR(r.gamma_ratio.value, 1.0, 4 * r.gamma_ratio.error);
  // forcing the frames: the tracer never moves 2σ → InputError naming steady_distance
  s.source = TracerPathSource::Frames;
  ActiveMicrorheology frames_only(s, 1, "cfg.json");
  try {
    for_each_replica({p}, positions_and_observables(), [&](const Trajectory& tr, std::size_t) { frames_only.accumulate(tr); });
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "steady_distance");
  }
}

TEST_F(MicrorheologyTest, AWindowLimitsTheTracerPathObservableToItsTimes) {
  const double D = 0.1, v = 2.0;
  const SyntheticTrajectory t = with_observed_path(pulled_tracer(21, 1.0, D, 0.0, 5), pulled_tracer(2001, 0.01, D, v, 6));
  const std::string p = file("window.h5");
  t.write(p);
  ActiveMicrorheologySettings s = tracer_settings(D, v);
  s.steady_distance = 0.0;  // steady from the window's first sample
  s.density_map = false;
  TrajectoryNeeds needs = positions_and_observables();
  needs.window = anisodyn::testing_support::time_window(10.0, 15.0);
  ActiveMicrorheology a(s, 1);
  for_each_replica({p}, needs, [&](const Trajectory& tr, std::size_t) { a.accumulate(tr); });
  const ActiveResult r = a.compute();
  EXPECT_EQ(r.path_source, "observable tracer_position");
  // the fitted path is the observable's rows with 10 ≤ t ≤ 15 (501 rows at 0.01 τ)
  EXPECT_NEAR(r.replicas[0].t_start, 10.0, 1e-9);
  EXPECT_NEAR(r.replicas[0].t_end, 15.0, 1e-9);
  EXPECT_EQ(r.replicas[0].points, 501u);
  EXPECT_NEAR(r.gamma_ratio.value, 1.0, 4 * r.gamma_ratio.error);
}

// ---------------------------------------------------------------------------------------------
// Active: density maps (in-memory replicas: many bath particle-frames, no file I/O)

struct BathSpec {
  Vec3 box = Vec3(8, 8, 16);
  std::size_t frames = 60, bath = 800;
  double D = 0.1, v = 1.0, dt = 0.1;
  bool anisotropic = false, aligned = false;
  // bath centres are uniform in the box outside this region of tracer-frame separations (dz, rho_c)
  std::function<bool(double dz, double rho)> excluded = [](double, double) { return false; };
};

Trajectory bath_replica(const BathSpec& b, unsigned seed) {
  Trajectory t;
  t.path = "memory-" + std::to_string(seed);
  t.frames = b.frames;
  t.particles = 1 + b.bath;
  t.species_table = {Species{"tracer", Shape::sphere(1.0), 1.0, Vec3(b.D, b.D, b.D), Vec3::Zero()},
                     Species{"bath", b.anisotropic ? Shape::cuboid(1, 2, 4) : Shape::sphere(1.0), 1.0, Vec3::Ones(), Vec3::Ones()}};
  t.species.assign(t.particles, 1);
  t.species[0] = 0;
  for (std::size_t i = 0; i < t.particles; ++i) t.id.push_back(static_cast<std::int64_t>(i));
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Box box(b.box);
  // body L (z) along lab x: a quarter turn about y
  const Quat q = b.aligned ? Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitY())) : Quat::Identity();
  Vec3 tracer(4, 4, 4);
  for (std::size_t f = 0; f < b.frames; ++f) {
    t.time.push_back(static_cast<double>(f) * b.dt);
    t.step.push_back(static_cast<std::int64_t>(f));
    for (int a = 0; a < 3; ++a) t.box.push_back(b.box[a]);
    if (f > 0)
      for (int a = 0; a < 3; ++a) tracer[a] += (a == 2 ? b.v * b.dt : 0.0) + std::sqrt(2 * b.D * b.dt) * g(rng);
    for (int a = 0; a < 3; ++a) t.position.push_back(tracer[a]);
    for (std::size_t j = 0; j < b.bath; ++j) {
      Vec3 r;
      for (;;) {  // an ideal gas, independent at every frame
        r = Vec3(u(rng) * b.box.x(), u(rng) * b.box.y(), u(rng) * b.box.z());
        const Vec3 d = box.min_image(r - tracer);
        if (!b.excluded(d.z(), std::hypot(d.x(), d.y()))) break;
      }
      for (int a = 0; a < 3; ++a) t.position.push_back(r[a]);
    }
    if (b.anisotropic)
      for (std::size_t i = 0; i < t.particles; ++i)
        for (double c : {q.w(), q.x(), q.y(), q.z()}) t.orientation.push_back(c);
  }
  return t;
}

ActiveResult run_map(const BathSpec& b, std::size_t replicas, ActiveMicrorheologySettings s) {
  ActiveMicrorheology a(s, replicas);
  for (std::size_t r = 0; r < replicas; ++r) a.accumulate(bath_replica(b, 900 + static_cast<unsigned>(r)));
  return a.compute();
}

ActiveMicrorheologySettings map_settings() {
  ActiveMicrorheologySettings s;
  s.species = "tracer";
  s.beta_force = 10.0;
  s.D_s = 0.1;
  return s;
}

TEST(DensityMap, IdealBathIsUniformWithinItsErrors) {
  const BathSpec b;
  const ActiveResult r = run_map(b, 20, map_settings());
  ASSERT_TRUE(r.has_map);
  EXPECT_FALSE(r.has_order);  // spherical bath
  EXPECT_EQ(r.grid.nz, 64u);   // |dz| ≤ L_z/2 = 8 in bins of 0.25 (Decision)
  EXPECT_EQ(r.grid.nrho, 16u); // rho_c ≤ L_x/2 = 4
  EXPECT_EQ(r.map_samples, 20u);
  // Volume-weighted mean over the map: exactly 1 in expectation (the bins lie inside the minimum-image cell).
  double wsum = 0, mean = 0, var = 0;
  std::size_t beyond = 0, bins = r.density.size();
  for (std::size_t k = 0; k < r.grid.nz; ++k)
    for (std::size_t m = 0; m < r.grid.nrho; ++m) {
      const std::size_t i = k * r.grid.nrho + m;
      const double w = r.grid.ring_volume(m);
      wsum += w;
      mean += w * r.density[i];
      var += w * w * r.density_error[i] * r.density_error[i];
      if (std::abs(r.density[i] - 1.0) > 4 * r.density_error[i]) ++beyond;
      EXPECT_TRUE(std::isnan(r.order[i]));
    }
  mean /= wsum;
  const double se = std::sqrt(var) / wsum;
  std::printf("ideal bath: mean density %.5f ± %.5f, %zu of %zu bins beyond 4 SE\n", mean, se, beyond, bins);
  EXPECT_NEAR(mean, 1.0, 4 * se);
  // per bin: |t| > 4 with 19 degrees of freedom has probability 8e-4; 1 % allows for the skew of small counts
  EXPECT_LT(static_cast<double>(beyond), 0.01 * static_cast<double>(bins));
  double axis_mean = 0, axis_var = 0;
  for (std::size_t k = 0; k < r.grid.nz; ++k) { axis_mean += r.on_axis[k]; axis_var += r.on_axis_error[k] * r.on_axis_error[k]; }
  axis_mean /= static_cast<double>(r.grid.nz);
  EXPECT_NEAR(axis_mean, 1.0, 4 * std::sqrt(axis_var) / static_cast<double>(r.grid.nz));
  EXPECT_DOUBLE_EQ(r.on_axis_radius_used, 0.5);
}

TEST(DensityMap, EmptyCylinderBehindTheTracerGivesTheOnAxisProfileAndWakeLength) {
  // No bath centre within rho_c < 1 and -3 < dz < 0 of the tracer: the on-axis (rho_c < 0.5) density is
  // 0 there and c = V/(V − V_hole) elsewhere, the wake ends between the bin centres at distances 2.875
  // (density 0) and 3.125 (density c), at 2.875 + 0.25 · 0.9/c by the linear interpolation.
  BathSpec b;
  b.excluded = [](double dz, double rho) { return rho < 1.0 && dz > -3.0 && dz < 0.0; };
  const double c = b.box.prod() / (b.box.prod() - kPi * 1.0 * 3.0);
  const ActiveResult r = run_map(b, 20, map_settings());
  const auto& g = r.grid;
  double outside = 0, outside_var = 0;
  int n_out = 0;
  for (std::size_t k = 0; k < g.nz; ++k) {
    const double z = g.dz_centre(k);
    if (z > -3 && z < 0) {
      EXPECT_EQ(r.on_axis[k], 0.0) << "dz=" << z;
    } else {
      outside += r.on_axis[k];
      outside_var += r.on_axis_error[k] * r.on_axis_error[k];
      ++n_out;
    }
  }
  EXPECT_NEAR(outside / n_out, c, 4 * std::sqrt(outside_var) / n_out);
  const double expected = 2.875 + 0.25 * 0.9 / c;
  std::printf("wake length %.4f ± %.4f (expected %.4f)\n", r.wake_length.value, r.wake_length.error, expected);
  EXPECT_NEAR(r.wake_length.value, expected, 4 * r.wake_length.error);
  EXPECT_GT(r.wake_length.error, 0.0);
  EXPECT_LT(r.wake_length.error, 0.05);
  // in front of the tracer the map is undisturbed: the first bins upstream are at c
  const std::size_t front = g.nz / 2;
  EXPECT_NEAR(r.on_axis[front], c, 4 * r.on_axis_error[front]);
}

TEST(DensityMap, AlignedBathHasLocalOrderOneAndSteadyFromSelectsFrames) {
  BathSpec b;
  b.anisotropic = true;
  b.aligned = true;
  b.bath = 200;
  b.frames = 20;
  ActiveMicrorheologySettings s = map_settings();
  s.order_axis = 2;  // L, along lab x in every bath particle
  s.steady_from = 1.05;  // frames at t = 1.1 … 1.9
  const ActiveResult r = run_map(b, 3, s);
  ASSERT_TRUE(r.has_order);
  EXPECT_EQ(r.steady_frames, 3u * 9u);
  std::size_t filled = 0;
  for (std::size_t i = 0; i < r.order.size(); ++i)
    if (r.particle_frames[i] > 0) {
      EXPECT_NEAR(r.order[i], 1.0, 1e-12);
      ++filled;
    }
  EXPECT_GT(filled, r.order.size() / 2);
  for (const auto& p : r.replicas) EXPECT_NEAR(p.t_start, 1.1, 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Bad input and configuration

TEST_F(MicrorheologyTest, MissingTracerSpeciesIsAnInputError) {
  const std::string p = file("walk.h5");
  gaussian_walks(5, linear_times(11, 0.1), Vec3(1, 1, 1), 1).write(p);
  PassiveMicrorheologySettings s;
  s.species = "probe";
  s.radius = 0.5;
  PassiveMicrorheology passive(s, 1, "cfg.json");
  try {
    for_each_replica({p}, positions_and_observables(), [&](const Trajectory& t, std::size_t) { passive.accumulate(t); });
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "species");
    EXPECT_NE(std::string(e.what()).find("probe"), std::string::npos);
  }
  // the active mode: a tracer species with five particles is not a single pulled tracer
  ActiveMicrorheologySettings a = map_settings();
  a.species = "A";
  ActiveMicrorheology active(a, 1, "cfg.json");
  EXPECT_THROW(for_each_replica({p}, positions_and_observables(), [&](const Trajectory& t, std::size_t) { active.accumulate(t); }), InputError);
  // no radius and a non-spherical species
  PassiveMicrorheologySettings cube;
  cube.species = "C";
  EXPECT_THROW(resolve_tracer_radius(cube, {Species{"C", Shape::cuboid(1, 1, 1), 1.0, Vec3::Ones(), Vec3::Ones()}}, "cfg.json"), InputError);
  PassiveMicrorheologySettings negative;
  negative.species = "A";
  negative.radius = -1.0;
  EXPECT_THROW(PassiveMicrorheology(negative, 1), InputError);
}

TEST(MicrorheologySettings, KeysAreParsedAndCheckedWithTheirPaths) {
  nlohmann::json j = {{"species", "tracer"}, {"force", 4.0}, {"kT", 2.0}, {"direction", {0, 0, -1}}, {"bin_width", 0.5},
                      {"rho_bin", 0.2}, {"steady_from", 3.0}, {"order_axis", "W"}, {"position_source", "frames"}};
  tool::ConfigNode cfg(j, "cfg.json");
  const ActiveMicrorheologySettings s = parse_active_microrheology_settings(cfg);
  cfg.finish();
  EXPECT_DOUBLE_EQ(s.beta_force, 2.0);
  EXPECT_EQ(s.direction, Vec3(0, 0, -1));
  EXPECT_DOUBLE_EQ(s.dz_bin, 0.5);
  EXPECT_DOUBLE_EQ(s.rho_bin, 0.2);
  EXPECT_EQ(s.order_axis, 1);
  EXPECT_EQ(s.source, TracerPathSource::Frames);
  ASSERT_TRUE(s.steady_from.has_value());

  nlohmann::json bad = {{"species", "tracer"}, {"direction", {1, 1, 0}}};
  tool::ConfigNode bad_cfg(bad, "cfg.json");
  try {
    parse_active_microrheology_settings(bad_cfg);
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "direction");
  }
  nlohmann::json both = {{"species", "tracer"}, {"beta_force", 1.0}, {"pe", 1.0}};
  tool::ConfigNode both_cfg(both, "cfg.json");
  EXPECT_THROW(parse_active_microrheology_settings(both_cfg), InputError);
  // steady_from decides where the steady part starts: steady_distance beside it has no effect
  nlohmann::json window_twice = {{"species", "tracer"}, {"steady_from", 1.0}, {"steady_distance", 1.0}};
  tool::ConfigNode twice_cfg(window_twice, "cfg.json");
  try {
    parse_active_microrheology_settings(twice_cfg);
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "steady_distance");
  }

  nlohmann::json p = {{"species", "probe"}, {"tracer_diameter", 3.0}, {"fit", {{"t_min", 10.0}, {"t_max", 100.0}}}};
  tool::ConfigNode pcfg(p, "cfg.json");
  const PassiveMicrorheologySettings ps = parse_passive_microrheology_settings(pcfg);
  pcfg.finish();
  EXPECT_DOUBLE_EQ(ps.radius, 1.5);
  EXPECT_EQ(ps.msd.species, "probe");
  ASSERT_TRUE(ps.msd.fit_window.has_value());
}

}  // namespace
