// Verlet lists of segments (neighbors/verlet_list.hpp) and the BD rod forces over them
// (PairForceField<RodOverlapPairs>, each pair evaluated once), on dense configurations of rods
// (L/D = 20, (L/D)φ ≈ 1.8) with stacks of nearly parallel rods (the near-parallel branch, whose
// pairs reach a little beyond D in segment distance) and spheres (points in the same list), along
// a random walk of small moves and turns that makes the list rebuild many times:
//   - after every step the list holds every pair of segments closer than the cut-off (checked
//     against all pairs), and update() rebuilt exactly when some |Δr| + h|Δû| exceeded skin/2 (a
//     few jumps beyond the candidates' half-skin make those be searched again too);
//   - the rows are sorted and consistent (each pair in both rows with one pair number);
//   - forces, torques and energy equal an O(N²) sum of the kernel over all minimum-image pairs to
//     10⁻¹² relative, and the same bits for 1 and 2 threads;
//   - evaluating each pair once gives the same bits as owner-computes (each pair from both sides);
//   - a turn about the centre alone rebuilds the list once the end has moved more than skin/2;
//   - lists of points hold exactly the pairs within cut-off + skin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/geometry/spherocylinder.hpp"
#include "anisodyn/interactions/pair_force_field.hpp"
#include "anisodyn/interactions/rod_overlap_pairs.hpp"
#include "anisodyn/neighbors/verlet_list.hpp"
#include "field_forces.hpp"
#include "thread_count.hpp"

using namespace anisodyn;

namespace {

constexpr double kL = 20.0, kD = 1.0, kEdge = 50.0, kSkin = 0.6;
constexpr int kRods = 640, kStacks = 80, kSpheres = 30;

Vec3 axis_of(const Particles& p, std::size_t i) { return p.orientation(i) * Vec3::UnitZ(); }

void place(Particles& p, int species, Vec3 r, const Quat& q) {
  Int3 image(0, 0, 0);
  Box(Vec3::Constant(kEdge)).wrap(r, image);
  p.add(species, r, q, static_cast<std::int64_t>(p.size()));
}

/// kRods random rods (species 0), kStacks pairs of nearly parallel rods (sin γ < D/L) at
/// perpendicular distance below D and axial offsets up to about L, and kSpheres spheres (species 1).
State dense_rods(std::uint64_t seed) {
  State s;
  s.species = {Species{"rod", Shape::spherocylinder(kL, kD), 1.0, {}, {}}, Species{"ball", Shape::sphere(kD), 1.0, {}, {}}};
  s.box = Box(Vec3::Constant(kEdge));
  Rng rng(seed, 0);
  auto random_point = [&] { return Vec3(rng.uniform(0, kEdge), rng.uniform(0, kEdge), rng.uniform(0, kEdge)); };
  for (int i = 0; i < kRods; ++i)
    place(s.particles, 0, random_point(), uniform_quaternion(rng.uniform(), rng.uniform(), rng.uniform()));
  for (int k = 0; k < kStacks; ++k) {
    const Quat q = uniform_quaternion(rng.uniform(), rng.uniform(), rng.uniform());
    const Vec3 u = q * Vec3::UnitZ(), side = q * Vec3::UnitX();
    // Turned by up to 0.99 of the switch angle about a random perpendicular axis.
    const double phi = rng.uniform(0, 2 * M_PI);
    const Vec3 about = q * Vec3(std::cos(phi), std::sin(phi), 0.0);
    const Quat turned = quat_from_rotation_vector(std::asin(0.99 * kD / kL * rng.uniform()) * about) * q;
    const Vec3 r = random_point();
    place(s.particles, 0, r, q);
    place(s.particles, 0, r + rng.uniform(-1.0, 1.0) * kL * u + rng.uniform(0.0, 1.05 * kD) * side, turned);
  }
  for (int i = 0; i < kSpheres; ++i) place(s.particles, 1, random_point(), Quat::Identity());
  return s;
}

RodOverlapPairs evaluator() {
  return RodOverlapPairs{OverlapVolume({kL, kD, OverlapVolume::hardness_for(kD, 1.0), FiniteLengthRule::SegmentDistance}), 0, {}, {}};
}

/// The same evaluator, evaluated from both sides of each pair (owner computes).
struct BothSides : RodOverlapPairs {
  static constexpr bool kOncePerPair = false;
};

/// One step of the walk: every particle moves by a Gaussian of σ per axis, every rod turns by a
/// Gaussian rotation vector of σ_turn per axis (ends move by about L/2 · σ_turn √2).
void walk(State& s, Rng& rng, double sigma, double sigma_turn) {
  Particles& p = s.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    Vec3 r = p.position(i) + sigma * Vec3(rng.normal(), rng.normal(), rng.normal());
    Int3 image = p.image(i);
    s.box.wrap(r, image);
    p.set_position(i, r);
    p.set_image(i, image);
    if (p.species[i] == 0)
      p.set_orientation(i, rotate_in_lab_frame(p.orientation(i), sigma_turn * Vec3(rng.normal(), rng.normal(), rng.normal())));
  }
}

/// Ten particles jump by `distance` in random directions.
void kick(State& s, Rng& rng, double distance) {
  for (int k = 0; k < 10; ++k) {
    const auto i = static_cast<std::size_t>(rng.index(s.particles.size()));
    Vec3 r = s.particles.position(i) + distance * Vec3(rng.normal(), rng.normal(), rng.normal()).normalized();
    Int3 image = s.particles.image(i);
    s.box.wrap(r, image);
    s.particles.set_position(i, r);
    s.particles.set_image(i, image);
  }
}

double segment_distance2(const State& s, std::size_t i, std::size_t j) {
  const Particles& p = s.particles;
  const double hi = p.species[i] == 0 ? 0.5 * kL : 0.0, hj = p.species[j] == 0 ? 0.5 * kL : 0.0;
  return segment_segment_dist2(axis_of(p, i), hi, axis_of(p, j), hj, s.box.min_image(p.position(j) - p.position(i)));
}

/// Every pair closer than its cut-off (the segment cut-off between rods) is in both rows; the rows
/// are sorted, partners_above is the tail of the row above i, and each pair has one number.
void expect_complete_and_consistent(const VerletList& list, const State& s, int& near_pairs, int& beyond_d) {
  const Particles& p = s.particles;
  const std::size_t n = p.size();
  std::vector<int> seen(list.pairs(), 0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto row = list.partners(i);
    const auto slots = list.pair_slots(i);
    ASSERT_TRUE(std::is_sorted(row.begin(), row.end())) << i;
    ASSERT_TRUE(std::adjacent_find(row.begin(), row.end()) == row.end()) << i;
    const auto above = list.partners_above(i);
    ASSERT_EQ(above.data() + above.size(), row.data() + row.size());
    for (std::size_t m = 0; m < row.size(); ++m) {
      const auto j = static_cast<std::size_t>(row[m]);
      ASSERT_NE(j, i);
      ASSERT_EQ(j > i, m >= row.size() - above.size()) << i;
      const auto slot = static_cast<std::size_t>(slots[m]);
      ASSERT_LT(slot, list.pairs());
      ++seen[slot];
      if (j > i) {
        ASSERT_EQ(slot, list.first_pair_above(i) + (m - (row.size() - above.size())));
      }
      // The other row has i with the same pair number.
      const auto other = list.partners(j);
      const auto at = std::lower_bound(other.begin(), other.end(), static_cast<std::int32_t>(i));
      ASSERT_TRUE(at != other.end() && *at == static_cast<std::int32_t>(i)) << i << " " << j;
      ASSERT_EQ(list.pair_slots(j)[static_cast<std::size_t>(at - other.begin())], slots[m]);
    }
  }
  for (const int c : seen) ASSERT_EQ(c, 2);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const double rc = list.cutoff(p.species[i], p.species[j]);
      if (rc <= 0.0) continue;
      const double d2 = segment_distance2(s, i, j);
      if (d2 >= rc * rc) continue;
      ++near_pairs;
      beyond_d += d2 > kD * kD;
      const auto above = list.partners_above(i);
      ASSERT_TRUE(std::binary_search(above.begin(), above.end(), static_cast<std::int32_t>(j)))
          << "pair " << i << " " << j << " at segment distance " << std::sqrt(d2) << " is not listed";
    }
}

struct AllPairs {
  std::vector<Vec3> force, torque;
  double energy = 0.0, scale = 0.0;  // scale: the largest |F| and |T|/L, what round-off is relative to
  int interacting = 0, near_parallel = 0, beyond_d = 0;  // beyond_d: interacting at segment distance > D
};

AllPairs all_pairs(const State& s) {
  const OverlapVolume& pot = evaluator().potential;
  const Particles& p = s.particles;
  AllPairs a{std::vector<Vec3>(p.size(), Vec3::Zero()), std::vector<Vec3>(p.size(), Vec3::Zero())};
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.species[i] != 0) continue;
    for (std::size_t j = 0; j < p.size(); ++j) {
      if (j == i || p.species[j] != 0) continue;
      const Vec3 d = s.box.min_image(p.position(j) - p.position(i));
      const RodPairTerm t = pot(d, axis_of(p, i), axis_of(p, j));
      if (!t.interacts) continue;
      a.force[i] += t.force;
      a.torque[i] += t.torque;
      a.energy += 0.5 * t.energy;
      a.interacting += i < j;
      a.near_parallel += i < j && t.near_parallel;
      a.beyond_d += i < j && segment_distance2(s, i, j) > kD * kD;
    }
  }
  for (std::size_t i = 0; i < p.size(); ++i) a.scale = std::max({a.scale, a.force[i].norm(), a.torque[i].norm() / kL});
  return a;
}

BodyForces evaluate(PairForceField<RodOverlapPairs>& field, const State& s, int threads) {
  return testing_support::with_threads(threads, [&] { return testing_support::forces_of(field, s); });
}

}  // namespace

TEST(VerletList, SegmentCutoffOfTheRodsExceedsDByTheNearParallelReach) {
  const OverlapVolume& pot = evaluator().potential;
  const double gs = std::asin(kD / kL), eps = kL * std::pow(std::sin(gs / 2), 2) / std::cos(gs / 2);
  EXPECT_NEAR(pot.segment_cutoff(), std::sqrt(kD * kD + eps * eps), 1e-15 * kD);
  EXPECT_GT(pot.segment_cutoff(), kD);
  EXPECT_LT(pot.segment_cutoff(), kD * (1.0 + 1e-3));
}

TEST(VerletList, RodListHoldsEveryCloseSegmentPairAndForcesEqualTheAllPairsSumAlongAWalk) {
  State s = dense_rods(7);
  const RodOverlapPairs e = evaluator();
  PairForceField<RodOverlapPairs> field(e, e.segment_cutoffs(2), 2, kSkin, e.half_lengths(2));
  Rng rng(7, 1);
  std::vector<Vec3> r_ref, u_ref;  // where the list was last built
  int near_pairs = 0, beyond_d = 0, checked = 0, interacting = 0, near_parallel = 0, interacting_beyond_d = 0, quiet_steps = 0;
  double worst = 0.0;
  const int steps = 120;
  for (int step = 0; step <= steps; ++step) {
    if (step > 0) walk(s, rng, 0.01 * kD, 0.004);  // ends move by about 0.06 D per step
    if (step % 40 == 20) kick(s, rng, 1.25 * kSkin);  // beyond the candidates' half-skin
    // The rule of the list, by hand: rebuilt iff some |Δr| + (L/2)|Δû| > skin/2 (or no list yet).
    bool expect_rebuild = r_ref.empty();
    for (std::size_t i = 0; !expect_rebuild && i < s.particles.size(); ++i) {
      const double h = s.particles.species[i] == 0 ? 0.5 * kL : 0.0;
      const double moved = s.box.min_image(s.particles.position(i) - r_ref[i]).norm() + h * (axis_of(s.particles, i) - u_ref[i]).norm();
      expect_rebuild = moved > 0.5 * kSkin;
    }
    const std::int64_t builds = field.list().builds();
    const BodyForces one = evaluate(field, s, 1);
    const bool rebuilt = field.list().builds() > builds;
    ASSERT_EQ(rebuilt, expect_rebuild) << "step " << step;
    quiet_steps += !rebuilt;
    if (rebuilt) {
      r_ref.resize(s.particles.size());
      u_ref.resize(s.particles.size());
      for (std::size_t i = 0; i < s.particles.size(); ++i) {
        r_ref[i] = s.particles.position(i);
        u_ref[i] = axis_of(s.particles, i);
      }
    }
    expect_complete_and_consistent(field.list(), s, near_pairs, beyond_d);
    const BodyForces two = evaluate(field, s, 2);
    ASSERT_EQ(one.force, two.force) << "step " << step;
    ASSERT_EQ(one.torque, two.torque) << "step " << step;
    ASSERT_EQ(one.energy, two.energy) << "step " << step;
    if (step % 8 != 0) continue;
    const AllPairs ref = all_pairs(s);
    ++checked;
    interacting += ref.interacting;
    near_parallel += ref.near_parallel;
    interacting_beyond_d += ref.beyond_d;
    for (std::size_t i = 0; i < s.particles.size(); ++i) {
      const double ef = (one.force[i] - ref.force[i]).norm(), et = (one.torque[i] - ref.torque[i]).norm() / kL;
      worst = std::max({worst, ef / ref.scale, et / ref.scale});
      ASSERT_LE(ef, 1e-12 * ref.scale) << "step " << step << " particle " << i;
      ASSERT_LE(et, 1e-12 * ref.scale) << "step " << step << " particle " << i;
      if (s.particles.species[i] != 0) {
        ASSERT_EQ(one.force[i], Vec3::Zero());
      }
    }
    ASSERT_NEAR(one.energy, ref.energy, 1e-12 * ref.energy) << "step " << step;
  }
  const std::int64_t builds = field.list().builds(), candidate_builds = field.list().candidates()->builds();
  std::printf("%d steps: %lld list builds (%lld of the candidates), %d steps without; %d close segment pairs "
              "(%d beyond D); %d checks against all pairs: %d interacting pairs (%d near-parallel, %d beyond D), worst %.2g\n",
              steps, static_cast<long long>(builds), static_cast<long long>(candidate_builds), quiet_steps, near_pairs, beyond_d,
              checked, interacting, near_parallel, interacting_beyond_d, worst);
  EXPECT_GT(builds, 10);   // the rule was exercised both ways
  EXPECT_GT(quiet_steps, steps / 2);
  EXPECT_GT(candidate_builds, 1);
  EXPECT_LT(candidate_builds, builds);
  EXPECT_GT(interacting, 1000 * checked);
  EXPECT_GT(near_parallel, 20 * checked);
}

TEST(VerletList, EachPairOnceGivesTheBitsOfOwnerComputes) {
  State s = dense_rods(11);
  Rng rng(11, 1);
  RodOverlapPairs once = evaluator();
  BothSides both{once};
  VerletList list(once.segment_cutoffs(2), 2, kSkin, once.half_lengths(2));
  for (int step = 0; step < 10; ++step) {
    walk(s, rng, 0.01 * kD, 0.004);
    list.update(s.box, s.particles);
    once.prepare(s);
    both.prepare(s);
    std::vector<Vec3> f_once, t_once, f_both, t_both;
    const auto sums_once = accumulate_pair_forces(s.box, s.particles, list, once, f_once, &t_once);
    const auto sums_both = accumulate_pair_forces(s.box, s.particles, list, both, f_both, &t_both);
    ASSERT_EQ(f_once, f_both) << "step " << step;
    ASSERT_EQ(t_once, t_both) << "step " << step;
    ASSERT_EQ(sums_once.energy, sums_both.energy);
    ASSERT_EQ(sums_once.virial[0], sums_both.virial[0]);
  }
}

TEST(VerletList, TurningARodAboutItsCentreRebuildsOnceTheEndMovedHalfTheSkin) {
  State s = dense_rods(13);
  const RodOverlapPairs e = evaluator();
  VerletList list(e.segment_cutoffs(2), 2, kSkin, e.half_lengths(2));
  list.build(s.box, s.particles);
  const Quat q0 = s.particles.orientation(5);
  const Vec3 about = q0 * Vec3::UnitX();  // perpendicular to the axis
  // The end moves by (L/2)|Δû| = L sin(θ/2).
  auto turn_end_by = [&](double distance) {
    s.particles.set_orientation(5, quat_from_rotation_vector(2.0 * std::asin(distance / kL) * about) * q0);
  };
  turn_end_by(0.49 * kSkin);
  EXPECT_FALSE(list.update(s.box, s.particles));
  turn_end_by(0.51 * kSkin);
  EXPECT_TRUE(list.update(s.box, s.particles));
  EXPECT_EQ(list.builds(), 2);
  // Spinning about its own axis moves no point of the segment.
  s.particles.set_orientation(5, s.particles.orientation(5) * quat_from_rotation_vector(Vec3(0.0, 0.0, 2.0)));
  EXPECT_FALSE(list.update(s.box, s.particles));
}

TEST(VerletList, ListsOfPointsHoldExactlyThePairsWithinCutoffPlusSkin) {
  Rng rng(17, 0);
  const Box box(Vec3(6.0, 7.0, 8.0));
  Particles p;
  for (int i = 0; i < 600; ++i) p.add(static_cast<int>(rng.index(2)), Vec3(rng.uniform(0, 6), rng.uniform(0, 7), rng.uniform(0, 8)), Quat::Identity(), i);
  const double skin = 0.2;
  const std::vector<double> cutoffs = {0.5, 0.7, 0.7, 0.9};
  VerletList list(cutoffs, 2, skin);
  list.build(box, p);
  EXPECT_EQ(list.candidates(), nullptr);
  std::size_t listed = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::vector<std::int32_t> expected;
    for (std::size_t j = 0; j < p.size(); ++j) {
      const double rc = list.cutoff(p.species[i], p.species[j]) + skin;
      if (j != i && box.min_image(p.position(j) - p.position(i)).squaredNorm() <= rc * rc) expected.push_back(static_cast<std::int32_t>(j));
    }
    const auto row = list.partners(i);
    EXPECT_EQ(std::vector<std::int32_t>(row.begin(), row.end()), expected) << i;
    listed += row.size();
  }
  EXPECT_EQ(listed, 2 * list.pairs());
  EXPECT_GT(list.pairs(), 1000u);
}
