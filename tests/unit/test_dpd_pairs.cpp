// The DPD pair forces (interactions/dpd_pairs.hpp, DpdForceField) against an independent
// O(N²) sum written here from spec 30 §2, part by part; the conservative force against central
// differences of the pair energy; Newton's third law; the virial by part against Σ r_ij F_ij; the
// pair noise symmetric in (i, j) and of unit variance; and the same bits for one and two threads.
#include <gtest/gtest.h>

#include <cmath>

#include "anisodyn/core/keyed_random.hpp"
#include "anisodyn/core/pair_noise.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/interactions/dpd_pairs.hpp"
#include "thread_count.hpp"

using namespace anisodyn;

namespace {

constexpr double kA = 25.0, kGamma = 4.5, kDt = 0.005;
constexpr std::uint64_t kSeed = 17;

/// n liquid particles at density 3 in a cubic box, random positions and velocities; ids shuffled
/// away from the indices so that the noise is keyed by id, not by position in the arrays.
State liquid(std::size_t n, double edge, std::uint64_t seed) {
  State s;
  s.species = {Species{"liquid", Shape::sphere(1.0), 1.0, {}, {}}};
  s.box = Box(Vec3::Constant(edge));
  Rng rng(seed, 0);
  for (std::size_t i = 0; i < n; ++i)
    s.particles.add(0, Vec3(rng.uniform(0, edge), rng.uniform(0, edge), rng.uniform(0, edge)), Quat::Identity(),
                    static_cast<std::int64_t>(7 * n - 3 * i));
  s.particles.carry_velocities();
  for (std::size_t i = 0; i < n; ++i) s.particles.set_velocity(i, Vec3(rng.normal(), rng.normal(), rng.normal()));
  return s;
}

DpdForceField field(std::uint64_t step, double gamma = kGamma) {
  DpdForceField f({kA, gamma, 1.0, 1.0}, kDt, kSeed, 0.3);
  f.set_noise_step(step);
  return f;
}

struct Reference {
  std::vector<std::array<Vec3, 3>> force;  // by part
  std::array<Mat3, 3> virial{Mat3::Zero(), Mat3::Zero(), Mat3::Zero()};
  double energy = 0.0;
  int pairs = 0;
};

/// Spec 30 §2 summed over all pairs i < j.
Reference reference(const State& s, std::uint64_t step) {
  const PairNoise noise(kSeed, kDpdPairNoise);
  const Particles& p = s.particles;
  Reference out;
  out.force.assign(p.size(), {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()});
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const Vec3 rij = s.box.min_image(p.position(i) - p.position(j));
      const double r = rij.norm();
      if (r >= 1.0) continue;
      ++out.pairs;
      const Vec3 e = rij / r;
      const double w = 1.0 - r;
      const double theta = noise(step, static_cast<std::uint32_t>(p.id[i]), static_cast<std::uint32_t>(p.id[j]));
      const std::array<Vec3, 3> f{kA * w * e, -kGamma * w * w * e.dot(p.velocity(i) - p.velocity(j)) * e,
                                  std::sqrt(2.0 * kGamma / kDt) * w * theta * e};
      for (int k = 0; k < 3; ++k) {
        out.force[i][static_cast<std::size_t>(k)] += f[static_cast<std::size_t>(k)];
        out.force[j][static_cast<std::size_t>(k)] -= f[static_cast<std::size_t>(k)];
        out.virial[static_cast<std::size_t>(k)] += rij * f[static_cast<std::size_t>(k)].transpose();
      }
      out.energy += 0.5 * kA * w * w;
    }
  return out;
}

BodyForces evaluate(DpdForceField& f, const State& s) {
  BodyForces out;
  out.reset(s.particles.size());
  f(s, out);
  return out;
}

}  // namespace

TEST(DpdPairs, ForcesEnergyAndVirialEqualTheAllPairsSumPartByPart) {
  const State s = liquid(648, 6.0, 3);
  auto f = field(41);
  const BodyForces got = evaluate(f, s);
  const Reference ref = reference(s, 41);
  ASSERT_GT(ref.pairs, 1500);
  EXPECT_NEAR(got.energy, ref.energy, 1e-10 * ref.energy);
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    const Vec3 total = ref.force[i][0] + ref.force[i][1] + ref.force[i][2];
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(got.force[i][k], total[k], 1e-9 * (1.0 + total.norm())) << i;
  }
  const auto& parts = f.last_sums().virial;
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_LT((parts[k] - ref.virial[k]).norm(), 1e-9 * (1.0 + ref.virial[k].norm())) << "part " << k;
}

TEST(DpdPairs, ConservativeForceIsMinusTheGradientOfTheEnergy) {
  // γ = 0 leaves the conservative part: F_i = −∂U/∂r_i by central differences.
  State s = liquid(200, 4.0, 5);
  auto f = field(0, 0.0);
  const BodyForces got = evaluate(f, s);
  const double h = 1e-6;
  for (std::size_t i : {0u, 17u, 99u, 150u})
    for (int k = 0; k < 3; ++k) {
      State plus = s, minus = s;
      Vec3 r = s.particles.position(i);
      r[k] += h;
      plus.particles.set_position(i, r);
      r[k] -= 2 * h;
      minus.particles.set_position(i, r);
      auto fp = field(0, 0.0), fm = field(0, 0.0);
      const double derivative = (evaluate(fp, plus).energy - evaluate(fm, minus).energy) / (2 * h);
      EXPECT_NEAR(got.force[i][k], -derivative, 1e-5 * (1.0 + std::abs(derivative))) << i << " " << k;
    }
}

TEST(DpdPairs, NewtonsThirdLawHoldsPairByPair) {
  const State s = liquid(648, 6.0, 7);
  auto f = field(3);
  const BodyForces got = evaluate(f, s);
  Vec3 sum = Vec3::Zero();
  double scale = 0.0;
  for (const Vec3& v : got.force) {
    sum += v;
    scale += v.norm();
  }
  EXPECT_LT(sum.norm(), 1e-12 * scale);
}

TEST(DpdPairs, PairNoiseIsSymmetricUnitNormalAndNewEachStep) {
  const PairNoise noise(kSeed, kDpdPairNoise);
  double sum = 0, sum2 = 0, lag = 0;
  const int n = 200000;
  for (int k = 0; k < n; ++k) {
    const auto i = static_cast<std::uint32_t>(k % 1000), j = static_cast<std::uint32_t>(1000 + k / 1000);
    const double x = noise(5, i, j);
    ASSERT_EQ(x, noise(5, j, i));
    sum += x;
    sum2 += x * x;
    lag += x * noise(6, i, j);
  }
  // Mean 0, variance 1 and no correlation between steps, each within 4 standard errors.
  EXPECT_LT(std::abs(sum / n), 4.0 / std::sqrt(n));
  EXPECT_LT(std::abs(sum2 / n - 1.0), 4.0 * std::sqrt(2.0 / n));
  EXPECT_LT(std::abs(lag / n), 4.0 / std::sqrt(n));
}

TEST(DpdPairs, ForcesAreTheSameBitsForOneAndTwoThreads) {
  const State s = liquid(1536, 8.0, 9);
  const std::vector<BodyForces> results = testing_support::on_thread_counts({1, 2}, [&] {
    auto f = field(12);
    return evaluate(f, s);
  });
  for (std::size_t i = 0; i < s.particles.size(); ++i) ASSERT_EQ(results[0].force[i], results[1].force[i]) << i;
  EXPECT_EQ(results[0].energy, results[1].energy);
  EXPECT_EQ(results[0].virial, results[1].virial);
}

TEST(DpdPairs, TheThreadCountDoesNotChangeABit) {
  // Blocks of positions per thread, pairs across blocks through slots: the same sums in the same
  // order for 1, 2 and 3 threads (on any machine: OpenMP runs 3 threads on 2 cores too).
  const State s = liquid(1536, 8.0, 9);
  std::vector<BodyForces> got;
  std::vector<DpdSums> sums;
  for (int threads : {1, 2, 3}) {
    const testing_support::ScopedThreadCount count(threads);
    // A second evaluation with moved particles and the same list: nothing of the first may remain
    // (pairs across blocks that left the cut-off once left stale slots behind).
    auto f = field(5);
    evaluate(f, s);
    State moved = s;
    for (std::size_t i = 0; i < moved.particles.size(); ++i) moved.particles.x[i] += 0.1 * std::sin(static_cast<double>(i));
    got.push_back(evaluate(f, moved));
    sums.push_back(f.last_sums());
  }
  for (std::size_t t = 1; t < got.size(); ++t) {
    for (std::size_t i = 0; i < s.particles.size(); ++i)
      ASSERT_TRUE(got[t].force[i] == got[0].force[i]) << "particle " << i << ", " << t + 1 << " threads: " << got[t].force[i].transpose()
                                                      << " against " << got[0].force[i].transpose();
    EXPECT_EQ(sums[t].energy, sums[0].energy);
    for (std::size_t k = 0; k < 3; ++k) EXPECT_TRUE(sums[t].virial[k] == sums[0].virial[k]);
  }
}

TEST(DpdPairs, PairsAcrossBlocksFollowListRebuildsAndThreadCounts) {
  // The pairs across blocks are found once per list build and block count: one field, evaluated
  // with 2 threads, then after moves past the skin (a new list) with 2, then with 3 and 1, gives
  // each time the bits of a fresh field on one thread.
  const State s = liquid(1536, 8.0, 9);
  State far = s;
  for (std::size_t i = 0; i < far.particles.size(); ++i) far.particles.x[i] += 0.4 * std::sin(static_cast<double>(i));
  auto fresh = [](const State& st) {
    return testing_support::with_threads(1, [&] {
      auto f = field(5);
      return evaluate(f, st);
    });
  };
  const BodyForces want_s = fresh(s), want_far = fresh(far);
  auto f = field(5);
  const auto builds_before = [&] { return f.list().builds(); };
  struct Case {
    int threads;
    const State* state;
    const BodyForces* want;
  };
  for (const Case& c : {Case{2, &s, &want_s}, Case{2, &far, &want_far}, Case{3, &far, &want_far}, Case{2, &s, &want_s}, Case{1, &far, &want_far}}) {
    const testing_support::ScopedThreadCount count(c.threads);
    const auto builds = builds_before();
    const BodyForces got = evaluate(f, *c.state);
    if (c.state == &far && c.threads == 2) {
      EXPECT_GT(f.list().builds(), builds) << "the move must rebuild the list";
    }
    for (std::size_t i = 0; i < s.particles.size(); ++i)
      ASSERT_TRUE(got.force[i] == c.want->force[i]) << "particle " << i << ", " << c.threads << " threads";
    EXPECT_EQ(got.energy, c.want->energy);
  }
}

TEST(DpdPairs, OnlyTheListedLiquidParticlesTakeDpdForces) {
  // The liquid of a state with other particles among it (colloids-to-be, here at random places):
  // the liquid's forces, energy and virial are those of the liquid alone, bit for bit, and the
  // others get nothing.
  const State alone_state = liquid(648, 6.0, 21);
  State mixed = alone_state;
  mixed.species.push_back(Species{"colloid", Shape::sphere(2.0), 4.2, {}, {}});
  const Particles& p = alone_state.particles;
  Rng rng(4, 0);
  std::vector<std::int32_t> liquid_indices;
  // Interleave: a colloid before every 100th liquid particle.
  Particles merged;
  merged.carry_velocities();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (i % 100 == 0) {
      merged.add(1, Vec3(rng.uniform(0, 6), rng.uniform(0, 6), rng.uniform(0, 6)), Quat::Identity(), static_cast<std::int64_t>(100000 + i));
      merged.set_velocity(merged.size() - 1, Vec3(1, 2, 3));
    }
    liquid_indices.push_back(static_cast<std::int32_t>(merged.size()));
    merged.add(0, p.position(i), Quat::Identity(), p.id[i]);
    merged.set_velocity(merged.size() - 1, p.velocity(i));
  }
  mixed.particles = merged;
  auto alone = field(3);
  const BodyForces expected = evaluate(alone, alone_state);
  auto subset = field(3);
  subset.set_liquid(liquid_indices);
  const BodyForces got = evaluate(subset, mixed);
  std::size_t u = 0;
  for (std::size_t i = 0; i < mixed.particles.size(); ++i) {
    if (u < liquid_indices.size() && static_cast<std::size_t>(liquid_indices[u]) == i) {
      ASSERT_TRUE(got.force[i] == expected.force[u]) << "liquid particle " << u;
      ++u;
    } else {
      ASSERT_TRUE(got.force[i] == Vec3::Zero()) << "colloid at " << i;
    }
  }
  EXPECT_EQ(subset.last_sums().energy, alone.last_sums().energy);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_TRUE(subset.last_sums().virial[k] == alone.last_sums().virial[k]);
}
