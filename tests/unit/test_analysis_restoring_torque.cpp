// Method III (spec 20 §6.3) against rods integrated here by an independent Itô scheme, û ←
// (û + D_r (T×û) h + √(2D_r h)(ξ₁ê₁ + ξ₂ê₂)) / |…| with kT = 1, under an external orientational
// potential U = −(κ/2)(û·ẑ)² (torque T = −û×∂U/∂û = κ(û·ẑ) û×ẑ), the torque at each frame written as
// the `systematic_torque` element. The stage's D_r(φ, t) must equal −½ d ln C₁/dt of its own directly
// measured C₁ (central differences), and the reconstructed C₁ the direct one, both within 4
// standard errors of the difference over replicas; free rods give βT_r ≡ 0 and D_r(φ, t) = D_r.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "anisodyn/analysis/restoring_torque.hpp"
#include "anisodyn/core/quaternion.hpp"
#include "scratch_dir.hpp"
#include "synthetic_trajectory.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;
using anisodyn::testing_support::SyntheticTrajectory;

namespace {

constexpr double kDr = 1.0;
constexpr double kFrameSpacing = 0.02;
constexpr std::size_t kFrames = 51;
constexpr int kSubsteps = 40;

Vec3 torque_of(const Vec3& u, double kappa) { return kappa * u.z() * u.cross(Vec3::UnitZ()); }

/// One Itô step of a rod axis under torque T (kT = 1).
Vec3 ito_step(const Vec3& u, const Vec3& T, double h, std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  const Vec3 helper = std::abs(u.x()) < 0.5 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 e1 = u.cross(helper).normalized(), e2 = u.cross(e1);
  const double s = std::sqrt(2 * kDr * h);
  const double x1 = g(rng), x2 = g(rng);
  return (u + kDr * T.cross(u) * h + s * (x1 * e1 + x2 * e2)).normalized();
}

/// n rods equilibrated for 1/D_r under U = −(κ/2)(û·ẑ)², then kFrames frames kFrameSpacing apart.
SyntheticTrajectory rods_in_potential(std::size_t n, double kappa, unsigned seed) {
  SyntheticTrajectory t = anisodyn::testing_support::gaussian_walks(n, anisodyn::testing_support::linear_times(kFrames, kFrameSpacing),
                                                                  Vec3::Zero(), seed);
  t.table = {Species{"rod", Shape::spherocylinder(5.0, 0.1), 1.0, Vec3(1, 1, 2), Vec3(kDr, kDr, 0)}};
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  const double h = kFrameSpacing / kSubsteps;
  std::vector<Vec3> u(n);
  for (auto& a : u) a = Vec3(g(rng), g(rng), g(rng)).normalized();
  for (int s = 0; s < static_cast<int>(1.0 / h); ++s)
    for (auto& a : u) a = ito_step(a, torque_of(a, kappa), h, rng);
  t.orientation.assign(kFrames, std::vector<Quat>(n));
  std::vector<std::vector<double>> torque(kFrames, std::vector<double>(3 * n));
  for (std::size_t f = 0; f < kFrames; ++f) {
    if (f > 0)
      for (int s = 0; s < kSubsteps; ++s)
        for (auto& a : u) a = ito_step(a, torque_of(a, kappa), h, rng);
    for (std::size_t i = 0; i < n; ++i) {
      t.orientation[f][i] = Quat::FromTwoVectors(Vec3::UnitZ(), u[i]);
      const Vec3 T = torque_of(u[i], kappa);
      for (int d = 0; d < 3; ++d) torque[f][3 * i + d] = T[d];
    }
  }
  t.extras.push_back({kSystematicTorque, {3, torque}});
  return t;
}

class RestoringTorqueTest : public anisodyn::testing_support::ScratchDirTest {
 protected:
  RestoringTorqueTest() : ScratchDirTest("restoring_torque") {}

  std::vector<std::string> write_replicas(double kappa, unsigned replicas, unsigned seed) {
    std::vector<std::string> paths;
    for (unsigned r = 0; r < replicas; ++r) {
      paths.push_back(file("kappa" + std::to_string(kappa) + "_" + std::to_string(r) + ".h5"));
      rods_in_potential(300, kappa, seed + r).write(paths.back());
    }
    return paths;
  }

  static RestoringTorqueResult analyse(const std::vector<std::string>& paths) {
    RestoringTorqueSettings s;
    s.lags_per_decade = 0;  // every lag, for the finite differences
    RestoringTorqueAnalysis a(s, paths.size());
    TrajectoryNeeds needs;
    needs.orientations = true;
    needs.elements = {kSystematicTorque};
    for_each_replica(paths, needs, [&](const Trajectory& t, std::size_t) { a.accumulate(t, 0); });
    return a.compute(kDr);
  }
};

/// −d ln C_n/dt / (n(n+1)) at lag index c by a central difference over ±3 frames (adjacent lags
/// share nearly all their noise; the wider base halves the scatter at an O(Δ²) bias far below it).
double decay_rate(const std::vector<double>& cn, const std::vector<double>& lag, std::size_t c, int n) {
  return -(std::log(cn[c + 3]) - std::log(cn[c - 3])) / (lag[c + 3] - lag[c - 3]) / (n * (n + 1));
}

TEST_F(RestoringTorqueTest, FreeRodsHaveNoRestoringTorque) {
  const RestoringTorqueResult r = analyse(write_replicas(0.0, 8, 10));
  ASSERT_EQ(r.lag.size(), kFrames - 1);
  for (std::size_t c = 0; c < r.lag.size(); ++c) {
    EXPECT_EQ(r.beta_torque[c], 0.0);
    EXPECT_EQ(r.dr1[c], kDr);
    EXPECT_EQ(r.dr2[c], kDr);
    EXPECT_NEAR(r.c1_reconstructed[c], std::exp(-2 * kDr * r.lag[c]), 1e-12);
  }
  for (std::size_t c : {std::size_t{0}, r.lag.size() / 2, r.lag.size() - 1})
    EXPECT_NEAR(r.c1[c], std::exp(-2 * kDr * r.lag[c]), 4 * r.c1_error[c]) << "t=" << r.lag[c];
  EXPECT_EQ(r.dr1_plateau.value, kDr);
  EXPECT_GT(r.plateau_lags, 5u);
}

TEST_F(RestoringTorqueTest, TorqueGivesTheDecayRateAndReconstructsC1) {
  const std::vector<std::string> paths = write_replicas(3.0, 8, 100);
  // per replica: D_r(φ, t) − (−½ d ln C₁/dt) and C₁^rec − C₁, then mean ± SE over the replicas
  const std::vector<std::size_t> lags = {3, 6, 12, 25, 40};
  std::vector<std::vector<double>> rate_gap(lags.size()), rate2_gap(lags.size()), rec_gap(lags.size());
  for (const auto& p : paths) {
    const RestoringTorqueResult r = analyse({p});
    for (std::size_t k = 0; k < lags.size(); ++k) {
      const std::size_t c = lags[k];
      rate_gap[k].push_back(r.dr1[c] - decay_rate(r.c1, r.lag, c, 1));
      rate2_gap[k].push_back(r.dr2[c] - decay_rate(r.c2, r.lag, c, 2));
      rec_gap[k].push_back(r.c1_reconstructed[c] - r.c1[c]);
    }
  }
  const RestoringTorqueResult all = analyse(paths);
  for (std::size_t k = 0; k < lags.size(); ++k) {
    const Estimate rate = mean_and_error(rate_gap[k]), rate2 = mean_and_error(rate2_gap[k]), rec = mean_and_error(rec_gap[k]);
    const std::size_t c = lags[k];
    std::printf("t = %.2f: C1 %.4f, D_r(phi,t) %.4f ± %.4f, -dlnC1/dt/2 %.4f; gap %.5f ± %.5f; n = 2 gap %.5f ± %.5f; "
                "C1_rec - C1 %.5f ± %.5f\n",
                all.lag[c], all.c1[c], all.dr1[c], all.dr1_error[c], decay_rate(all.c1, all.lag, c, 1), rate.value, rate.error,
                rate2.value, rate2.error, rec.value, rec.error);
    EXPECT_LT(std::abs(rate.value), 4 * rate.error) << "t=" << all.lag[c];
    EXPECT_LT(std::abs(rate2.value), 4 * rate2.error) << "t=" << all.lag[c];
    EXPECT_LT(std::abs(rec.value), 4 * rec.error) << "t=" << all.lag[c];
  }
  // the torque matters: the late-time D_r(φ, t) is well below the free D_r
  EXPECT_LT(all.dr1_plateau.value, kDr - 10 * all.dr1_plateau.error);
  std::printf("plateau t = %.3f … %.3f: D_r(phi)/D_r = %.4f ± %.4f, n = 2: %.4f ± %.4f, betaT_r %.4f ± %.4f\n", all.plateau_t_min,
              all.plateau_t_max, all.dr1_plateau.value, all.dr1_plateau.error, all.dr2_plateau.value, all.dr2_plateau.error,
              all.beta_torque_plateau.value, all.beta_torque_plateau.error);
}

}  // namespace
