// The closure check (spec 20 §9, spec 50 I4): S⁽⁴⁾:S from (1/N) Σ ûû (û·S·û) against the brute-force
// four-index sum Σ_γδ ⟨û_α û_β û_γ û_δ⟩ S_γδ; both sides ẑẑ at perfect alignment; both I/9 in
// expectation for isotropic random axes; and the stage on a trajectory of aligned rods.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "anisodyn/analysis/closure.hpp"
#include "scratch_dir.hpp"
#include "synthetic_trajectory.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

std::vector<Vec3> random_axes(std::size_t n, std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<Vec3> u(n);
  for (auto& v : u) v = Vec3(g(rng), g(rng), g(rng)).normalized();
  return u;
}

/// Σ_γδ ⟨u_α u_β u_γ u_δ⟩ S_γδ with the 81 components of ⟨uuuu⟩ formed explicitly.
Mat3 brute_force_contraction(const std::vector<Vec3>& axes, const Mat3& s) {
  double s4[3][3][3][3] = {};
  for (const Vec3& u : axes)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int c = 0; c < 3; ++c)
          for (int d = 0; d < 3; ++d) s4[a][b][c][d] += u[a] * u[b] * u[c] * u[d] / static_cast<double>(axes.size());
  Mat3 out = Mat3::Zero();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d) out(a, b) += s4[a][b][c][d] * s(c, d);
  return out;
}

}  // namespace

TEST(ClosureKernels, ContractionEqualsTheFourIndexSum) {
  std::mt19937_64 rng(11);
  for (std::size_t n : {1u, 7u, 200u}) {
    const auto axes = random_axes(n, rng);
    const ClosureSides c = closure_sides(axes);
    EXPECT_LT((c.exact - brute_force_contraction(axes, c.order)).cwiseAbs().maxCoeff(), 1e-15) << n;
    // and with any symmetric tensor in place of S (the contraction is linear in it)
    Mat3 m;
    m << 0.3, -0.2, 0.7, -0.2, 1.1, 0.05, 0.7, 0.05, -0.4;
    EXPECT_LT((fourth_moment_contraction(axes, m) - brute_force_contraction(axes, m)).cwiseAbs().maxCoeff(), 1e-15) << n;
  }
  // the closure by components: (1/5)(2 S_ac S_cb + 3 S_ab S_cd S_cd)
  Mat3 s;
  s << 0.5, 0.1, -0.2, 0.1, 0.3, 0.05, -0.2, 0.05, 0.2;
  double ss = 0;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) ss += s(a, b) * s(a, b);
  const Mat3 closure = closure_approximation(s);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      double sq = 0;
      for (int c = 0; c < 3; ++c) sq += s(a, c) * s(c, b);
      EXPECT_NEAR(closure(a, b), (2 * sq + 3 * s(a, b) * ss) / 5, 1e-15);
    }
}

TEST(ClosureKernels, BothSidesAreZZAtPerfectAlignment) {
  const ClosureSides c = closure_sides(std::vector<Vec3>(50, Vec3::UnitZ()));
  const Mat3 zz = Vec3::UnitZ() * Vec3::UnitZ().transpose();
  EXPECT_EQ(c.order, zz);
  EXPECT_EQ(c.exact, zz);
  EXPECT_EQ(c.closure, zz);
}

TEST(ClosureKernels, BothSidesAreIOverNineAtIsotropy) {
  // M sets of N random axes; the mean of each component against I/9, within 4 standard errors of
  // the mean over sets. The finite-N bias of the exact side, E = I/9 + 2I/(9N), is 4e-5 here,
  // about 0.2 standard errors.
  std::mt19937_64 rng(12);
  constexpr std::size_t M = 40, N = 5000;
  Mat3 sum_e = Mat3::Zero(), sum2_e = Mat3::Zero(), sum_c = Mat3::Zero(), sum2_c = Mat3::Zero();
  for (std::size_t m = 0; m < M; ++m) {
    const ClosureSides c = closure_sides(random_axes(N, rng));
    sum_e += c.exact;
    sum2_e += c.exact.cwiseProduct(c.exact);
    sum_c += c.closure;
    sum2_c += c.closure.cwiseProduct(c.closure);
  }
  const double k = static_cast<double>(M);
  for (const auto& [sum, sum2] : {std::pair{sum_e, sum2_e}, std::pair{sum_c, sum2_c}}) {
    const Mat3 mean = sum / k;
    const Mat3 se = ((sum2 / k - mean.cwiseProduct(mean)) * k / (k - 1) / k).cwiseSqrt();
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        EXPECT_NEAR(mean(a, b), a == b ? 1.0 / 9.0 : 0.0, 4 * se(a, b)) << a << b;
        EXPECT_LT(se(a, b), 5e-4);
      }
    std::printf("isotropic: mean xx %.6f (1/9 = %.6f) ± %.1e, xy %.1e ± %.1e\n", mean(0, 0), 1.0 / 9, se(0, 0), mean(0, 1), se(0, 1));
  }
  // S = I/3 exactly (the six axes ±x, ±y, ±z): both sides I/9 exactly.
  const ClosureSides exact = closure_sides({Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitY(), Vec3::UnitZ(), -Vec3::UnitZ()});
  EXPECT_LT((exact.exact - Mat3::Identity() / 9).cwiseAbs().maxCoeff(), 1e-16);
  EXPECT_LT((exact.closure - Mat3::Identity() / 9).cwiseAbs().maxCoeff(), 1e-16);
}

class ClosureFileTest : public anisodyn::testing_support::ScratchDirTest {
 protected:
  ClosureFileTest() : ScratchDirTest("closure") {}
};

TEST_F(ClosureFileTest, AlignedRodsThroughTheStage) {
  // Rods along the lab z (identity quaternions: body L = lab z) in frame 0, along lab x (a quarter
  // turn about y) in frame 1; two replicas.
  std::vector<std::string> paths;
  for (int r = 0; r < 2; ++r) {
    anisodyn::testing_support::SyntheticTrajectory t;
    t.table = {Species{"rod", Shape::spherocylinder(5.0, 0.1), 1.0, Vec3(1, 1, 2), Vec3(0.5, 0.5, 0.0)}};
    t.time = {0.0, 1.0};
    t.position.assign(2, std::vector<Vec3>(10, Vec3(1, 2, 3)));
    const Quat turn(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitY()));
    t.orientation = {std::vector<Quat>(10, Quat::Identity()), std::vector<Quat>(10, turn)};
    paths.push_back(file("rep" + std::to_string(r) + ".h5"));
    t.write(paths.back());
  }
  ClosureAnalysis a(2);
  TrajectoryNeeds needs;
  needs.orientations = true;
  const auto grid = for_each_replica(paths, needs, [&](const Trajectory& t, std::size_t) { a.accumulate(t, 0); });
  const ClosureResult r = a.compute(grid);
  ASSERT_EQ(r.series.size(), 9u);
  const auto at = [&](const std::string& name, std::size_t f) {
    for (const auto& s : r.series)
      if (s.name == name) return s.mean[f];
    return std::nan("");
  };
  for (const char* side : {"S_", "S4S_", "closure_"}) {
    const std::string p(side);
    EXPECT_NEAR(at(p + "zz", 0), 1.0, 1e-12);
    EXPECT_NEAR(at(p + "xx", 0), 0.0, 1e-12);
    EXPECT_NEAR(at(p + "xx", 1), 1.0, 1e-12);
    EXPECT_NEAR(at(p + "zz", 1), 0.0, 1e-12);
    EXPECT_NEAR(at(p + "yy", 1), 0.0, 1e-12);
  }
  EXPECT_EQ(r.rods, 10u);
  EXPECT_EQ(r.replicas, 2u);
}
