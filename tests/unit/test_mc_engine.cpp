// MC engine against closed forms: ideal-gas NPT, a free cuboid in the orientational field, free
// rotation (uniform orientations), and hard-sphere sweeps that never create an overlap; a rejected
// squeeze or volume move leaves every position bit-identical. The
// sampled averages are compared within 4 standard errors, each bounded from above by
// markov_chain_error_bound (tests/support) with the chain's crossing time derived from its moves.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/statistics.hpp"
#include "anisodyn/mc/mc_engine.hpp"
#include "lattice_states.hpp"
#include "thread_count.hpp"
#include "markov_chain_error_bound.hpp"

using namespace anisodyn;
using anisodyn::testing_support::gas_of_points;
using anisodyn::testing_support::markov_chain_error_bound;
using anisodyn::testing_support::ScopedThreadCount;

namespace {

/// Hard spheres (d = 1) on a simple cubic lattice of spacing a.
State sphere_lattice(int side, double a) {
  State s;
  s.box = Box(Vec3::Constant(side * a));
  s.species.push_back(Species{"hs", Shape::sphere(1.0), 1.0, Vec3::Zero(), Vec3::Zero()});
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (int k = 0; k < side; ++k)
        s.particles.add(0, a * Vec3(i + 0.5, j + 0.5, k + 0.5), Quat::Identity(), (i * side + j) * side + k);
  return s;
}

/// The same lattice melted by NVT sweeps, so that the coordinates are generic doubles (a
/// rescaling and its inverse then round differently from the identity).
State melted_spheres(int side, double a) {
  State s = sphere_lattice(side, a);
  McEngine mc(s, RngState{3, 0, 0, 4});
  for (int c = 0; c < 200; ++c) mc.cycle();
  return s;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

/// Cycles for ln V to cross its width: Var ln V = ψ₁(N + 1) < 1/N for p(V) ∝ V^N e^{−βPV}, against
/// one volume move per cycle (on average) of ln V uniform in ±δ, accepted with probability A.
double log_volume_crossing(std::size_t n, double delta, double acceptance) {
  return (1.0 / static_cast<double>(n)) / (acceptance * delta * delta / 3.0);
}

/// 1/(6 D_r) of a body axis under McEngine's rotations: a rotation vector uniform in [−a, a]³
/// tilts the axis by ⟨θ_⊥²⟩ = 2a²/3, tried in half the moves of a lone particle (one per cycle)
/// and accepted with probability A: ⟨Δu²⟩ = 4 D_r per cycle gives D_r = A a²/12.
double rotation_crossing(double a, double acceptance) { return 1.0 / (6.0 * acceptance * a * a / 12.0); }

State single_cuboid() {
  State s;
  s.box = Box(Vec3::Constant(100.0));
  s.species.push_back(Species{"board", Shape::cuboid(1.0, 3.4641, 12.0), 1.0, Vec3::Zero(), Vec3::Zero()});
  s.particles.add(0, Vec3(50, 50, 50), Quat::Identity(), 0);
  return s;
}

}  // namespace

TEST(McEngine, IdealGasNptMeanVolumeIsExact) {
  // ln V moves with acceptance exp(-βPΔV + (N+1) ln V'/V) sample p(V) ∝ V^N exp(-βPV): <V> = (N+1)/βP.
  // Sequential sweeps (a volume move with probability 1/(N + 1) per move) and domain sweeps (one
  // per cycle, made together at the end of each cut) alike.
  const std::size_t n = 20;
  const double beta_p = 0.5;
  const ScopedThreadCount one_thread(1);  // domain sweeps give the same bits on any thread count
  for (const bool domains : {false, true}) {
    State s = gas_of_points(n, std::cbrt((n + 1) / beta_p));
    McEngine mc(s, RngState{12345, 0, 0, 4});
    mc.set_domain_sweeps(domains);
    mc.set_pressure(beta_p);
    mc.move_sizes().log_volume = 0.5;
    for (int c = 0; c < 2000; ++c) mc.cycle();
    std::vector<double> v;
    for (int c = 0; c < 100000; ++c) {
      mc.cycle();
      v.push_back(s.box.volume());
    }
    const MeanError m = block_average(v);
    const double exact = (n + 1) / beta_p;
    EXPECT_NEAR(m.mean, exact, 4.0 * m.error) << "domains " << domains << ": mean " << m.mean << " ± " << m.error;
    // Var V = (N + 1)/(βP)² for the Gamma distribution of V
    const double acceptance = MoveCounters::ratio(mc.counters().volume_accepted, mc.counters().volume_tried);
    const double bound = markov_chain_error_bound((n + 1) / (beta_p * beta_p), log_volume_crossing(n, 0.5, acceptance), v.size());
    std::printf("domains %d: <V> = %.4f ± %.4f (bound %.4f, tau_int %.1f cycles, exact %.4f)\n", domains, m.mean, m.error, bound,
                m.tau_int, exact);
    EXPECT_LT(m.error, bound);
  }
}

TEST(McEngine, PerAxisBoxMovesSampleTheSameIdealGas) {
  const std::size_t n = 10;
  const double beta_p = 1.0;
  State s = gas_of_points(n, std::cbrt((n + 1) / beta_p));
  McEngine mc(s, RngState{777, 0, 0, 4});
  mc.set_pressure(beta_p, BoxMoves::PerAxis);
  mc.move_sizes().log_volume = 0.5;
  std::vector<double> v;
  for (int c = 0; c < 150000; ++c) {
    mc.cycle();
    if (c >= 2000) v.push_back(s.box.volume());
  }
  const MeanError m = block_average(v);
  EXPECT_NEAR(m.mean, (n + 1) / beta_p, 4.0 * m.error) << "mean " << m.mean << " ± " << m.error;
  // the same Gamma distribution of V: one edge scaled by e^{Δ ln V} changes ln V as much
  const double acceptance = MoveCounters::ratio(mc.counters().volume_accepted, mc.counters().volume_tried);
  const double bound = markov_chain_error_bound((n + 1) / (beta_p * beta_p), log_volume_crossing(n, 0.5, acceptance), v.size());
  std::printf("<V> = %.4f ± %.4f (bound %.4f, tau_int %.1f cycles)\n", m.mean, m.error, bound, m.tau_int);
  EXPECT_LT(m.error, bound);
}

TEST(McEngine, FreeCuboidInFieldFollowsBoltzmann) {
  // With U = -(ε/2)(3c² - 1), c = ŵ·ê uniform on [-1, 1] without the field, the exact
  // <P2(c)> = ∫ P2(c) e^{-U} dc / ∫ e^{-U} dc (quadrature below).
  const double eps = 2.0;
  State s = single_cuboid();
  McEngine mc(s, RngState{4242, 0, 0, 4});
  OrientationalField field;
  field.strength = eps;
  field.body_axis = 1;
  field.direction = Vec3(1, 1, 0).normalized();
  mc.set_field(field);
  mc.move_sizes().rotate[0] = 0.6;
  std::vector<double> p2;
  for (int c = 0; c < 400000; ++c) {
    mc.cycle();
    const double cw = s.particles.orientation(0).toRotationMatrix().col(1).dot(field.direction);
    p2.push_back(1.5 * cw * cw - 0.5);
  }
  double num = 0.0, second = 0.0, den = 0.0;
  const int q = 200000;
  for (int k = 0; k < q; ++k) {
    const double c = -1.0 + (k + 0.5) * 2.0 / q;
    const double w = std::exp(0.5 * eps * (3.0 * c * c - 1.0));
    const double p = 1.5 * c * c - 0.5;
    num += p * w;
    second += p * p * w;
    den += w;
  }
  const MeanError m = block_average(p2);
  EXPECT_NEAR(m.mean, num / den, 4.0 * m.error) << "MC " << m.mean << " ± " << m.error << " exact " << num / den;
  // the exact variance of P2 in the field (same quadrature), the rotations' acceptance in the field
  const double variance = second / den - (num / den) * (num / den);
  const double acceptance = MoveCounters::ratio(mc.counters().rotate_accepted[0], mc.counters().rotate_tried[0]);
  const double bound = markov_chain_error_bound(variance, rotation_crossing(0.6, acceptance), p2.size());
  std::printf("<P2> = %.5f ± %.5f (bound %.5f, tau_int %.1f cycles, acceptance %.3f, exact %.5f)\n", m.mean, m.error, bound, m.tau_int,
              acceptance, num / den);
  EXPECT_LT(m.error, bound);
}

TEST(McEngine, FreeCuboidOrientationsBecomeUniform) {
  State s = single_cuboid();
  McEngine mc(s, RngState{5, 0, 0, 4});
  mc.move_sizes().rotate[0] = 0.8;
  std::vector<double> p2[3];
  for (int c = 0; c < 200000; ++c) {
    mc.cycle();
    const Mat3 r = s.particles.orientation(0).toRotationMatrix();
    for (int k = 0; k < 3; ++k) p2[k].push_back(1.5 * r(2, k) * r(2, k) - 0.5);
  }
  // uniform orientations: Var P2 = 1/5; every rotation of a lone particle without a field is accepted
  const double bound = markov_chain_error_bound(0.2, rotation_crossing(0.8, 1.0), p2[0].size());
  for (int k = 0; k < 3; ++k) {
    const MeanError m = block_average(p2[k]);
    EXPECT_NEAR(m.mean, 0.0, 4.0 * m.error) << "axis " << k;
    std::printf("axis %d: <P2> = %+.5f ± %.5f (bound %.5f, tau_int %.1f cycles)\n", k, m.mean, m.error, bound, m.tau_int);
    EXPECT_LT(m.error, bound) << "axis " << k;
  }
}

TEST(McEngine, DenseHardSpheresNeverOverlap) {
  State s = sphere_lattice(6, 1.05);  // η ≈ 0.45
  McEngine mc(s, RngState{1, 0, 0, 4});
  mc.set_pressure(3.0);
  MoveCounters mark = mc.counters();
  for (int c = 0; c < 300; ++c) {
    mc.cycle();
    if (c % 20 == 19) {
      mc.tune(0.35, mc.counters().since(mark));
      mark = mc.counters();
    }
  }
  EXPECT_FALSE(mc.overlap().first_overlap().has_value());
  const auto& n = mc.counters();
  EXPECT_GT(n.translate_accepted[0], 0);
  EXPECT_LT(n.translate_accepted[0], n.translate_tried[0]);
  EXPECT_GT(n.volume_accepted, 0);
}

TEST(McEngine, RejectedRescaleLeavesEveryPositionBitIdentical) {
  State s = melted_spheres(6, 1.05);
  const Particles before = s.particles;
  const Vec3 edges = s.box.edges();
  // The test has power: scaling back by the inverse factor would not restore these coordinates.
  const double f = std::cbrt(0.98), back = 1.0 / f;
  int inexact = 0;
  for (double x : before.x) inexact += (x * f) * back != x;
  ASSERT_GT(inexact, 0);

  McEngine mc(s, RngState{8, 0, 0, 4});
  ASSERT_FALSE(mc.try_rescale(0.98 * s.box.volume()));  // 2% denser than a dense fluid: overlaps
  EXPECT_TRUE(same_bits(s.particles.x, before.x));
  EXPECT_TRUE(same_bits(s.particles.y, before.y));
  EXPECT_TRUE(same_bits(s.particles.z, before.z));
  EXPECT_EQ(s.box.edges(), edges);
  EXPECT_FALSE(mc.overlap().first_overlap().has_value());
}

TEST(McEngine, RejectedVolumeMovesLeaveEveryPositionBitIdentical) {
  // At βP = 1000 every compression passes the Metropolis test, and with zero particle moves the
  // spheres stay put, so the box soon cannot shrink without an overlap: from then on volume moves
  // are rejected by the overlap test, after rescaling. A cycle without an accepted volume move must
  // leave the positions exactly as they were.
  for (BoxMoves moves : {BoxMoves::Isotropic, BoxMoves::PerAxis}) {
    State s = melted_spheres(6, 1.05);
    McEngine mc(s, RngState{17, 0, 0, 4});
    mc.set_pressure(1000.0, moves);
    mc.move_sizes().translate[0] = 0.0;
    mc.move_sizes().log_volume = 0.02;
    std::int64_t rejected = 0;
    for (int c = 0; c < 300; ++c) {
      const Particles before = s.particles;
      const Vec3 edges = s.box.edges();
      const MoveCounters mark = mc.counters();
      mc.cycle();
      const MoveCounters w = mc.counters().since(mark);
      if (w.volume_accepted > 0) continue;
      rejected += w.volume_tried;
      ASSERT_TRUE(same_bits(s.particles.x, before.x) && same_bits(s.particles.y, before.y) && same_bits(s.particles.z, before.z))
          << "cycle " << c;
      ASSERT_EQ(s.box.edges(), edges) << "cycle " << c;
    }
    EXPECT_GT(rejected, 100);
    EXPECT_FALSE(mc.overlap().first_overlap().has_value());
  }
}

TEST(McEngine, RejectsOverlappingInput) {
  State s;
  s.box = Box(Vec3::Constant(10));
  s.species.push_back(Species{"hs", Shape::sphere(1.0), 1.0, Vec3::Zero(), Vec3::Zero()});
  s.particles.add(0, Vec3(1, 1, 1), Quat::Identity(), 0);
  s.particles.add(0, Vec3(1.5, 1, 1), Quat::Identity(), 1);
  EXPECT_THROW(McEngine(s, RngState{}), InputError);
}

TEST(BlockAverage, ShortRunsAreNotOverconfident) {
  // 20 correlation times only: blocking alone cannot reach its plateau; the reported error must
  // still cover the true one (within the estimator's own noise).
  const double phi = 0.999;  // τ_int ≈ 1000 samples
  const std::size_t n = 20000;
  const double exact = std::sqrt((1 + phi) / (1 - phi) / static_cast<double>(n));
  double mean_ratio = 0.0;
  const int repeats = 40;
  for (int r = 0; r < repeats; ++r) {
    Rng rng(100 + r, 1);
    std::vector<double> x(n);
    double v = rng.normal();
    for (auto& xi : x) {
      v = phi * v + std::sqrt(1 - phi * phi) * rng.normal();
      xi = v;
    }
    mean_ratio += block_average(x).error / exact / repeats;
  }
  EXPECT_GT(mean_ratio, 0.7);
}

TEST(BlockAverage, RecoversTheErrorOfACorrelatedSeries) {
  // AR(1) with coefficient φ: the standard error of the mean is σ/√n · √((1+φ)/(1−φ)).
  const double phi = 0.9;
  const std::size_t n = 1 << 18;
  Rng rng(8, 8);
  std::vector<double> x(n);
  double v = 0.0;
  for (auto& xi : x) {
    v = phi * v + std::sqrt(1 - phi * phi) * rng.normal();
    xi = v;
  }
  const MeanError m = block_average(x);
  const double exact = std::sqrt((1 + phi) / (1 - phi) / static_cast<double>(n));
  EXPECT_NEAR(m.error_blocking, exact, 0.25 * exact);
  EXPECT_NEAR(m.error_autocorrelation, exact, 0.25 * exact);
  EXPECT_NEAR(m.tau_int, 0.5 * (1 + phi) / (1 - phi), 0.25 * 0.5 * (1 + phi) / (1 - phi));
  EXPECT_NEAR(m.mean, 0.0, 4 * exact);
}
