// Cell-list neighbour sets against brute-force O(N²) minimum-image sets, for mixtures of very
// different sizes and for elongated boxes, before and after many incremental moves.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "anisodyn/core/rng.hpp"
#include "anisodyn/neighbors/cell_list.hpp"

using namespace anisodyn;

namespace {

struct Cloud {
  Box box;
  std::vector<double> x, y, z;
  std::vector<std::int32_t> species;
};

Cloud random_cloud(Rng& rng, const Vec3& edges, const std::vector<std::size_t>& counts) {
  Cloud c{Box(edges), {}, {}, {}, {}};
  for (std::size_t s = 0; s < counts.size(); ++s)
    for (std::size_t i = 0; i < counts[s]; ++i) {
      c.x.push_back(rng.uniform() * edges.x());
      c.y.push_back(rng.uniform() * edges.y());
      c.z.push_back(rng.uniform() * edges.z());
      c.species.push_back(static_cast<std::int32_t>(s));
    }
  return c;
}

std::set<int> brute_force(const Cloud& c, const Vec3& r, int species, double rc, int exclude) {
  std::set<int> out;
  for (std::size_t j = 0; j < c.x.size(); ++j) {
    if (c.species[j] != species || static_cast<int>(j) == exclude) continue;
    const Vec3 d = c.box.min_image(Vec3(c.x[j], c.y[j], c.z[j]) - r);
    if (d.squaredNorm() <= rc * rc) out.insert(static_cast<int>(j));
  }
  return out;
}

void expect_same_sets(const Cloud& c, const CellList& cells, const std::vector<double>& cutoff_per_pair,
                      int nspecies, int queries, Rng& rng) {
  for (int q = 0; q < queries; ++q) {
    const int i = static_cast<int>(rng.index(c.x.size()));
    const Vec3 r(c.x[i], c.y[i], c.z[i]);
    for (int b = 0; b < nspecies; ++b) {
      const double rc = cutoff_per_pair[static_cast<std::size_t>(c.species[i] * nspecies + b)];
      std::set<int> found;
      cells.visit(b, r, rc, [&](int j, const Vec3& d, double r2) {
        EXPECT_NEAR(d.squaredNorm(), r2, 1e-9);
        if (j != i) {
          EXPECT_TRUE(found.insert(j).second) << "visited twice: " << j;
        }
        return false;
      });
      ASSERT_EQ(found, brute_force(c, r, b, rc, i)) << "query " << q << " species " << b;
    }
  }
}

/// As many moves of random particles as there are particles, each by up to `step` per axis.
void move_at_random(Cloud& c, CellList& cells, double step, Rng& rng) {
  for (std::size_t m = 0; m < c.x.size(); ++m) {
    const std::size_t i = rng.index(c.x.size());
    Vec3 r(c.x[i] + rng.uniform(-step, step), c.y[i] + rng.uniform(-step, step), c.z[i] + rng.uniform(-step, step));
    Int3 image(0, 0, 0);
    c.box.wrap(r, image);
    c.x[i] = r.x(); c.y[i] = r.y(); c.z[i] = r.z();
    cells.move(static_cast<std::int32_t>(i), r);
  }
}

/// A filter that keeps separations inside a lab box of half-widths e: the grid may then skip cells
/// that do not meet it, and must still find every kept particle once.
struct KeepInsideBox {
  Vec3 e;
  bool operator()(double dx, double dy, double dz) const {
    return std::abs(dx) <= e.x() && std::abs(dy) <= e.y() && std::abs(dz) <= e.z();
  }
  Vec3 extent(double rc) const { return e.cwiseMin(rc); }
};

void expect_filtered_sets(const Cloud& c, const CellList& cells, double rc, int queries, Rng& rng) {
  const Vec3 L = c.box.edges();
  for (int q = 0; q < queries; ++q) {
    // Half the queries sit within a hair of a cell or box boundary, where rounding decides.
    Vec3 r(rng.uniform() * L.x(), rng.uniform() * L.y(), rng.uniform() * L.z());
    if (q % 2 == 0) {
      const int k = static_cast<int>(rng.index(3));
      r[k] = rng.uniform() < 0.5 ? 1e-13 : std::nextafter(L[k], 0.0);
    }
    const KeepInsideBox keep{Vec3(rng.uniform(0.05, 1.2), rng.uniform(0.05, 1.2), rng.uniform(0.05, 1.2)) * rc};
    std::set<int> found, expected;
    cells.visit(0, r, rc, [&](int j, const Vec3& d, double) {
      EXPECT_TRUE(keep(d.x(), d.y(), d.z()));
      EXPECT_TRUE(found.insert(j).second) << "visited twice: " << j;
      return false;
    }, keep);
    for (int j : brute_force(c, r, 0, rc, -1)) {
      const Vec3 d = c.box.min_image(Vec3(c.x[static_cast<std::size_t>(j)], c.y[static_cast<std::size_t>(j)], c.z[static_cast<std::size_t>(j)]) - r);
      if (keep(d.x(), d.y(), d.z())) expected.insert(j);
    }
    ASSERT_EQ(found, expected) << "query " << q;
  }
}

}  // namespace

TEST(CellList, FilterWithShortExtentFindsEveryKeptParticle) {
  Rng rng(11, 4);
  // Sparse cells (the short pass over slots that may be empty) and full ones (the vector pass),
  // before and after moves that leave emptied slots behind.
  for (std::size_t n : {300, 6000}) {
    Cloud c = random_cloud(rng, Vec3(12, 15, 20), {n});
    CellList cells;
    cells.build(c.box, c.x, c.y, c.z, c.species, {2.0});
    expect_filtered_sets(c, cells, 2.0, 300, rng);
    move_at_random(c, cells, 2.0, rng);
    expect_filtered_sets(c, cells, 2.0, 300, rng);
  }
}

TEST(CellList, MixtureOfTinySpheresAndLargeBoards) {
  // 12×8×1 boards (circumradius 7.23) with spheres of diameter 0.1, as in the tracer study.
  Rng rng(2024, 1);
  const double rb = 0.5 * std::sqrt(144.0 + 64.0 + 1.0), rs = 0.05;
  Cloud c = random_cloud(rng, Vec3(40, 40, 40), {300, 2000});
  const std::vector<double> self = {2 * rb, 2 * rs};
  const std::vector<double> pair = {2 * rb, rb + rs, rb + rs, 2 * rs};
  CellList cells;
  cells.build(c.box, c.x, c.y, c.z, c.species, self);
  // The sphere grid must not have degenerated to one huge cell or millions of tiny ones.
  EXPECT_GT(cells.grid(1).cells_per_axis().minCoeff(), 5);
  EXPECT_LE(cells.grid(1).cells_per_axis().cast<double>().prod(), 2.0 * 2000);
  expect_same_sets(c, cells, pair, 2, 300, rng);
}

TEST(CellList, ElongatedBoxAndIncrementalMoves) {
  Rng rng(7, 2);
  Cloud c = random_cloud(rng, Vec3(10, 10, 30), {600, 150});
  const std::vector<double> self = {1.0, 2.5};
  const std::vector<double> pair = {1.0, 1.75, 1.75, 2.5};
  CellList cells;
  cells.build(c.box, c.x, c.y, c.z, c.species, self);
  // The long axis gets about three times as many cells as the short ones.
  const Int3 n = cells.grid(0).cells_per_axis();
  EXPECT_NEAR(double(n.z()) / n.x(), 3.0, 0.5);
  for (int sweep = 0; sweep < 5; ++sweep) {
    move_at_random(c, cells, 3.0, rng);
    expect_same_sets(c, cells, pair, 2, 200, rng);
  }
}

TEST(CellList, CutoffLongerThanThirdOfTheBoxVisitsEachCellOnce) {
  // Reach wraps the whole axis: every particle must still be found exactly once.
  Rng rng(3, 3);
  Cloud c = random_cloud(rng, Vec3(6, 6, 18), {400});
  CellList cells;
  cells.build(c.box, c.x, c.y, c.z, c.species, {1.0});
  expect_same_sets(c, cells, {2.9}, 1, 200, rng);
}

TEST(CellList, OverfullCellsGrowCapacity) {
  Rng rng(5, 5);
  Cloud c = random_cloud(rng, Vec3(10, 10, 10), {200});
  CellList cells;
  cells.build(c.box, c.x, c.y, c.z, c.species, {1.0});
  const std::size_t cap = cells.grid(0).capacity();
  for (std::size_t i = 0; i < 60; ++i) {  // pile 60 particles into one cell
    c.x[i] = 0.5; c.y[i] = 0.5; c.z[i] = 0.5 + 0.001 * static_cast<double>(i);
    cells.move(static_cast<std::int32_t>(i), Vec3(c.x[i], c.y[i], c.z[i]));
  }
  EXPECT_GT(cells.grid(0).capacity(), cap);
  expect_same_sets(c, cells, {1.0}, 1, 200, rng);
}
