// HardOverlap (cell grids or AABB trees + kernels) against an O(N²) brute-force overlap search
// with the generic dispatcher, for trial moves in dense mixtures, after NPT volume moves, and
// after many accepted moves in a box only a few rod lengths wide (the trees' case).
#include <gtest/gtest.h>

#include "anisodyn/config/builder.hpp"
#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/geometry/overlap.hpp"
#include "anisodyn/interactions/hard_overlap.hpp"
#include "anisodyn/mc/mc_engine.hpp"
#include "brute_force_search.hpp"
#include "lattice_states.hpp"
#include "thread_count.hpp"

using namespace anisodyn;
using anisodyn::testing_support::brute_force_overlaps;
using anisodyn::testing_support::lattice_of;
using anisodyn::testing_support::on_thread_counts;
using anisodyn::testing_support::with_threads;

namespace {

void compare_trials(const State& s, const HardOverlap& ho, Rng& rng, int trials, double step) {
  int hits = 0;
  for (int t = 0; t < trials; ++t) {
    const std::size_t i = rng.index(s.particles.size());
    Vec3 r = s.particles.position(i) + Vec3(rng.uniform(-step, step), rng.uniform(-step, step), rng.uniform(-step, step));
    Int3 image(0, 0, 0);
    s.box.wrap(r, image);
    const Quat q = rotate_in_body_frame(s.particles.orientation(i), Vec3(rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3)));
    const Mat3 rot = q.toRotationMatrix();
    const bool expected = brute_force_overlaps(s, i, r, rot);
    hits += expected;
    ASSERT_EQ(ho.overlaps(static_cast<std::int32_t>(i), r, rot), expected) << "trial " << t << " particle " << i;
  }
  // Both outcomes must occur, or the comparison says little.
  EXPECT_GT(hits, trials / 20);
  EXPECT_LT(hits, trials - trials / 20);
}

/// 150 randomly oriented boards 12×3.46×1 and 100 spheres d = 0.5, placed at random in a box two
/// or three board cut-offs wide (trees for the boards, a grid for the spheres).
State boards_and_spheres(Rng& rng) {
  State s;
  s.species.push_back(Species{"board", Shape::cuboid(1.0, 3.4641, 12.0), 1.0, {}, {}});
  s.species.push_back(Species{"tracer", Shape::sphere(0.5), 1.0, {}, {}});
  s.box = Box(Vec3(30, 30, 40));
  PlacementRequest req{{150, 100}, {OrientationRule{OrientationRule::Mode::Random}, OrientationRule{}}, 100000};
  insert_randomly(s, req, rng);
  return s;
}

}  // namespace

TEST(HardOverlap, MatchesBruteForceForHardSpheresAfterVolumeMoves) {
  Rng rng(17, 0);
  State s = lattice_of(Species{"hs", Shape::sphere(1.0), 1.0, {}, {}}, 500, 0.3, rng);
  McEngine mc(s, RngState{3, 0, 0, 4});
  mc.set_pressure(8.0);
  for (int c = 0; c < 200; ++c) mc.cycle();
  ASSERT_GT(mc.counters().volume_accepted, 0);
  HardOverlap fresh(s);
  compare_trials(s, fresh, rng, 4000, 0.3);
  compare_trials(s, mc.overlap(), rng, 4000, 0.3);  // the engine's incrementally updated copy
}

TEST(HardOverlap, MatchesBruteForceForBoardsAndSpheres) {
  Rng rng(5, 0);
  const State s = boards_and_spheres(rng);
  HardOverlap ho(s);
  // The box is two or three board cut-offs wide: the board grid would scan every cell.
  EXPECT_TRUE(ho.uses_tree(0, 0));
  EXPECT_TRUE(ho.uses_tree(1, 0));
  EXPECT_FALSE(ho.first_overlap().has_value());
  compare_trials(s, ho, rng, 3000, 1.0);
}

TEST(HardOverlap, TreesMatchBruteForceAfterManyAcceptedMoves) {
  // Rods 12×1×1 at η = 0.2 in a box about three rod lengths wide, compressed under pressure:
  // the engine's trees are refitted on every accepted move and after every volume move, and
  // rebuilt once per sweep; its decisions must still be the brute force's.
  Rng rng(23, 0);
  State s = lattice_of(Species{"rod", Shape::cuboid(1.0, 1.0, 12.0), 1.0, {}, {}}, 400, 0.2, rng);
  McEngine mc(s, RngState{9, 0, 0, 4});
  ASSERT_TRUE(mc.overlap().uses_tree(0, 0));
  mc.set_pressure(1.0);
  for (int c = 0; c < 60; ++c) mc.cycle();
  ASSERT_GT(mc.counters().translate_accepted[0], 400);
  ASSERT_GT(mc.counters().volume_accepted, 0);
  EXPECT_FALSE(mc.overlap().first_overlap().has_value());
  compare_trials(s, mc.overlap(), rng, 4000, 0.5);
  HardOverlap fresh(s);
  compare_trials(s, fresh, rng, 2000, 0.5);
}

TEST(HardOverlap, AnyOverlapFindsOnePlantedPairOnOneOrTwoThreads) {
  // Lattices without overlaps (rods, searched by trees; spheres, by the grid), large enough that
  // the check runs on two threads when it has them, then copies in which one particle sits on
  // another's centre: the pair overlaps whatever the shapes (checked by brute force). The planted
  // pairs lie at the start, the middle and the end of the index range, so that on two threads
  // either thread's share holds them.
  Rng rng(41, 0);
  for (const State& s : {lattice_of(Species{"rod", Shape::cuboid(1.0, 1.0, 12.0), 1.0, {}, {}}, 1200, 0.2, rng),
                         lattice_of(Species{"hs", Shape::sphere(1.0), 1.0, {}, {}}, 1500, 0.3, rng)}) {
    const std::size_t n = s.particles.size();
    ASSERT_GE(n, 1000u);
    ASSERT_FALSE(HardOverlap(s).first_overlap().has_value());
    EXPECT_EQ(on_thread_counts({1, 2}, [&] { return HardOverlap(s).any_overlap(); }), (std::vector<bool>{false, false}));
    for (const auto& [i, j] : {std::pair<std::size_t, std::size_t>{0, 1}, {n / 2, 7}, {n - 1, n - 2}, {n / 3, n - 1}}) {
      State t = s;
      t.particles.set_position(i, t.particles.position(j));
      ASSERT_TRUE(brute_force_overlaps(t, i, t.particles.position(i), t.particles.orientation(i).toRotationMatrix()));
      EXPECT_EQ(on_thread_counts({1, 2}, [&] { return HardOverlap(t).any_overlap(); }), (std::vector<bool>{true, true}))
          << s.species[0].name << ": particle " << i << " on " << j;
    }
  }
}

TEST(HardOverlap, RefreshAfterMovesMadeBehindItsBackMatchesBruteForce) {
  // Rods (trees) and spheres (grid) moved by an engine working on a copy of the state, which the
  // search is not told of; refresh() with fewer unseen moves than particles refits the trees
  // instead of rebuilding them. Then the copy is compressed by 1%, positions with the box, as a
  // volume move does. Either way the search must decide trials as the brute force does.
  Rng rng(29, 0);
  State s = lattice_of(Species{"rod", Shape::cuboid(1.0, 1.0, 12.0), 1.0, {}, {}}, 400, 0.2, rng);
  HardOverlap ho(s);
  ASSERT_TRUE(ho.uses_tree(0, 0));
  State moved = s;
  McEngine mc(moved, RngState{5, 0, 0, 4});
  mc.cycle();
  const std::int64_t accepted = mc.counters().translate_accepted[0] + mc.counters().rotate_accepted[0];
  ASSERT_GT(accepted, 50);
  ASSERT_LT(accepted, 400);  // below one move per particle: the refit path
  ho.refresh(moved, {accepted});
  EXPECT_TRUE(ho.uses_tree(0, 0));
  compare_trials(moved, ho, rng, 3000, 0.5);
  const Vec3 old_edges = moved.box.edges();
  moved.box.set_edges(old_edges * 0.99);
  for (std::size_t i = 0; i < moved.particles.size(); ++i) moved.particles.set_position(i, moved.particles.position(i) * 0.99);
  ho.refresh(moved, {0});
  compare_trials(moved, ho, rng, 3000, 0.5);
  EXPECT_EQ(ho.first_overlap().has_value(), HardOverlap(moved).first_overlap().has_value());
  EXPECT_THROW(ho.refresh(moved, {}), std::invalid_argument);
}

TEST(HardOverlap, OverlappingParticleNamesAWitnessAndQueriesSuspectsFirst) {
  // Two planted pairs (a particle on another's centre) in a lattice of rods. On one thread the
  // scan in index order names the lower index of the first pair; on two, either pair's; with the
  // second pair's lower index among the suspects, that one, whatever the threads.
  Rng rng(41, 1);
  const State s = lattice_of(Species{"rod", Shape::cuboid(1.0, 1.0, 12.0), 1.0, {}, {}}, 1200, 0.2, rng);
  const std::size_t n = s.particles.size();
  EXPECT_EQ(on_thread_counts({1, 2}, [&] { return HardOverlap(s).overlapping_particle({3, 5}).has_value(); }),
            (std::vector<bool>{false, false}));
  State t = s;
  t.particles.set_position(n / 2, t.particles.position(7));    // pair (7, n/2)
  t.particles.set_position(n - 1, t.particles.position(n / 3));  // pair (n/3, n − 1)
  const auto first = 7, second = static_cast<std::int32_t>(n / 3);
  EXPECT_EQ(with_threads(1, [&] { return HardOverlap(t).overlapping_particle(); }), std::optional<std::int32_t>(first));
  const std::int32_t witness = with_threads(2, [&] { return HardOverlap(t).overlapping_particle().value_or(-1); });
  EXPECT_TRUE(witness == first || witness == second) << witness;
  EXPECT_EQ(on_thread_counts({1, 2}, [&] { return HardOverlap(t).overlapping_particle({3, second, first}).value_or(-1); }),
            (std::vector<std::int32_t>{second, second}));
  // Suspects outside the configuration are skipped.
  EXPECT_EQ(HardOverlap(t).overlapping_particle({-1, static_cast<std::int32_t>(n)}), std::optional<std::int32_t>(first));
}

TEST(HardOverlap, SpheresInALargeBoxKeepTheGrid) {
  Rng rng(3, 0);
  const State s = lattice_of(Species{"hs", Shape::sphere(1.0), 1.0, {}, {}}, 500, 0.3, rng);
  EXPECT_FALSE(HardOverlap(s).uses_tree(0, 0));
}

TEST(HardOverlap, AlignedRodsInABoxOfManyCellsTakeTheTree) {
  // 6000 rods 12×1×1 at η = 0.2: a box of 6 cells, so the grid does not scan every cell, but a
  // query's 27 cells hold ~100 times the volume of the rods' lab boxes (the tree wins). The
  // same rods turned at random (overlapping, which the choice does not look at) keep the grid.
  Rng rng(8, 0);
  const State rods = lattice_of(Species{"rod", Shape::cuboid(1.0, 1.0, 12.0), 1.0, {}, {}}, 6000, 0.2, rng);
  const HardOverlap ho(rods);
  ASSERT_TRUE(ho.uses_tree(0, 0));
  compare_trials(rods, ho, rng, 3000, 0.4);
  State turned = rods;
  for (std::size_t i = 0; i < turned.particles.size(); ++i) turned.particles.set_orientation(i, uniform_quaternion(rng.uniform(), rng.uniform(), rng.uniform()));
  EXPECT_FALSE(HardOverlap(turned).uses_tree(0, 0));
}
