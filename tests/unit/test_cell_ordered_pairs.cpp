// CellOrderedPairs against a brute-force search of all pairs: the same pairs (closer than cut-off +
// skin, minimum image) in boxes of 2, 3 and many cells per edge, non-cubic ones and unwrapped
// positions; rows ascending; lower_pairs the transpose of the rows; the rebuild rule; and a list
// rebuilt from built_positions() identical to the original.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "anisodyn/neighbors/cell_ordered_pairs.hpp"
#include "thread_count.hpp"

using namespace anisodyn;

namespace {

struct Cloud {
  Box box;
  std::vector<double> x, y, z;
};

Cloud random_cloud(const Vec3& edges, std::size_t n, unsigned seed, double unwrap = 0.0) {
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0), shift(-unwrap, unwrap);
  Cloud c{Box(edges), {}, {}, {}};
  for (std::size_t i = 0; i < n; ++i) {
    // Some particles far outside the box (unwrapped trajectories): the list must wrap them.
    c.x.push_back(edges.x() * (u(gen) + std::round(shift(gen))));
    c.y.push_back(edges.y() * (u(gen) + std::round(shift(gen))));
    c.z.push_back(edges.z() * (u(gen) + std::round(shift(gen))));
  }
  return c;
}

std::set<std::pair<int, int>> brute_force(const Cloud& c, double reach) {
  std::set<std::pair<int, int>> out;
  for (std::size_t i = 0; i < c.x.size(); ++i)
    for (std::size_t j = i + 1; j < c.x.size(); ++j) {
      const Vec3 d = c.box.min_image(Vec3(c.x[i] - c.x[j], c.y[i] - c.y[j], c.z[i] - c.z[j]));
      if (d.squaredNorm() < reach * reach) out.insert({static_cast<int>(i), static_cast<int>(j)});
    }
  return out;
}

/// The list's pairs as particle pairs (lower index first), checking the structure on the way.
std::set<std::pair<int, int>> listed(const CellOrderedPairs& list) {
  std::set<std::pair<int, int>> out;
  const auto order = list.order();
  std::vector<std::vector<std::int32_t>> lower(list.size());
  for (std::size_t k = 0; k < list.size(); ++k) {
    const auto row = list.partners_above(k);
    EXPECT_TRUE(std::is_sorted(row.begin(), row.end()));
    for (std::size_t m = 0; m < row.size(); ++m) {
      EXPECT_GT(static_cast<std::size_t>(row[m]), k);
      const int i = order[k], j = order[static_cast<std::size_t>(row[m])];
      EXPECT_TRUE(out.insert({std::min(i, j), std::max(i, j)}).second) << "pair listed twice";
      lower[static_cast<std::size_t>(row[m])].push_back(static_cast<std::int32_t>(list.first_pair(k) + m));
    }
  }
  for (std::size_t k = 0; k < list.size(); ++k) {
    const auto got = list.lower_pairs(k);
    EXPECT_EQ(std::vector<std::int32_t>(got.begin(), got.end()), lower[k]) << "position " << k;
  }
  return out;
}

}  // namespace

TEST(CellOrderedPairs, ThePairsOfABruteForceSearch) {
  // On 1, 2 and 3 threads: the rows and the lower pairs are built in blocks, one per thread.
  for (int threads : {1, 2, 3}) {
    const testing_support::ScopedThreadCount count(threads);
    SCOPED_TRACE(std::to_string(threads) + " threads");
    const double cutoff = 1.0, skin = 0.3;
    const std::vector<Vec3> boxes = {Vec3(2.6, 2.6, 2.6), Vec3(3.0, 3.0, 3.0), Vec3(4.0, 5.3, 2.7), Vec3(8.0, 8.0, 8.0), Vec3(11.0, 6.5, 9.2)};
    unsigned seed = 1;
    for (const Vec3& edges : boxes) {
      const auto n = static_cast<std::size_t>(3.0 * edges.prod());
      const Cloud c = random_cloud(edges, n, seed++, 2.0);
      CellOrderedPairs list(cutoff, skin);
      ASSERT_TRUE(list.update(c.box, c.x.data(), c.y.data(), c.z.data(), n));
      std::vector<std::int32_t> order(list.order().begin(), list.order().end());
      std::sort(order.begin(), order.end());
      for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(order[i], static_cast<std::int32_t>(i)) << "order is not a permutation";
      const auto expected = brute_force(c, cutoff + skin);
      EXPECT_EQ(listed(list), expected) << "box " << edges.transpose();
      EXPECT_EQ(list.pairs(), expected.size());
    }
  }
}

TEST(CellOrderedPairs, RebuildsOnceAParticleMovedHalfTheSkin) {
  Cloud c = random_cloud(Vec3(6.0, 6.0, 6.0), 648, 7);
  CellOrderedPairs list(1.0, 0.3);
  ASSERT_TRUE(list.update(c.box, c.x.data(), c.y.data(), c.z.data(), c.x.size()));
  c.x[10] += 0.149;
  EXPECT_FALSE(list.update(c.box, c.x.data(), c.y.data(), c.z.data(), c.x.size()));
  c.x[10] += 0.002;
  EXPECT_TRUE(list.update(c.box, c.x.data(), c.y.data(), c.z.data(), c.x.size()));
  EXPECT_EQ(list.builds(), 2);
  // A move across the periodic boundary is a short move, not a jump of a box edge.
  c.y[20] += 6.0;
  EXPECT_FALSE(list.update(c.box, c.x.data(), c.y.data(), c.z.data(), c.x.size()));
}

TEST(CellOrderedPairs, ARebuildFromTheBuildPositionsIsTheSameList) {
  Cloud c = random_cloud(Vec3(7.0, 7.0, 7.0), 1029, 9, 1.0);
  CellOrderedPairs list(1.0, 0.3), again(1.0, 0.3);
  list.update(c.box, c.x.data(), c.y.data(), c.z.data(), c.x.size());
  for (double& v : c.x) v += 0.01;  // moved since, within the skin
  again.rebuild_at(c.box, list.built_positions());
  EXPECT_FALSE(again.update(c.box, c.x.data(), c.y.data(), c.z.data(), c.x.size()));
  ASSERT_EQ(list.pairs(), again.pairs());
  EXPECT_TRUE(std::equal(list.order().begin(), list.order().end(), again.order().begin()));
  for (std::size_t k = 0; k < list.size(); ++k) {
    const auto a = list.partners_above(k), b = again.partners_above(k);
    ASSERT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end()));
  }
}
