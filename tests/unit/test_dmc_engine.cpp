// DMC engine against free-particle theory (spec 10 §4.8): displacements and rotations of a lone
// particle diffuse with 2Dt per body axis under the time mapping t = (δt/3) Σ A; the pulled
// tracer drifts at DβF with A_t = 1/2 + (1 − e^{−u})/(2u); the rotation proposal leaves the
// orientation distribution uniform; the time-step balance; checkpoints continue bit-for-bit.
#include <gtest/gtest.h>

#include <cmath>

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/statistics.hpp"
#include "anisodyn/dmc/dmc_engine.hpp"
#include "anisodyn/dmc/time_balance.hpp"
#include "markov_chain_error_bound.hpp"

using namespace anisodyn;
using anisodyn::testing_support::markov_chain_error_bound;

namespace {

const Vec3 kBoardDt(0.022, 0.026, 0.031);   // anisotropic body-frame D (T, W, L)
const Vec3 kBoardDr(0.0011, 0.0023, 0.023);

State lone(const Shape& shape, const Vec3& Dt, const Vec3& Dr) {
  State s;
  s.box = Box(Vec3::Constant(100.0));
  s.species.push_back(Species{"p", shape, 1.0, Dt, Dr});
  s.particles.add(0, Vec3(50, 50, 50), Quat::Identity(), 0);
  return s;
}

/// Mean and standard error of independent samples.
std::pair<double, double> mean_se(const std::vector<double>& x) {
  double m = 0.0, v = 0.0;
  for (double a : x) m += a;
  m /= static_cast<double>(x.size());
  for (double a : x) v += (a - m) * (a - m);
  v /= static_cast<double>(x.size() - 1);
  return {m, std::sqrt(v / static_cast<double>(x.size()))};
}


/// Independent random streams per time step: with one stream the displacements at every δt would
/// be the same numbers scaled by δ.
std::uint64_t stream_for(double dt) { return static_cast<std::uint64_t>(std::lround(-std::log10(dt))); }

}  // namespace

class FreeParticle : public ::testing::TestWithParam<double> {};

TEST_P(FreeParticle, SphereMsdPerAxisIsTwoDt) {
  const double dt = GetParam();
  const double D = 1.0 / (3.0 * M_PI);
  State s = lone(Shape::sphere(1.0), Vec3::Constant(D), Vec3::Zero());
  DmcEngine e(s, RngState{7, stream_for(dt), 0, 4}, DmcMoveOptions{});
  e.set_time_steps({dt});
  const int blocks = 4000, block = 50;
  std::array<std::vector<double>, 3> sq;
  Vec3 start = s.box.unwrap(s.particles.position(0), s.particles.image(0));
  double t_block = 0.0;
  for (int b = 0; b < blocks; ++b) {
    double t = 0.0;
    for (int c = 0; c < block; ++c) {
      e.cycle();
      t += dt * e.last_cycle()[0].acceptance() / 3.0;  // A ≡ 1 for a free particle
    }
    const Vec3 r = s.box.unwrap(s.particles.position(0), s.particles.image(0));
    for (int k = 0; k < 3; ++k) sq[static_cast<std::size_t>(k)].push_back((r[k] - start[k]) * (r[k] - start[k]));
    start = r;
    t_block = t;
  }
  for (int k = 0; k < 3; ++k) {
    const auto [m, se] = mean_se(sq[static_cast<std::size_t>(k)]);
    std::printf("sphere dt=%g axis %d: MSD/(2Dt) = %.4f ± %.4f\n", dt, k, m / (2.0 * D * t_block), se / (2.0 * D * t_block));
    EXPECT_NEAR(m, 2.0 * D * t_block, 4.0 * se) << "axis " << k << " dt " << dt;
  }
}

TEST_P(FreeParticle, CuboidBodyFrameMsdAndRotationAreTwoDt) {
  const double dt = GetParam();
  State s = lone(Shape::cuboid(1.0, 3.46, 12.0), kBoardDt, kBoardDr);
  DmcEngine e(s, RngState{11, stream_for(dt), 0, 4}, DmcMoveOptions{});
  e.set_time_steps({dt});
  const int blocks = 4000, block = 20;
  const double t_block = block * dt / 3.0;
  std::array<std::vector<double>, 3> disp, rot, rotvec;
  std::vector<double> lab;
  std::vector<double> d0 = e.body_displacement(), r0 = e.body_rotation(), v0 = e.rotation_vectors();
  Vec3 start = s.box.unwrap(s.particles.position(0), s.particles.image(0));
  for (int b = 0; b < blocks; ++b) {
    for (int c = 0; c < block; ++c) {
      e.cycle();
      ASSERT_EQ(e.last_cycle()[0].accepted, 1);  // nothing can block a lone particle
    }
    const auto& d = e.body_displacement();
    const auto& r = e.body_rotation();
    const auto& v = e.rotation_vectors();
    for (std::size_t k = 0; k < 3; ++k) {
      disp[k].push_back((d[k] - d0[k]) * (d[k] - d0[k]));
      rot[k].push_back((r[k] - r0[k]) * (r[k] - r0[k]));
      double s2 = 0.0;
      for (std::size_t c = 0; c < 3; ++c) s2 += (v[3 * k + c] - v0[3 * k + c]) * (v[3 * k + c] - v0[3 * k + c]);
      rotvec[k].push_back(s2);
    }
    const Vec3 now = s.box.unwrap(s.particles.position(0), s.particles.image(0));
    lab.push_back((now - start).squaredNorm());
    start = now;
    d0 = d; r0 = r; v0 = v;
  }
  for (std::size_t k = 0; k < 3; ++k) {
    const auto [md, sd] = mean_se(disp[k]);
    const auto ratio = [&](const std::vector<double>& x, double D) {
      const auto [m, se] = mean_se(x);
      return std::make_pair(m / (2.0 * D * t_block), se / (2.0 * D * t_block));
    };
    const auto a = ratio(disp[k], kBoardDt[static_cast<int>(k)]);
    const auto b = ratio(rot[k], kBoardDr[static_cast<int>(k)]);
    const auto c = ratio(rotvec[k], kBoardDr.sum() - kBoardDr[static_cast<int>(k)]);
    std::printf("cuboid dt=%g axis %c: MSD/(2Dt) = %.4f ± %.4f, rotation %.4f ± %.4f, rotation vector %.4f ± %.4f\n", dt,
                "TWL"[k], a.first, a.second, b.first, b.second, c.first, c.second);
    EXPECT_NEAR(md, 2.0 * kBoardDt[static_cast<int>(k)] * t_block, 4.0 * sd) << "translation axis " << k;
    const auto [mr, sr] = mean_se(rot[k]);
    EXPECT_NEAR(mr, 2.0 * kBoardDr[static_cast<int>(k)] * t_block, 4.0 * sr) << "rotation about axis " << k;
    // The rotation vector of axis k grows by the rotations about the other two axes.
    const double other = kBoardDr.sum() - kBoardDr[static_cast<int>(k)];
    const auto [mv, sv] = mean_se(rotvec[k]);
    EXPECT_NEAR(mv, 2.0 * other * t_block, 4.0 * sv)
        << "rotation vector of axis " << k;
  }
  // The lab-frame MSD is the trace: rotation-invariant.
  const auto [ml, sl] = mean_se(lab);
  EXPECT_NEAR(ml, 2.0 * kBoardDt.sum() * t_block, 4.0 * sl);
}

INSTANTIATE_TEST_SUITE_P(TimeSteps, FreeParticle, ::testing::Values(1e-4, 1e-3, 1e-2, 1e-1));

TEST(DmcEngine, RotationProposalLeavesOrientationsUniform) {
  // A lone cuboid's axes must become uniformly distributed: <P2(e_k·z)> → 0 for every body axis.
  for (auto rotation : {RotationComposition::ExponentialMap, RotationComposition::Sequential}) {
    const Vec3 Dr(0.05, 0.08, 0.1);  // with δt = 1
    State s = lone(Shape::cuboid(1.0, 3.46, 12.0), kBoardDt, Dr);
    DmcMoveOptions opt;
    opt.rotation = rotation;
    DmcEngine e(s, RngState{5, 3, 0, 4}, opt);
    e.set_time_steps({1.0});
    std::array<std::vector<double>, 3> p2;
    for (int c = 0; c < 200000; ++c) {
      e.cycle();
      const Mat3 r = s.particles.orientation(0).toRotationMatrix();
      for (int k = 0; k < 3; ++k) p2[static_cast<std::size_t>(k)].push_back(1.5 * r(2, k) * r(2, k) - 0.5);
    }
    for (int k = 0; k < 3; ++k) {
      const MeanError m = block_average(p2[static_cast<std::size_t>(k)]);
      EXPECT_NEAR(m.mean, 0.0, 4.0 * m.error) << "axis " << k;
      // Var P2 = 1/5 for uniform axes. A rotation vector uniform in ±√(2 D_j δt) per body axis, one
      // accepted trial per cycle (alone in the box), tilts axis k by ⟨Δu²⟩ = Σ_{j≠k} 2 D_j δt/3 =
      // 4 D_r per cycle, so its P2 decorrelates in 1/(6 D_r) = 1/Σ_{j≠k} D_j δt cycles.
      const double crossing = 1.0 / (Dr.sum() - Dr[k]);
      const double bound = markov_chain_error_bound(0.2, crossing, p2[static_cast<std::size_t>(k)].size());
      std::printf("axis %d: <P2> = %+.5f ± %.5f (bound %.5f, tau_int %.1f cycles)\n", k, m.mean, m.error, bound, m.tau_int);
      EXPECT_LT(m.error, bound) << "axis " << k;
    }
  }
}

class PulledTracerDrift : public ::testing::TestWithParam<std::pair<double, double>> {};

TEST_P(PulledTracerDrift, DriftIsDBetaFWithTheTracerTimeMapping) {
  const auto [pe, dt] = GetParam();
  const double D = 1.0 / (3.0 * M_PI);
  State s = lone(Shape::sphere(1.0), Vec3::Constant(D), Vec3::Zero());
  DmcEngine e(s, RngState{21, static_cast<std::uint64_t>(pe * 100), 0, 4}, DmcMoveOptions{});
  e.set_time_steps({dt});
  PulledTracer t;
  t.particle = 0;
  t.axis = 2;
  t.beta_force = pe / 0.5;
  e.set_tracer(t);
  TimeBalanceSettings bs;
  bs.tracer_species = 0;
  bs.species_counts = {1};
  TimeBalance balance(bs);
  const int blocks = 4000, block = 5000;
  std::vector<double> v;
  std::vector<double> dts{dt};
  TrialCounts all;
  double z0 = e.body_displacement()[2];
  for (int b = 0; b < blocks; ++b) {
    double tb = 0.0;
    for (int c = 0; c < block; ++c) {
      e.cycle();
      all.add(e.last_cycle()[0]);
      tb += balance.advance(e.last_cycle(), dts);
    }
    const double z = e.body_displacement()[2];
    v.push_back((z - z0) / tb);
    z0 = z;
  }
  const auto [mv, se] = mean_se(v);
  const double target = D * t.beta_force;
  EXPECT_NEAR(mv, target, 4.0 * se) << "Pe " << pe << ": v = " << mv << " ± " << se << ", DβF = " << target;
  // Power: the drift per cycle is small against the spread (v_free·δt/3 vs δx/√3), so 2×10⁷
  // trials resolve ±12% at Pe = 0.1 and ±3.5% at Pe = 1 and 10.
  EXPECT_LT(se, 0.03 * target);
  // Acceptance of the free pulled tracer: A_t = 1/2 + (1 − e^{−u})/(2u), u = βF δx_par (exact).
  const double u = t.beta_force * e.tracer_parallel_step();
  const double exact = 0.5 + (1.0 - std::exp(-u)) / (2.0 * u);
  const double n = static_cast<double>(all.tried);
  EXPECT_NEAR(all.acceptance(), exact, 4.0 * std::sqrt(exact * (1 - exact) / n));
  EXPECT_EQ(all.passed, all.tried);  // empty box: A_0 = 1
}

INSTANTIATE_TEST_SUITE_P(Peclet, PulledTracerDrift,
                         ::testing::Values(std::make_pair(0.1, 1e-1), std::make_pair(1.0, 1e-2), std::make_pair(10.0, 1e-4)));

TEST(TimeBalance, EffectiveAcceptanceAndBalancedSteps) {
  TimeBalanceSettings bs;
  bs.species_counts = {1000, 1};
  bs.reference = 1;
  bs.tracer_species = 1;
  bs.mode = BalanceMode::Equilibrium;
  TimeBalance b(bs);
  const std::vector<TrialCounts> c{{1000, 900, 600}, {100, 90, 80}};
  EXPECT_DOUBLE_EQ(b.effective_acceptance(0, c[0]), 0.6);
  EXPECT_DOUBLE_EQ(b.effective_acceptance(1, c[1]), 1.5 * 0.8 - 0.5 * 0.9);
  const auto dt = b.balanced_steps(c, {0.01, 0.02});
  EXPECT_DOUBLE_EQ(dt[1], 0.02);
  EXPECT_DOUBLE_EQ(dt[0] * 0.6, 0.02 * (1.5 * 0.8 - 0.5 * 0.9));
  BalanceSums sums;
  b.add_to(sums, c, dt);
  const auto r = b.realised_balance(sums);
  EXPECT_NEAR(r[0], 1.0, 1e-14);
  bs.a0 = TracerBathAcceptance::One;
  EXPECT_DOUBLE_EQ(TimeBalance(bs).effective_acceptance(1, c[1]), 1.5 * 0.8 - 0.5);
}

TEST(TimeBalance, RealisedBalanceIsARatioOfPooledCountsAndNaNWithoutEvidence) {
  TimeBalanceSettings bs;
  bs.species_counts = {1000, 1};
  bs.reference = 1;  // a lone tracer: one trial per cycle or so
  bs.tracer_species = 1;
  TimeBalance b(bs);
  const std::vector<double> dt{0.02, 0.01};
  // A tracer window with E = (3·1 − 3)/(2·3) = 0 exactly: 1.5·(1/3) − 0.5·1 is 0 only up to
  // rounding, and a ratio over that residue was how the observable reached 10¹¹.
  BalanceSums zero;
  b.add_to(zero, {{1000, 1000, 500}, {3, 3, 1}}, dt);
  EXPECT_EQ(b.effective_accepted(1, TrialCounts{3, 3, 1}), 0.0);
  for (double r : b.realised_balance(zero)) EXPECT_TRUE(std::isnan(r));
  BalanceSums none;  // no tracer trial at all
  b.add_to(none, {{1000, 1000, 500}, {0, 0, 0}}, dt);
  for (double r : b.realised_balance(none)) EXPECT_TRUE(std::isnan(r));
  // Pooled over cycles: (Σ tried·E·δt / Σ tried) per species, not a mean of per-cycle ratios.
  BalanceSums pooled;
  b.add_to(pooled, {{1000, 1000, 500}, {1, 1, 1}}, dt);  // tracer E = 1
  b.add_to(pooled, {{1000, 1000, 700}, {2, 2, 0}}, dt);  // tracer E = −1/2
  b.add_to(pooled, {{1000, 1000, 600}, {1, 1, 1}}, dt);  // tracer E = 1
  const double tracer = (1.0 - 1.0 + 1.0) / 4.0 * 0.01, bath = (500.0 + 700.0 + 600.0) / 3000.0 * 0.02;
  const auto r = b.realised_balance(pooled);
  EXPECT_NEAR(r[0], bath / tracer, 1e-12 * bath / tracer);
  EXPECT_DOUBLE_EQ(r[1], 1.0);
  // A fixed A_0 whose product with the counts cancels the accepted term up to rounding.
  bs.a0 = TracerBathAcceptance::Fixed;
  bs.a0_value = 0.6;
  EXPECT_EQ(TimeBalance(bs).effective_accepted(1, TrialCounts{5, 5, 1}), 0.0);
}

TEST(TimeBalance, PerCycleModeRebalancesEveryCycle) {
  TimeBalanceSettings bs;
  bs.species_counts = {100, 50};
  bs.reference = 1;
  bs.clock = 0;
  bs.mode = BalanceMode::PerCycle;
  TimeBalance b(bs);
  std::vector<double> dt{0.5, 0.01};
  const double dtb = b.advance({{100, 100, 40}, {50, 50, 25}}, dt);
  EXPECT_DOUBLE_EQ(dtb, 0.5 * 0.4 / 3.0);  // the clock uses the step in force during the cycle
  EXPECT_DOUBLE_EQ(dt[0], 0.5 * 0.01 / 0.4);
  EXPECT_DOUBLE_EQ(dt[1], 0.01);
}

TEST(DmcEngine, CheckpointContinuesBitForBit) {
  State a;
  a.box = Box(Vec3(30, 30, 30));
  a.species.push_back(Species{"board", Shape::cuboid(1.0, 2.0, 6.0), 1.0, kBoardDt, kBoardDr});
  a.species.push_back(Species{"ball", Shape::sphere(0.5), 1.0, Vec3::Constant(0.2), Vec3::Zero()});
  int id = 0;
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 4; ++y)
      for (int z = 0; z < 4; ++z) a.particles.add((x + y + z) % 3 == 0 ? 1 : 0, Vec3(3 + 7 * x, 3 + 7 * y, 3 + 7 * z), Quat::Identity(), id++);
  OrientationalField f;
  f.strength = 2.0;
  DmcEngine ea(a, RngState{3, 0, 0, 4}, DmcMoveOptions{});
  ea.set_time_steps({0.05, 0.02});
  ea.set_orientational_field(f);
  ea.set_field_on(true);
  for (int c = 0; c < 300; ++c) ea.cycle();
  const nlohmann::json saved = nlohmann::json::parse(ea.checkpoint().dump());  // through text, as on disk
  State mid = a;
  for (int c = 0; c < 300; ++c) ea.cycle();

  DmcEngine eb(mid, RngState{999, 9, 9, 4}, DmcMoveOptions{});
  eb.set_orientational_field(f);
  eb.restore(saved);
  for (int c = 0; c < 300; ++c) eb.cycle();
  for (std::size_t i = 0; i < a.particles.size(); ++i) {
    EXPECT_EQ(a.particles.x[i], mid.particles.x[i]);
    EXPECT_EQ(a.particles.z[i], mid.particles.z[i]);
    EXPECT_EQ(a.particles.qx[i], mid.particles.qx[i]);
  }
  EXPECT_EQ(ea.rotation_vectors(), eb.rotation_vectors());
  EXPECT_FALSE(ea.overlap().first_overlap().has_value());
}

TEST(DmcEngine, RejectsOverlappingStart) {
  State s = lone(Shape::sphere(1.0), Vec3::Constant(0.1), Vec3::Zero());
  s.particles.add(0, Vec3(50.5, 50, 50), Quat::Identity(), 1);
  EXPECT_THROW(DmcEngine(s, RngState{}, DmcMoveOptions{}), InputError);
}
