// The pair-force loop (interactions/pair_forces.hpp) over Verlet lists (neighbors/verlet_list.hpp),
// with the WCA evaluator: against an O(N²) sum over all pairs (same terms in the same order; the
// compiler may contract the two loops' arithmetic differently, so to round-off), against central finite differences of the energy (forces) and of the energy under a
// uniform dilation (virial), Newton's third law, the same results for 1 and 2 threads, and list
// rebuilds exactly when a particle has moved more than half the skin.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "anisodyn/core/rng.hpp"
#include "anisodyn/interactions/pair_force_field.hpp"
#include "anisodyn/interactions/wca.hpp"
#include "anisodyn/neighbors/verlet_list.hpp"
#include "thread_count.hpp"

using namespace anisodyn;

namespace {

/// 512 particles on a simple cubic lattice of spacing 1.05σ, each displaced by up to ±0.08σ per
/// axis: most neighbours within the WCA range, none closer than 0.89σ.
Particles jittered_lattice(Rng& rng, Box& box, int m = 8) {
  const double a = 1.05;
  box = Box(Vec3::Constant(m * a));
  Particles p;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k) {
        Vec3 r = a * Vec3(i + 0.5, j + 0.5, k + 0.5) + Vec3(rng.uniform(-0.08, 0.08), rng.uniform(-0.08, 0.08), rng.uniform(-0.08, 0.08));
        Int3 image(0, 0, 0);
        box.wrap(r, image);
        p.add(0, r, Quat::Identity(), static_cast<std::int64_t>(p.size()));
      }
  return p;
}

VerletList list_for(const Wca& wca, double skin) { return VerletList({wca.cutoff()}, 1, skin); }

/// A jittered WCA lattice of cells³ particles with its Verlet list built (skin 0.3).
struct WcaSystem {
  Rng rng;
  Box box;
  Particles p;
  Wca wca;
  VerletList list;
  WcaSystem(std::uint64_t seed, std::uint64_t stream, double sigma, int cells = 8)
      : rng(seed, stream), p(jittered_lattice(rng, box, cells)), wca{sigma, 1.0}, list(list_for(wca, 0.3)) {
    list.build(box, p);
  }
};

double energy_of(const Box& box, const Particles& p, const Wca& wca) {
  VerletList list = list_for(wca, 0.3);
  list.build(box, p);
  std::vector<Vec3> f;
  return accumulate_pair_forces(box, p, list, wca, f).energy;
}

struct Reference {
  std::vector<Vec3> force;
  std::vector<double> scale;  // Σ_j |F_ij|: what round-off is relative to
};

/// Σ over every other particle in index order: the same terms in the same order as the owner loop.
Reference brute_force(const Box& box, const Particles& p, const Wca& wca) {
  Reference ref{std::vector<Vec3>(p.size(), Vec3::Zero()), std::vector<double>(p.size(), 0.0)};
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = 0; j < p.size(); ++j) {
      if (j == i) continue;
      const Vec3 d = box.min_image(p.position(j) - p.position(i));
      const auto t = wca(i, j, d, d.squaredNorm());
      if (!t.interacts) continue;
      ref.force[i] += t.force[0];
      ref.scale[i] += t.force[0].norm();
    }
  return ref;
}

void expect_matches(const std::vector<Vec3>& f, const Reference& ref) {
  for (std::size_t i = 0; i < f.size(); ++i)
    ASSERT_LE((f[i] - ref.force[i]).norm(), 1e-13 * ref.scale[i]) << "particle " << i;
}

}  // namespace

TEST(PairForces, OwnerLoopEqualsTheAllPairsSum) {
  WcaSystem sys(3, 1, 1.0);
  const auto& [rng, box, p, wca, list] = sys;
  std::vector<Vec3> f;
  const auto sums = accumulate_pair_forces(box, p, list, wca, f);
  const Reference ref = brute_force(box, p, wca);
  expect_matches(f, ref);
  int interacting = 0;
  for (std::size_t i = 0; i < p.size(); ++i) interacting += ref.scale[i] > 0.0;
  EXPECT_GT(interacting, 400);
  EXPECT_GT(sums.energy, 0.0);
}

TEST(PairForces, ForcesAndVirialAreDerivativesOfTheEnergy) {
  WcaSystem sys(5, 2, 1.3);
  auto& [rng, box, p, wca, list] = sys;
  std::vector<Vec3> f;
  const auto sums = accumulate_pair_forces(box, p, list, wca, f);
  // Forces: F = −∂E/∂r, central differences on 30 random coordinates.
  const double h = 1e-6;
  for (int trial = 0; trial < 30; ++trial) {
    const std::size_t i = rng.index(p.size());
    const int k = static_cast<int>(rng.index(3));
    Particles plus = p, minus = p;
    Vec3 r = p.position(i);
    r[k] += h;
    plus.set_position(i, r);
    r[k] -= 2 * h;
    minus.set_position(i, r);
    const double numeric = -(energy_of(box, plus, wca) - energy_of(box, minus, wca)) / (2 * h);
    EXPECT_NEAR(f[i][k], numeric, 1e-5 * std::max(1.0, std::abs(numeric))) << "particle " << i << " axis " << k;
  }
  // Virial: scaling every position and the box by λ gives dE/dλ at λ = 1 equal to −tr W.
  auto dilated = [&](double lambda) {
    Particles q = p;
    for (std::size_t i = 0; i < q.size(); ++i) q.set_position(i, lambda * p.position(i));
    return energy_of(Box(lambda * box.edges()), q, wca);
  };
  const double dE = (dilated(1 + h) - dilated(1 - h)) / (2 * h);
  EXPECT_NEAR(sums.virial[0].trace(), -dE, 1e-5 * std::abs(dE));
  EXPECT_LT((sums.virial[0] - sums.virial[0].transpose()).norm(), 1e-9 * sums.virial[0].norm());
}

TEST(PairForces, NewtonsThirdLawAndThreadCountIndependence) {
  WcaSystem sys(7, 3, 1.0);
  const auto& [rng, box, p, wca, list] = sys;
  auto run = [&](int threads) {
    return testing_support::with_threads(threads, [&] {
      std::vector<Vec3> f;
      const auto s = accumulate_pair_forces(box, p, list, wca, f);
      return std::make_pair(f, s.energy);
    });
  };
  const auto one = run(1), two = run(2);
  EXPECT_EQ(one.first, two.first);
  EXPECT_EQ(one.second, two.second);
  Vec3 total = Vec3::Zero();
  double magnitude = 0.0;
  for (const auto& f : one.first) {
    total += f;
    magnitude += f.norm();
  }
  EXPECT_LT(total.norm(), 1e-12 * magnitude);
}

TEST(PairForces, ReusedScratchGivesTheSameSumsAsFreshStorage) {
  // The scratch holds the partial sums of an earlier, larger system and forces of another size:
  // nothing of them may leak into the next call.
  WcaSystem big(13, 5, 1.0), small(17, 6, 1.2, 6);
  std::vector<Vec3> f_fresh, f_reused, t_reused;
  PairScratch<Wca::kParts> scratch;
  accumulate_pair_forces(big.box, big.p, big.list, big.wca, f_reused, &t_reused, &scratch);
  const auto fresh = accumulate_pair_forces(small.box, small.p, small.list, small.wca, f_fresh);
  const auto reused = accumulate_pair_forces(small.box, small.p, small.list, small.wca, f_reused, &t_reused, &scratch);
  EXPECT_EQ(f_fresh, f_reused);
  EXPECT_EQ(fresh.energy, reused.energy);
  EXPECT_EQ(fresh.virial[0], reused.virial[0]);
  EXPECT_EQ(t_reused.size(), small.p.size());
}

TEST(PairForces, ListsAreRebuiltWhenAParticleMovedMoreThanHalfTheSkin) {
  WcaSystem sys(11, 4, 1.0);
  auto& [rng, box, p, wca, list] = sys;
  const double skin = 0.3;
  // Everyone moves by less than skin/2: the old list still holds every interacting pair.
  for (std::size_t i = 0; i < p.size(); ++i) {
    Vec3 r = p.position(i) + Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)).normalized() * 0.49 * skin * 0.999;
    Int3 image(0, 0, 0);
    box.wrap(r, image);
    p.set_position(i, r);
  }
  EXPECT_FALSE(list.update(box, p));
  std::vector<Vec3> f;
  accumulate_pair_forces(box, p, list, wca, f);
  expect_matches(f, brute_force(box, p, wca));
  // One particle beyond skin/2 from where the list was built: rebuilt.
  Vec3 r = p.position(17) + Vec3(0.2 * skin, 0.0, 0.0);
  Int3 image(0, 0, 0);
  box.wrap(r, image);
  p.set_position(17, r);
  EXPECT_TRUE(list.update(box, p));
  EXPECT_EQ(list.builds(), 2);
}

TEST(PairForces, AsAForceFieldItAddsTheSameTermsAndKeepsItsListUpToDate) {
  WcaSystem sys(19, 7, 1.0);
  State s;
  s.box = sys.box;
  s.particles = sys.p;
  PairForceField<Wca> field(sys.wca, {sys.wca.cutoff()}, 1, 0.3);
  BodyForces out;
  out.reset(s.particles.size());
  out.force[3] = Vec3(1, 2, 3);  // a term of another field, kept
  field(s, out);
  std::vector<Vec3> f;
  const auto sums = accumulate_pair_forces(sys.box, sys.p, sys.list, sys.wca, f);
  for (std::size_t i = 0; i < f.size(); ++i) EXPECT_EQ(out.force[i], f[i] + (i == 3 ? Vec3(1, 2, 3) : Vec3::Zero())) << i;
  EXPECT_EQ(out.energy, sums.energy);
  EXPECT_EQ(out.virial, sums.virial[0]);
  EXPECT_EQ(field.list().builds(), 1);
  // A particle moved beyond half the skin: the next call rebuilds and matches the all-pairs sum.
  Vec3 r = s.particles.position(5) + Vec3(0.2, 0.0, 0.0);
  Int3 image(0, 0, 0);
  s.box.wrap(r, image);
  s.particles.set_position(5, r);
  out.reset(s.particles.size());
  field(s, out);
  EXPECT_EQ(field.list().builds(), 2);
  expect_matches(out.force, brute_force(s.box, s.particles, sys.wca));
}
