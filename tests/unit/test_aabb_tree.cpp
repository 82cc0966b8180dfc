// AABB-tree candidate sets against brute-force O(N) minimum-image sets: randomly oriented and
// nematic rods 12×1×1 mixed with small spheres, in cubic and elongated boxes about three rod
// lengths wide, queried anywhere including at the faces, edges and corners of the box; the same
// after thousands of moves without a rebuild and after insertions; early stop, empty and
// one-particle trees. Also prints the candidates per query against a cell grid's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <vector>

#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/geometry/shape.hpp"
#include "anisodyn/neighbors/aabb_tree.hpp"
#include "anisodyn/neighbors/cell_list.hpp"

using namespace anisodyn;

namespace {

const double kInf = std::numeric_limits<double>::infinity();
const Shape kRod = Shape::cuboid(1, 1, 12);
const Shape kSphere = Shape::sphere(1.0);

enum class Order { Isotropic, Nematic };

Mat3 random_rotation(Rng& rng, Order order) {
  if (order == Order::Isotropic) return uniform_quaternion(rng.uniform(), rng.uniform(), rng.uniform()).toRotationMatrix();
  // Long axis (body z) along lab z, tilted by about 0.15 rad.
  return quat_from_rotation_vector(Vec3(0.15 * rng.normal(), 0.15 * rng.normal(), 0.0)).toRotationMatrix();
}

/// Particles 0 … rods−1 are rods, the rest spheres; each species is a list of global indices.
struct Cloud {
  Box box;
  Order order;
  std::vector<Vec3> r, h;
  std::vector<std::int32_t> rods, spheres;
};

Vec3 half_extent_of(const Cloud& c, std::size_t i, Rng& rng) {
  return static_cast<int>(i) < static_cast<int>(c.rods.size()) ? kRod.lab_half_extents(random_rotation(rng, c.order))
                                                                 : kSphere.lab_half_extents(Mat3::Identity());
}

Vec3 random_point(Rng& rng, const Box& box) {
  const Vec3& L = box.edges();
  return Vec3(rng.uniform() * L.x(), rng.uniform() * L.y(), rng.uniform() * L.z());
}

Cloud random_cloud(Rng& rng, const Vec3& edges, Order order, int rods, int spheres) {
  Cloud c{Box(edges), order, {}, {}, {}, {}};
  for (int i = 0; i < rods + spheres; ++i) {
    (i < rods ? c.rods : c.spheres).push_back(i);
    c.r.push_back(random_point(rng, c.box));
    c.h.push_back(half_extent_of(c, static_cast<std::size_t>(i), rng));
  }
  return c;
}

/// (j → d) for every j of `members` whose box overlaps the query's under the minimum image and
/// whose centre is within rc.
std::map<int, Vec3> brute_force(const Cloud& c, const std::vector<std::int32_t>& members, const Vec3& r,
                                const Vec3& h, double rc) {
  std::map<int, Vec3> out;
  for (const std::int32_t j : members) {
    const Vec3 d = c.box.min_image(c.r[static_cast<std::size_t>(j)] - r);
    bool overlap = d.squaredNorm() <= rc * rc;
    for (int k = 0; k < 3; ++k) overlap = overlap && std::abs(d[k]) <= h[k] + c.h[static_cast<std::size_t>(j)][k];
    if (overlap) out.emplace(j, d);
  }
  return out;
}

void expect_query_matches(const Cloud& c, const AabbTree& tree, const std::vector<std::int32_t>& members,
                          const Vec3& r, const Vec3& h, double rc) {
  std::map<int, Vec3> found;
  const bool stopped = tree.visit(c.box, r, h, rc, [&](int j, const Vec3& d, double r2) {
    EXPECT_NEAR(d.squaredNorm(), r2, 1e-9);
    EXPECT_TRUE(found.emplace(j, d).second) << "visited twice: " << j;
    return false;
  });
  EXPECT_FALSE(stopped);
  const std::map<int, Vec3> expected = brute_force(c, members, r, h, rc);
  ASSERT_EQ(found.size(), expected.size()) << "query at " << r.transpose() << " h " << h.transpose() << " rc " << rc;
  for (const auto& [j, d] : expected) {
    ASSERT_EQ(found.count(j), 1u) << "missed " << j << " for the query at " << r.transpose();
    EXPECT_LT((found[j] - d).norm(), 1e-9) << "separation of " << j;
  }
}

/// Points on every face, edge and corner of the box (each coordinate at 0, just below L or
/// anywhere), then uniformly random points.
std::vector<Vec3> query_points(Rng& rng, const Box& box, int random) {
  std::vector<Vec3> out;
  const Vec3& L = box.edges();
  for (int a = 0; a < 27; ++a)
    for (int rep = 0; rep < 2; ++rep) {
      Vec3 q;
      for (int k = 0, code = a; k < 3; ++k, code /= 3) {
        const int where = code % 3;
        const double near = rep == 0 ? 0.0 : 0.3 * rng.uniform();
        q[k] = where == 0 ? near : (where == 1 ? rng.uniform() * L[k] : std::nextafter(L[k], 0.0) - near);
      }
      out.push_back(q);
    }
  for (int i = 0; i < random; ++i) out.push_back(random_point(rng, box));
  return out;
}

/// Queries of both species' trees with rod and sphere query boxes and several cut-offs.
void expect_trees_match(const Cloud& c, const AabbTree& rod_tree, const AabbTree& sphere_tree, Rng& rng, int random) {
  const double rod_rod = 2 * kRod.circumradius();
  for (const Vec3& r : query_points(rng, c.box, random)) {
    const bool rod_query = rng.uniform() < 0.7;
    const Vec3 h = rod_query ? kRod.lab_half_extents(random_rotation(rng, c.order)) : Vec3(0.5, 0.5, 0.5);
    for (const double rc : {kInf, rod_query ? rod_rod : 0.5 * rod_rod, 4.0}) {
      expect_query_matches(c, rod_tree, c.rods, r, h, rc);
      expect_query_matches(c, sphere_tree, c.spheres, r, h, rc);
    }
  }
}

struct Trees {
  AabbTree rods, spheres;
};

Trees build_trees(const Cloud& c) {
  Trees t;
  t.rods.build(c.box, c.rods, c.r, c.h);
  t.spheres.build(c.box, c.spheres, c.r, c.h);
  return t;
}

/// Moves particle i of the cloud (not of a tree) by up to `reach` per axis, wrapped, and turns it.
void displace(Cloud& c, std::size_t i, Rng& rng, double reach) {
  Vec3 r = c.r[i] + Vec3(rng.uniform(-reach, reach), rng.uniform(-reach, reach), rng.uniform(-reach, reach));
  Int3 image(0, 0, 0);
  c.box.wrap(r, image);
  c.r[i] = r;
  c.h[i] = half_extent_of(c, i, rng);
}

/// Random moves, with displacements that often cross the box faces and new orientations.
void random_moves(Cloud& c, Trees& t, Rng& rng, int moves) {
  for (int m = 0; m < moves; ++m) {
    const std::size_t i = rng.index(c.r.size());
    displace(c, i, rng, 4.0);
    (static_cast<int>(i) < static_cast<int>(c.rods.size()) ? t.rods : t.spheres)
        .move(static_cast<std::int32_t>(i), c.r[i], c.h[i]);
  }
}

struct Case {
  const char* name;
  Vec3 edges;
  Order order;
};

const Case kCases[] = {
    {"isotropic cubic", Vec3(36, 36, 36), Order::Isotropic},
    {"nematic cubic", Vec3(36, 36, 36), Order::Nematic},
    {"isotropic elongated", Vec3(26, 30, 75), Order::Isotropic},
    {"nematic elongated", Vec3(26, 30, 75), Order::Nematic},
};

}  // namespace

TEST(AabbTree, MatchesBruteForceForRodsAndSpheres) {
  Rng rng(18, 1);
  for (const Case& k : kCases) {
    SCOPED_TRACE(k.name);
    const Cloud c = random_cloud(rng, k.edges, k.order, 600, 300);
    const Trees t = build_trees(c);
    EXPECT_EQ(t.rods.size(), 600u);
    EXPECT_EQ(t.spheres.size(), 300u);
    // Median splits keep the tree balanced: leaves of 4–8 entries, depth log2(N / 4) + 1 at most.
    EXPECT_LE(t.rods.depth(), static_cast<int>(std::ceil(std::log2(600.0 / 4.0))) + 1);
    EXPECT_LE(t.rods.node_count(), 2 * 600u / 4);
    expect_trees_match(c, t.rods, t.spheres, rng, 150);
  }
}

TEST(AabbTree, MatchesBruteForceAfterThousandsOfMovesWithoutRebuild) {
  Rng rng(18, 2);
  for (const Case& k : kCases) {
    SCOPED_TRACE(k.name);
    Cloud c = random_cloud(rng, k.edges, k.order, 500, 250);
    Trees t = build_trees(c);
    const std::size_t nodes = t.rods.node_count();
    for (int round = 0; round < 3; ++round) {
      random_moves(c, t, rng, 2000);
      expect_trees_match(c, t.rods, t.spheres, rng, 60);
    }
    EXPECT_EQ(t.rods.node_count(), nodes);  // moves refit, they never restructure
  }
}

TEST(AabbTree, MatchesBruteForceAfterInsertions) {
  Rng rng(18, 3);
  for (const Case& k : kCases) {
    SCOPED_TRACE(k.name);
    Cloud c = random_cloud(rng, k.edges, k.order, 800, 400);
    // Build over the first 100 of each species, insert the rest interleaved with moves.
    Cloud partial = c;
    partial.rods.resize(100);
    partial.spheres.resize(100);
    Trees t = build_trees(partial);
    for (std::size_t n = 100; n < 800; ++n) {
      partial.rods.push_back(c.rods[n]);
      t.rods.insert(c.rods[n], c.r[static_cast<std::size_t>(c.rods[n])], c.h[static_cast<std::size_t>(c.rods[n])]);
      if (n < 400) {
        partial.spheres.push_back(c.spheres[n]);
        t.spheres.insert(c.spheres[n], c.r[static_cast<std::size_t>(c.spheres[n])],
                         c.h[static_cast<std::size_t>(c.spheres[n])]);
      }
      if (n % 175 == 0) expect_trees_match(partial, t.rods, t.spheres, rng, 20);
    }
    EXPECT_EQ(t.rods.size(), 800u);
    EXPECT_EQ(t.spheres.size(), 400u);
    random_moves(partial, t, rng, 1000);
    expect_trees_match(partial, t.rods, t.spheres, rng, 100);
  }
}

TEST(AabbTree, RefitAllMatchesBruteForceAfterEveryParticleMovedBehindIt) {
  // Every particle moves (often across a face) and turns with the tree not told; refit_all then
  // re-reads them all. Then the whole cloud is compressed by 3% with the box, as after a volume
  // move. The tree keeps its shape and must answer as the brute force does.
  Rng rng(18, 8);
  for (const Case& k : kCases) {
    SCOPED_TRACE(k.name);
    Cloud c = random_cloud(rng, k.edges, k.order, 500, 250);
    Trees t = build_trees(c);
    const std::size_t nodes = t.rods.node_count();
    for (std::size_t i = 0; i < c.r.size(); ++i) displace(c, i, rng, 3.0);
    t.rods.refit_all(c.r, c.h);
    t.spheres.refit_all(c.r, c.h);
    expect_trees_match(c, t.rods, t.spheres, rng, 60);
    c.box = Box(c.box.edges() * 0.97);
    for (Vec3& r : c.r) r *= 0.97;
    t.rods.refit_all(c.r, c.h);
    t.spheres.refit_all(c.r, c.h);
    expect_trees_match(c, t.rods, t.spheres, rng, 60);
    EXPECT_EQ(t.rods.node_count(), nodes);
    EXPECT_EQ(t.rods.size(), 500u);
  }
}

TEST(AabbTree, BoxNarrowerThanTwiceTheReachGivesTheMinimumImageOnce) {
  // Rod boxes reach up to 12.1 along an axis of 20: a pair can overlap under two images; the tree
  // reports the minimum one only, once.
  Rng rng(18, 7);
  for (const Order order : {Order::Isotropic, Order::Nematic}) {
    Cloud c = random_cloud(rng, Vec3(20, 20, 20), order, 300, 100);
    Trees t = build_trees(c);
    expect_trees_match(c, t.rods, t.spheres, rng, 100);
    random_moves(c, t, rng, 1000);
    expect_trees_match(c, t.rods, t.spheres, rng, 100);
  }
}

TEST(AabbTree, InsertionInSortedOrderIntoAnEmptyTreeStaysShallow) {
  // A lattice filled in order, or a line of particles, sends every insertion to the same corner of
  // the tree; the tree must stay shallow (it is rebuilt) and exact.
  Rng rng(18, 4);
  const int n = 12 * 12 * 3;
  for (const bool line : {false, true}) {
    SCOPED_TRACE(line ? "line" : "lattice");
    Cloud c{Box(Vec3(36, 36, 36)), Order::Nematic, {}, {}, {}, {}};
    AabbTree tree;
    tree.build(c.box, {}, {}, {});
    for (int i = 0; i < n; ++i) {
      c.rods.push_back(i);
      if (line)
        c.r.emplace_back(0.5 + 35.0 * i / n, 1.0, 1.0);
      else
        c.r.emplace_back(3.0 * (i % 12) + 0.5, 3.0 * ((i / 12) % 12) + 0.5, 12.0 * (i / 144) + 0.5);
      c.h.push_back(kRod.lab_half_extents(random_rotation(rng, c.order)));
      tree.insert(i, c.r.back(), c.h.back());
      ASSERT_LE(tree.depth(), 16) << "after " << i + 1 << " insertions";
    }
    EXPECT_EQ(tree.size(), c.r.size());
    AabbTree no_spheres;
    expect_trees_match(c, tree, no_spheres, rng, 200);
  }
}

TEST(AabbTree, EarlyStopVisitsNoMore) {
  Rng rng(18, 5);
  const Cloud c = random_cloud(rng, Vec3(36, 36, 36), Order::Isotropic, 600, 0);
  const Trees t = build_trees(c);
  const Vec3 r(0.1, 18, 35.9), h = kRod.lab_half_extents(Mat3::Identity());
  int all = 0;
  EXPECT_FALSE(t.rods.visit(c.box, r, h, kInf, [&](int, const Vec3&, double) { return ++all, false; }));
  ASSERT_GE(all, 5);
  for (const int stop_at : {1, 3, all}) {
    int calls = 0;
    EXPECT_TRUE(t.rods.visit(c.box, r, h, kInf, [&](int, const Vec3&, double) { return ++calls == stop_at; }));
    EXPECT_EQ(calls, stop_at);
  }
}

TEST(AabbTree, EmptyAndSingleParticleTrees) {
  const Box box(Vec3(30, 30, 30));
  const Vec3 h(0.5, 0.5, 6.0);
  int calls = 0;
  auto count = [&](int, const Vec3&, double) { return ++calls, false; };

  AabbTree fresh;
  EXPECT_FALSE(fresh.visit(box, Vec3(1, 2, 3), h, kInf, count));
  AabbTree empty;
  empty.build(box, {}, {}, {});
  EXPECT_FALSE(empty.visit(box, Vec3(1, 2, 3), h, kInf, count));
  EXPECT_EQ(calls, 0);
  EXPECT_EQ(empty.size(), 0u);
  EXPECT_EQ(empty.node_count(), 0u);
  EXPECT_EQ(empty.depth(), 0);

  // One rod at a corner, found from the opposite corner through the periodic images.
  AabbTree one;
  one.build(box, {3}, std::vector<Vec3>(4, Vec3(0.1, 0.1, 0.1)), std::vector<Vec3>(4, h));
  EXPECT_EQ(one.size(), 1u);
  EXPECT_EQ(one.depth(), 1);
  std::vector<std::pair<int, Vec3>> seen;
  one.visit(box, Vec3(29.9, 29.9, 29.9), Vec3(0.1, 0.1, 0.1), kInf, [&](int j, const Vec3& d, double) {
    seen.emplace_back(j, d);
    return false;
  });
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].first, 3);
  EXPECT_LT((seen[0].second - Vec3(0.2, 0.2, 0.2)).norm(), 1e-9);
  // Out of reach along x (|dx| = 1.2 > 0.5 + 0.1), and excluded by rc.
  EXPECT_FALSE(one.visit(box, Vec3(28.9, 0.1, 0.1), Vec3(0.1, 0.1, 0.1), kInf, count));
  EXPECT_FALSE(one.visit(box, Vec3(0.1, 0.1, 4.0), Vec3(0.1, 0.1, 0.1), 3.8, count));
  EXPECT_EQ(calls, 0);
  EXPECT_FALSE(one.visit(box, Vec3(0.1, 0.1, 4.0), Vec3(0.1, 0.1, 0.1), 4.0, count));
  EXPECT_EQ(calls, 1);
}

TEST(AabbTree, RejectsBadInput) {
  const Box box(Vec3(30, 30, 30));
  AabbTree tree;
  const std::vector<Vec3> h(2, Vec3(0.5, 0.5, 0.5));
  EXPECT_THROW(tree.build(box, {0, 1}, {Vec3(1, 1, 1), Vec3(1, 30, 1)}, h), std::invalid_argument);
  EXPECT_THROW(tree.build(box, {2}, {Vec3(1, 1, 1), Vec3(1, 1, 1)}, h), std::invalid_argument);
  tree.build(box, {0}, {Vec3(1, 1, 1), Vec3(2, 2, 2)}, h);
  EXPECT_THROW(tree.move(1, Vec3(1, 1, 1), h[0]), std::invalid_argument);
  EXPECT_THROW(tree.insert(0, Vec3(1, 1, 1), h[0]), std::invalid_argument);
}

TEST(AabbTree, PrintsCandidatesPerQueryAgainstTheCellGrid) {
  // 2000 rods 12×1×1 at η = 0.34 in a cubic box (random centres: the density of a real state,
  // not its non-overlap). Printed, not asserted: the gain over the grid.
  Rng rng(18, 6);
  const int n = 2000;
  const double edge = std::cbrt(n * 12.0 / 0.34), rc = 2 * kRod.circumradius();
  for (const Order order : {Order::Nematic, Order::Isotropic}) {
    const Cloud c = random_cloud(rng, Vec3::Constant(edge), order, n, 0);
    const Trees t = build_trees(c);
    CellList grid;
    std::vector<double> x, y, z;
    for (const Vec3& r : c.r) x.push_back(r.x()), y.push_back(r.y()), z.push_back(r.z());
    grid.build(c.box, x, y, z, std::vector<std::int32_t>(n, 0), {rc});
    double tested = 0, candidates = 0, within_rc = 0, s2 = 0;
    for (int i = 0; i < n; ++i) {
      const std::size_t ii = static_cast<std::size_t>(i);
      const double cz = random_rotation(rng, order)(2, 2);  // a sample of the orientations' ⟨P2⟩
      s2 += 1.5 * cz * cz - 0.5;
      tested += static_cast<double>(t.rods.entries_tested(c.box, c.r[ii], c.h[ii]) - 1);
      t.rods.visit(c.box, c.r[ii], c.h[ii], rc, [&](int j, const Vec3&, double) { return candidates += j != i, false; });
      grid.visit(0, c.r[ii], rc, [&](int j, const Vec3&, double) { return within_rc += j != i, false; });
    }
    // The grid scans 3 cells per axis around the query's, or every cell when an axis has ≤ 3.
    const Int3 cells = grid.grid(0).cells_per_axis();
    double scanned = n - 1;
    for (int k = 0; k < 3; ++k) scanned *= cells[k] <= 3 ? 1.0 : 3.0 / cells[k];
    std::printf("[ aabb ] %s rods 12x1x1 (S = %.2f), N = %d, eta = 0.34, box %.1f, grid %dx%dx%d cells of %.2f:\n",
                order == Order::Nematic ? "nematic" : "isotropic", s2 / n, n, edge, cells.x(), cells.y(), cells.z(), rc);
    std::printf("[ aabb ]   tree: %.1f leaf entries tested, %.2f candidates (box overlap and |d| <= %.2f) per query\n",
                tested / n, candidates / n, rc);
    std::printf("[ aabb ]   grid: %.1f particles scanned, %.1f within |d| <= %.2f per query\n", scanned, within_rc / n,
                rc);
    std::printf("[ aabb ]   tree depth %d, %zu nodes\n", t.rods.depth(), t.rods.node_count());
  }
}
