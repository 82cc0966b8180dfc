// Domain sweeps (mc/domain_sweep.hpp), the slab and grid decompositions of MC preparation:
//   - Slab::holds / reaches against an enumeration of periodic images;
//   - dense rods never overlap after many cycles, every particle gets moved, and one and two
//     threads give the same bits, with slabs and with a grid;
//   - the automatic layout cuts large systems only where domains stay wide next to the particles;
//   - a cut restored from a checkpoint in the middle of its cycles continues the run bit for bit;
//     under NPT its volume moves wait for its end, and a checkpoint carries the moves owed;
//   - an ideal gas of rods keeps isotropic orientations, although movability depends on them;
//   - interacting boards in slabs about one board long keep the orientational correlations of the
//     sequential sweep (a movability test that broke detailed balance fails this);
//   - the sampled distribution is the hard-particle one: two hard spheres' separation against its
//     exact law and hard spheres' NPT packing fraction, with slabs and with a grid, against the
//     sequential sweep's (the ideal gas's NPT volume against (N + 1)/βP is in test_mc_engine).
// Averages are compared within 4 standard errors (block averages).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <optional>
#include <tuple>
#include <vector>

#include "anisodyn/core/statistics.hpp"
#include "anisodyn/mc/mc_engine.hpp"
#include "lattice_states.hpp"
#include "thread_count.hpp"

using namespace anisodyn;
using anisodyn::testing_support::lattice_of;
using anisodyn::testing_support::on_thread_counts;
using anisodyn::testing_support::ScopedThreadCount;

namespace {

const Species kRod{"rod", Shape::cuboid(1.0, 1.0, 12.0), 1.0, {}, {}};
const Species kSphere{"hs", Shape::sphere(1.0), 1.0, {}, {}};

/// Minimum-image distance between particles 0 and 1.
double separation(const State& s) {
  return s.box.min_image(s.particles.position(1) - s.particles.position(0)).norm();
}

}  // namespace

TEST(Slab, HoldsAndReachesAsThePeriodicImagesSay) {
  Rng rng(5, 0);
  const double L = 10.0;
  int held = 0, reached = 0;
  for (int t = 0; t < 20000; ++t) {
    const Slab slab{0, rng.uniform(-20.0, 20.0), L / 2};
    const double c = rng.uniform(0.0, L), h = rng.uniform(0.0, 2.4);
    bool inside = false, meets = false;
    for (int image = -3; image <= 3; ++image) {
      const double lo = c - h + image * L, hi = c + h + image * L;
      inside = inside || (lo > slab.start && hi < slab.start + slab.width);
      meets = meets || (lo <= slab.start + slab.width && hi >= slab.start);
    }
    ASSERT_EQ(slab.holds(c, h, L), inside) << "start " << slab.start << " c " << c << " h " << h;
    ASSERT_EQ(slab.reaches(c, h, L), meets) << "start " << slab.start << " c " << c << " h " << h;
    held += inside;
    reached += meets;
  }
  EXPECT_GT(held, 2000);
  EXPECT_LT(reached, 19000);
}

namespace {

/// Domain sweeps with the given layout (none: slabs), with the rods' fixed move sizes.
void use_domains(McEngine& mc, const std::optional<DomainSweep::Layout>& layout) {
  mc.set_domain_sweeps(true);
  mc.domain_sweep()->set_layout(layout);
  mc.move_sizes().translate[0] = 0.3;
  mc.move_sizes().rotate[0] = 0.05;
}

/// Dense rods under domain sweeps with the given layout (none: slabs): no overlaps after 60 cycles,
/// N trials per cycle, every particle moved, and the same bits on one and two threads.
void dense_rods_check(const std::optional<DomainSweep::Layout>& layout, int most_idle_cycles) {
  Rng rng(11, 0);
  const State start = lattice_of(kRod, 500, 0.30, rng);
  const auto runs = on_thread_counts({1, 2}, [&] {
    State s = start;
    McEngine mc(s, RngState{21, 0, 0, 4});
    use_domains(mc, layout);
    int idle = 0;
    for (int c = 0; c < 60; ++c) {
      const MoveCounters before = mc.counters();
      mc.cycle();
      // N trials per cycle, shared between the domains, unless no body fits inside one: on this
      // lattice, two layers of rods half a box apart, a slab cut along the rods mostly leaves none.
      const MoveCounters w = mc.counters().since(before);
      const auto tried = w.translate_tried[0] + w.rotate_tried[0];
      if (tried == 0) ++idle;
      else EXPECT_EQ(tried, 500) << "cycle " << c;
    }
    EXPECT_LE(idle, most_idle_cycles);
    EXPECT_FALSE(mc.overlap().first_overlap().has_value());
    const MoveCounters& n = mc.counters();
    EXPECT_GT(n.translate_accepted[0], 0);
    EXPECT_LT(n.translate_accepted[0], n.translate_tried[0]);
    return s.particles;
  });
  EXPECT_EQ(0, std::memcmp(runs[0].x.data(), runs[1].x.data(), runs[0].x.size() * sizeof(double)));
  EXPECT_EQ(0, std::memcmp(runs[0].qz.data(), runs[1].qz.data(), runs[0].qz.size() * sizeof(double)));
  std::size_t moved = 0;
  for (std::size_t i = 0; i < start.particles.size(); ++i) moved += runs[0].x[i] != start.particles.x[i] || runs[0].qw[i] != start.particles.qw[i];
  EXPECT_EQ(moved, start.particles.size());
}

}  // namespace

TEST(DomainSweep, DenseRodsNeverOverlapAndTheBitsDoNotDependOnTheThreadCount) {
  dense_rods_check(std::nullopt, 32);
  // A grid across the rods (box 27 T, domains 13.6 T wide): every cycle moves.
  dense_rods_check(DomainSweep::Layout{2, 2, 1}, 0);
}

TEST(DomainSweep, AutomaticLayoutCutsANematicAcrossTheDirectorOnly) {
  Rng rng(3, 0);
  const auto domains = [](const DomainSweep::Layout& g) { return static_cast<std::size_t>(g[0] * g[1] * g[2]); };
  // 8000 rods along z at η = 0.34 (box 65.6 T): about 8000 / kParticlesPerDomain domains, cut
  // along x and y alike, never along the rods.
  const std::size_t wanted = 8000 / DomainSweep::kParticlesPerDomain;
  const auto grid = DomainSweep::automatic_layout(lattice_of(kRod, 8000, 0.34, rng));
  ASSERT_TRUE(grid.has_value());
  EXPECT_EQ((*grid)[2], 1);
  EXPECT_LE(std::abs((*grid)[0] - (*grid)[1]), 1);
  EXPECT_GE(domains(*grid), wanted);
  EXPECT_LT(domains(*grid), 2 * wanted);
  // 2000 of them: two slabs along random axes.
  EXPECT_FALSE(DomainSweep::automatic_layout(lattice_of(kRod, 2000, 0.34, rng)).has_value());
  // 4000 spheres at η = 0.40 (box 17.4 diameters): every domain at least 3 diameters wide.
  const auto spheres = DomainSweep::automatic_layout(lattice_of(kSphere, 4000, 0.40, rng));
  ASSERT_TRUE(spheres.has_value());
  EXPECT_GE(domains(*spheres), 4000 / DomainSweep::kParticlesPerDomain);
  for (const int m : *spheres) EXPECT_LE(m, 5);
}

TEST(DomainSweep, ARestoredCutContinuesTheRunBitForBit) {
  // A cut serves several cycles, so a checkpoint in the middle of one must carry it.
  static_assert(DomainSweep::kCyclesPerCut > 5, "the checkpoint below must fall inside a cut");
  const ScopedThreadCount one_thread(1);
  Rng rng(12, 0);
  const State start = lattice_of(kRod, 300, 0.25, rng);
  const RngState seed{31, 0, 0, 4};
  auto prepared = [](McEngine& mc) { use_domains(mc, std::nullopt); };
  State whole = start;
  McEngine uninterrupted(whole, seed);
  prepared(uninterrupted);
  for (int c = 0; c < 13; ++c) uninterrupted.cycle();

  State first = start;
  McEngine before(first, seed);
  prepared(before);
  for (int c = 0; c < 5; ++c) before.cycle();
  const std::optional<DomainSweep::Cut> cut = before.domain_sweep()->cut();
  ASSERT_TRUE(cut.has_value());
  EXPECT_EQ(cut->cycles_done, 5);
  auto resume = [&](const std::optional<DomainSweep::Cut>& c) {
    State s = first;
    McEngine after(s, seed);
    prepared(after);
    after.restore(before.rng_state(), before.counters(), before.move_sizes());
    after.domain_sweep()->restore_cut(c);
    for (int k = 0; k < 8; ++k) after.cycle();
    return s.particles;
  };
  const Particles resumed = resume(cut);
  EXPECT_EQ(resumed.x, whole.particles.x);
  EXPECT_EQ(resumed.qw, whole.particles.qw);
  EXPECT_EQ(resumed.qz, whole.particles.qz);
  // Without the cut the resumed run draws a new one and leaves the uninterrupted trajectory.
  EXPECT_NE(resume(std::nullopt).x, whole.particles.x);
}

TEST(DomainSweep, CyclesRunAtOnceGiveTheBitsOfSingleCycles) {
  // Each domain runs its share of several cycles back to back; the domains are independent within
  // a cut, so the result must be that of the cycles run one by one, cut boundaries included. Under
  // NPT too: the cut's volume moves are made at its end either way.
  Rng rng(13, 0);
  const State start = lattice_of(kRod, 400, 0.25, rng);
  const std::optional<DomainSweep::Layout> slabs, grid = DomainSweep::Layout{2, 2, 1};
  for (const auto& [layout, pressure] : {std::pair{slabs, std::optional<double>{}}, std::pair{grid, std::optional<double>{}},
                                          std::pair{slabs, std::optional<double>{0.05}}}) {
    auto run = [&](int batch) {
      State s = start;
      McEngine mc(s, RngState{41, 0, 0, 4});
      use_domains(mc, layout);
      mc.set_pressure(pressure);
      mc.move_sizes().log_volume = 0.01;
      std::vector<int> runs;
      for (int done = 0; done < 21;) {
        const int k = mc.cycles(std::min(batch, 21 - done));
        EXPECT_GE(k, 1);
        EXPECT_LE(k, std::min(batch, DomainSweep::kCyclesPerCut));
        runs.push_back(k);
        done += k;
      }
      EXPECT_FALSE(mc.overlap().first_overlap().has_value());
      return std::make_tuple(s.particles, mc.counters(), mc.rng_state(), runs, s.box.edges());
    };
    const auto [one, one_counters, one_rng, one_runs, one_edges] = run(1);
    const auto [five, five_counters, five_rng, five_runs, five_edges] = run(5);
    // Batches of 5 stop at each cut's end (8 cycles): 5, 3, 5, 3, 5.
    EXPECT_EQ(five_runs, (std::vector<int>{5, 3, 5, 3, 5}));
    EXPECT_EQ(one.x, five.x);
    EXPECT_EQ(one.y, five.y);
    EXPECT_EQ(one.z, five.z);
    EXPECT_EQ(one.qw, five.qw);
    EXPECT_EQ(one.qx, five.qx);
    EXPECT_EQ(one.qz, five.qz);
    EXPECT_EQ(one_counters.translate_accepted, five_counters.translate_accepted);
    EXPECT_EQ(one_counters.rotate_tried, five_counters.rotate_tried);
    EXPECT_EQ(one_rng.counter, five_rng.counter);
    EXPECT_EQ(one_edges, five_edges);
    EXPECT_EQ(one_counters.volume_tried, pressure ? 16 : 0);  // the cuts that ended: two of 8 cycles
    EXPECT_EQ(one_counters.volume_accepted, five_counters.volume_accepted);
    EXPECT_EQ(one_edges == start.box.edges(), !pressure);
    EXPECT_NE(one.x, start.particles.x);
  }
}

TEST(DomainSweep, NptVolumeMovesWaitForTheCutsEndAndAResumedRunStillOwesThem) {
  // Under NPT each domain cycle owes one volume move, made when its cut ends, so that the cut's
  // cycles run as one batch on unchanged copies. A checkpoint in the middle of a cut must carry
  // the moves owed.
  const ScopedThreadCount one_thread(1);
  Rng rng(14, 0);
  const State start = lattice_of(kRod, 300, 0.25, rng);
  const RngState seed{32, 0, 0, 4};
  auto prepared = [](McEngine& mc) {
    use_domains(mc, std::nullopt);
    mc.set_pressure(0.005);  // βPV ≈ 0.4 N: the box expands, and expansions never overlap
    mc.move_sizes().log_volume = 0.01;
  };
  State whole = start;
  McEngine uninterrupted(whole, seed);
  prepared(uninterrupted);
  for (int c = 0; c < 5; ++c) uninterrupted.cycle();
  EXPECT_EQ(uninterrupted.counters().volume_tried, 0);
  EXPECT_EQ(uninterrupted.volume_moves_owed(), 5);
  EXPECT_EQ(whole.box.edges(), start.box.edges());
  const State mid_cut = whole;
  const RngState rng_mid = uninterrupted.rng_state();
  const MoveCounters counters_mid = uninterrupted.counters();
  const std::optional<DomainSweep::Cut> cut = uninterrupted.domain_sweep()->cut();
  ASSERT_TRUE(cut.has_value());
  for (int c = 5; c < 8; ++c) uninterrupted.cycle();
  EXPECT_EQ(uninterrupted.counters().volume_tried, 8);
  EXPECT_EQ(uninterrupted.volume_moves_owed(), 0);
  EXPECT_GT(uninterrupted.counters().volume_accepted, 0);
  for (int c = 8; c < 13; ++c) uninterrupted.cycle();

  auto resume = [&](int owed) {
    State s = mid_cut;
    McEngine after(s, seed);
    prepared(after);
    after.restore(rng_mid, counters_mid, uninterrupted.move_sizes(), owed);
    after.domain_sweep()->restore_cut(cut);
    for (int k = 0; k < 8; ++k) after.cycle();
    return s;
  };
  const State resumed = resume(5);
  EXPECT_EQ(resumed.box.edges(), whole.box.edges());
  EXPECT_EQ(resumed.particles.x, whole.particles.x);
  EXPECT_EQ(resumed.particles.qw, whole.particles.qw);
  // Forgetting what was owed leaves the uninterrupted trajectory.
  EXPECT_NE(resume(0).box.edges(), whole.box.edges());
}

TEST(DomainSweep, TwoHardSpheresSampleTheExactSeparationLaw) {
  // Sphere 1 is uniform over the box outside the excluded sphere around sphere 0: the fraction of
  // samples with 1 ≤ r < b is (4π/3)(b³ − 1)/(L³ − 4π/3) for b ≤ L/2.
  const double L = 4.0;
  State s;
  s.box = Box(Vec3::Constant(L));
  s.species.push_back(kSphere);
  s.particles.add(0, Vec3(1, 1, 1), Quat::Identity(), 0);
  s.particles.add(0, Vec3(3, 3, 3), Quat::Identity(), 1);
  // One thread: the bits do not depend on the thread count (tested above), and two threads beside
  // another test process spend these short cycles waiting for each other.
  const ScopedThreadCount one_thread(1);
  McEngine mc(s, RngState{8, 0, 0, 4});
  mc.set_domain_sweeps(true);
  mc.move_sizes().translate[0] = 0.7;
  const double edges[] = {1.25, 1.5, 1.75, 2.0};
  std::vector<std::vector<double>> inside(4);
  for (int c = 0; c < 200000; ++c) {
    mc.cycle();
    const double r = separation(s);
    ASSERT_GE(r, 1.0) << "cycle " << c;
    for (int b = 0; b < 4; ++b) inside[static_cast<std::size_t>(b)].push_back(r < edges[b] ? 1.0 : 0.0);
  }
  const double free_volume = L * L * L - 4.0 * M_PI / 3.0;
  for (int b = 0; b < 4; ++b) {
    const MeanError m = block_average(inside[static_cast<std::size_t>(b)]);
    const double exact = 4.0 * M_PI / 3.0 * (std::pow(edges[b], 3) - 1.0) / free_volume;
    EXPECT_NEAR(m.mean, exact, 4.0 * m.error) << "r < " << edges[b] << ": " << m.mean << " ± " << m.error;
    EXPECT_LT(m.error, 0.1 * exact);
  }
}

TEST(DomainSweep, AnIdealGasOfRodsStaysIsotropic) {
  // Rods 12×1×1 far apart in a box of 40 (they seldom meet): each long axis is uniform on the
  // sphere, so <u_k²> = 1/3 on every lab axis, although the slab test depends on orientation.
  const ScopedThreadCount one_thread(1);
  State s;
  s.box = Box(Vec3::Constant(40.0));
  s.species.push_back(kRod);
  for (int i = 0; i < 8; ++i) s.particles.add(0, Vec3(5.0 + 10.0 * (i % 4), 10.0 + 20.0 * (i / 4), 20.0), Quat::Identity(), i);
  McEngine mc(s, RngState{17, 0, 0, 4});
  mc.set_domain_sweeps(true);
  mc.move_sizes().translate[0] = 2.0;
  mc.move_sizes().rotate[0] = 0.5;
  std::vector<std::vector<double>> u2(3);
  for (int c = 0; c < 100000; ++c) {
    mc.cycle();
    Vec3 sum = Vec3::Zero();
    for (std::size_t i = 0; i < s.particles.size(); ++i) sum += (s.particles.orientation(i) * Vec3::UnitZ()).cwiseAbs2();
    for (int k = 0; k < 3; ++k) u2[static_cast<std::size_t>(k)].push_back(sum[k] / 8.0);
  }
  for (int k = 0; k < 3; ++k) {
    const MeanError m = block_average(u2[static_cast<std::size_t>(k)]);
    std::printf("<u_%d^2> = %.5f ± %.5f\n", k, m.mean, m.error);
    EXPECT_NEAR(m.mean, 1.0 / 3.0, 4.0 * m.error);
  }
}

namespace {

/// Σ_{i<j} P2(u_i · u_j) / N over the long axes u: zero on average for independent orientations,
/// and what the finite-size order parameter U_L measures in an isotropic fluid.
double long_axis_pair_order(const State& s) {
  const Particles& p = s.particles;
  std::vector<Vec3> u(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) u[i] = p.orientation(i) * Vec3::UnitZ();
  double sum = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i)
    for (std::size_t j = i + 1; j < u.size(); ++j) {
      const double c = u[i].dot(u[j]);
      sum += 1.5 * c * c - 0.5;
    }
  return sum / static_cast<double>(p.size());
}

}  // namespace

TEST(DomainSweep, BoardsInSlabsOneBoardWideKeepTheSequentialOrientationalCorrelations) {
  // 27 boards 12×3.46×1 at η = 0.07 in a box of 25.2: each slab (12.6) is about one board long, so
  // which boards may move depends strongly on their orientation. A deliberately broken build that
  // let a board move when only its centre was inside (while its moves had to keep its whole lab box
  // inside) failed here: 0.1520 ± 0.0056 against the sequential 0.0683 ± 0.0029 (13 errors).
  const ScopedThreadCount one_thread(1);
  const Species board{"board", Shape::cuboid(1.0, 3.46, 12.0), 1.0, {}, {}};
  Rng rng(6, 0);
  const State start = lattice_of(board, 27, 0.07, rng);
  auto pair_order = [&](bool domains) {
    State s = start;
    McEngine mc(s, RngState{31, 0, 0, 4});
    mc.set_domain_sweeps(domains);
    mc.move_sizes().translate[0] = 1.5;
    mc.move_sizes().rotate[0] = 0.8;
    for (int c = 0; c < 5000; ++c) mc.cycle();  // the lattice starts aligned
    std::vector<double> order;
    for (int c = 0; c < 300000; ++c) {
      mc.cycle();
      order.push_back(long_axis_pair_order(s));
    }
    return block_average(order);
  };
  const MeanError sequential = pair_order(false), domains = pair_order(true);
  std::printf("pair order: sequential %.4f ± %.4f, domains %.4f ± %.4f\n", sequential.mean, sequential.error, domains.mean,
              domains.error);
  const double error = std::hypot(sequential.error, domains.error);
  EXPECT_NEAR(domains.mean, sequential.mean, 4.0 * error);
  EXPECT_LT(error, 0.0075);                            // resolves a shift of 0.03 by 4 errors
  EXPECT_GT(sequential.mean, 4.0 * sequential.error);  // the boards do correlate
}

TEST(DomainSweep, HardSpheresNptPackingFractionMatchesTheSequentialSweep) {
  // Under NPT the volume of a small system wanders slowly and one run's block errors can be far
  // too small, so each sweep runs from 16 seeds (fixed move sizes) and the error of the mean comes
  // from their spread.
  const ScopedThreadCount one_thread(1);  // as above
  Rng rng(4, 0);
  const State start = lattice_of(kSphere, 216, 0.40, rng);
  // The slabs, and a grid of 2 × 2 × 2 domains (3.3 diameters wide).
  auto mean_eta = [&](int sweeps, std::uint64_t seed) {
    State s = start;
    McEngine mc(s, RngState{seed, 0, 0, 4});
    mc.set_domain_sweeps(sweeps > 0);
    if (sweeps == 2) mc.domain_sweep()->set_layout(DomainSweep::Layout{2, 2, 2});
    mc.set_pressure(5.3);  // Carnahan–Starling: η ≈ 0.40
    mc.move_sizes().translate[0] = 0.12;
    mc.move_sizes().log_volume = 0.02;
    for (int c = 0; c < 1000; ++c) mc.cycle();
    double sum = 0.0;
    for (int c = 0; c < 8000; ++c) {
      mc.cycle();
      sum += s.packing_fraction();
    }
    EXPECT_FALSE(mc.overlap().first_overlap().has_value());
    return sum / 8000.0;
  };
  std::vector<double> sequential, slabs, grid;
  for (std::uint64_t seed = 100; seed < 116; ++seed) {
    sequential.push_back(mean_eta(0, seed));
    slabs.push_back(mean_eta(1, seed));
    grid.push_back(mean_eta(2, seed));
  }
  const MeanError a = mean_of_independent(sequential), b = mean_of_independent(slabs), g = mean_of_independent(grid);
  std::printf("eta over 16 seeds: sequential %.5f ± %.5f, slabs %.5f ± %.5f, grid %.5f ± %.5f\n", a.mean, a.error, b.mean, b.error,
              g.mean, g.error);
  EXPECT_NEAR(b.mean, a.mean, 4.0 * std::hypot(a.error, b.error));
  EXPECT_NEAR(g.mean, a.mean, 4.0 * std::hypot(a.error, g.error));
  EXPECT_LT(std::hypot(a.error, b.error), 0.003);
  EXPECT_LT(std::hypot(a.error, g.error), 0.003);
  EXPECT_NEAR(a.mean, 0.40, 0.01);  // the pressure was chosen for it
}
