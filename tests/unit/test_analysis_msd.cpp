// MSD stage on synthetic data with known answers: Gaussian walks with anisotropic D (MSD = 2 D_a t
// per axis, D fit, NGP = 0, β = 1, D_tot = (D_par + 2 D_perp)/3), a walk with a non-Gaussian
// jump law (NGP closed form), and the body-frame components.
#include <gtest/gtest.h>

#include "anisodyn/analysis/msd.hpp"
#include "scratch_dir.hpp"
#include "synthetic_trajectory.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;
using anisodyn::testing_support::gaussian_walks;
using anisodyn::testing_support::linear_times;

namespace {

class MsdTest : public anisodyn::testing_support::ScratchDirTest {
 protected:
  MsdTest() : ScratchDirTest("msd") {}

  MsdResult run(const std::vector<std::string>& paths, MsdSettings s) {
    MsdAnalysis a(s, paths.size());
    TrajectoryNeeds needs;
    needs.positions = true;
    needs.orientations = true;
    for_each_replica(paths, needs, [&](const Trajectory& t, std::size_t) { a.accumulate(t, -1); });
    return a.compute();
  }
};

TEST_F(MsdTest, GaussianWalksGiveLinearMsdPerAxisAndZeroNgp) {
  const Vec3 D(0.5, 0.5, 2.0);
  std::vector<std::string> paths;
  for (unsigned r = 0; r < 10; ++r) {
    paths.push_back(file("walk" + std::to_string(r) + ".h5"));
    gaussian_walks(200, linear_times(201, 0.1), D, 100 + r, Vec3(5, 6, 7)).write(paths.back());
  }
  MsdSettings s;
  s.reference = MsdReference::Vector;
  s.direction = Vec3::UnitZ();
  const MsdResult r = run(paths, s);
  ASSERT_GT(r.lag.size(), 10u);
  EXPECT_TRUE(r.uniform_frames);
  // a few lags across the range (every lag would be many correlated comparisons at 4 σ)
  for (std::size_t c : {std::size_t{0}, r.lag.size() / 4, r.lag.size() / 2, 3 * r.lag.size() / 4}) {
    const double t = r.lag[c];
    const auto check = [&](const char* name, double expected) {
      const auto& comp = r.component(name);
      EXPECT_NEAR(comp.msd[c], expected, 4 * comp.msd_error[c] + 1e-12) << name << " t=" << t;
    };
    check("x", 2 * D.x() * t);
    check("z", 2 * D.z() * t);
    check("par", 2 * D.z() * t);
    check("perp", 2 * (D.x() + D.y()) * t);
    check("tot", 2 * D.sum() * t);
    for (const char* name : {"x", "z", "perp"}) {
      const auto& comp = r.component(name);
      EXPECT_NEAR(comp.ngp[c], 0.0, 4 * comp.ngp_error[c]) << name << " t=" << t;
    }
  }
  // the fit: D per component, D_tot = (D_par + 2 D_perp)/3 identically (spec 50 §1.3)
  const auto& par = r.component("par").diffusion;
  const auto& perp = r.component("perp").diffusion;
  const auto& tot = r.component("tot").diffusion;
  EXPECT_NEAR(par.value, D.z(), 4 * par.error);
  EXPECT_NEAR(perp.value, 0.5 * (D.x() + D.y()), 4 * perp.error);
  EXPECT_NEAR(tot.value, (par.value + 2 * perp.value) / 3, 1e-12 * tot.value);
  EXPECT_NEAR(r.fit_mean_beta, 1.0, 0.05);
}

TEST_F(MsdTest, AnisotropicNgpConstantMakesTheAnisotropicGaussianZero) {
  const Vec3 D(0.2, 0.2, 3.0);
  std::vector<std::string> paths;
  for (unsigned r = 0; r < 3; ++r) {
    paths.push_back(file("aniso" + std::to_string(r) + ".h5"));
    gaussian_walks(300, linear_times(101, 0.05), D, 7 + r).write(paths.back());
  }
  MsdSettings s;
  s.reference = MsdReference::Vector;
  s.direction = Vec3::UnitZ();
  s.ngp_constant = "anisotropic";
  const MsdResult aniso = run(paths, s);
  s.ngp_constant = "isotropic";
  const MsdResult iso = run(paths, s);
  // c'_2,3 for D_par/D_perp = 15: the isotropic 5/3 reads a spurious positive α_2
  const double dp = 3.0, dq = 0.2;
  const double c_aniso = (3 * dp * dp + 8 * dq * dq + 4 * dp * dq) / (dp * dp + 4 * dq * dq + 4 * dp * dq);
  for (std::size_t c = 0; c < aniso.lag.size(); ++c) {
    const auto& a = aniso.component("tot");
    EXPECT_NEAR(a.ngp[c], 0.0, 4 * a.ngp_error[c]);
    EXPECT_NEAR(iso.component("tot").ngp[c], c_aniso / (5.0 / 3.0) - 1.0, 4 * a.ngp_error[c] * c_aniso);
  }
}

TEST_F(MsdTest, NonGaussianJumpsMatchTheClosedFormNgp) {
  // Each frame interval every particle jumps by ±a along x with probability p, else stays:
  // after k intervals the jump count is Binomial(k, p) and
  //   <x²> = k p a²,  <x⁴> = a⁴ (k p (1 − p)(1 − 6p(1 − p))... ) — use the exact moments of a sum of
  // k iid steps s with <s²> = p a², <s⁴> = p a⁴:  <x⁴> = k <s⁴> + 3 k (k − 1) <s²>²,
  // so α_2,1 = <x⁴>/(3<x²>²) − 1 = (1/p − 3)/(3k).
  const double p = 0.1, a = 0.5;
  std::vector<std::string> paths;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  for (unsigned r = 0; r < 4; ++r) {
    auto t = gaussian_walks(500, linear_times(41, 1.0), Vec3(0, 0, 0), 1);
    for (std::size_t f = 1; f < t.time.size(); ++f)
      for (std::size_t i = 0; i < t.particles(); ++i) {
        const double x = u(rng);
        const double step = x < p / 2 ? a : x < p ? -a : 0.0;
        t.position[f][i] = t.position[f - 1][i] + Vec3(step, 0, 0);
      }
    paths.push_back(file("jumps" + std::to_string(r) + ".h5"));
    t.write(paths.back());
  }
  MsdSettings s;
  s.lags_per_decade = 0;  // every lag
  const MsdResult r = run(paths, s);
  const auto& x = r.component("x");
  for (std::size_t c = 0; c < r.lag.size(); ++c) {
    const double k = r.lag[c];
    EXPECT_NEAR(x.msd[c], k * p * a * a, 4 * x.msd_error[c]);
    EXPECT_NEAR(x.ngp[c], (1.0 / p - 3.0) / (3.0 * k), 4 * x.ngp_error[c]) << "k=" << k;
  }
}

TEST_F(MsdTest, SingleReplicaUsesOriginBlocksForErrorsAndLogFramesAreBinned) {
  // log-spaced frames: t_k = 0.01·10^(k/10); the lag classes are log bins
  std::vector<double> time{0.0};
  for (int k = 0; k <= 40; ++k) time.push_back(0.01 * std::pow(10.0, k / 10.0));
  const std::string path = file("log.h5");
  gaussian_walks(400, time, Vec3(1, 1, 1), 11).write(path);
  MsdSettings s;
  const MsdResult r = run({path}, s);
  EXPECT_FALSE(r.uniform_frames);
  EXPECT_EQ(r.samples, 10u);
  for (std::size_t c = 0; c < r.lag.size(); ++c) {
    const auto& tot = r.component("tot");
    if (std::isnan(tot.msd_error[c])) continue;
    EXPECT_NEAR(tot.msd[c], 6 * r.lag[c], 5 * tot.msd_error[c] + 1e-9 * r.lag[c]) << r.lag[c];
  }
}

}  // namespace
