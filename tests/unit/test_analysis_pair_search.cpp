// The shared neighbour-pair finder (pair_search.hpp) against the O(N²) pair loop it replaces:
// random boxes with unequal edges, cut-offs from a few cells up to and beyond half the smallest
// edge, particles exactly on the box faces and on cell boundaries, unwrapped coordinates several
// boxes away, coincident particles, and a lattice whose neighbours sit exactly at the cut-off.
// The pair sets must be equal and the minimum-image separations equal bit for bit; the reference
// checks separately that they are minimum images. DBSCAN, which finds its Eps-neighbourhoods through
// the same finder (open boundaries, points at negative coordinates, neighbours exactly Eps apart),
// is checked against a brute-force DBSCAN.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>

#include "anisodyn/analysis/dbscan.hpp"
#include "anisodyn/analysis/pair_search.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

struct Found {
  std::size_t i, j;
  double dx, dy, dz;
  bool operator<(const Found& o) const { return std::tie(i, j) < std::tie(o.i, o.j); }
};

/// The O(N²) loop of anisodyn-structure before the cell lists: coordinates wrapped into the box,
/// one shift per axis to the minimum image, pairs with |d|² < cutoff². `b` null: like pairs i < j.
std::vector<Found> brute_force(const std::vector<Vec3>& a, const std::vector<Vec3>* b, const Vec3& L, double cutoff) {
  auto wrap = [&](const Vec3& r) {
    Vec3 w;
    for (int k = 0; k < 3; ++k) w[k] = r[k] - L[k] * std::floor(r[k] / L[k]);
    return w;
  };
  auto image = [](double d, double l) { return d - l * static_cast<double>(d > l / 2) + l * static_cast<double>(d < -l / 2); };
  const std::vector<Vec3>& other = b ? *b : a;
  std::vector<Found> out;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = b ? 0 : i + 1; j < other.size(); ++j) {
      const Vec3 wi = wrap(a[i]), wj = wrap(other[j]);
      const double dx = image(wj.x() - wi.x(), L.x()), dy = image(wj.y() - wi.y(), L.y()), dz = image(wj.z() - wi.z(), L.z());
      if (dx * dx + dy * dy + dz * dz < cutoff * cutoff) out.push_back({i, j, dx, dy, dz});
    }
  return out;
}

std::vector<Found> with_finder(const std::vector<Vec3>& a, const std::vector<Vec3>* b, const Vec3& L, double cutoff) {
  const PairGrid grid(L, cutoff, a.size() + (b ? b->size() : 0));
  std::vector<Found> out;
  auto keep = [&](std::size_t i, std::size_t j, const Vec3& d, double r2) {
    EXPECT_DOUBLE_EQ(r2, d.squaredNorm());
    out.push_back({i, j, d.x(), d.y(), d.z()});
  };
  if (b) grid.for_each_pair(grid.sort(a), grid.sort(*b), keep);
  else grid.for_each_pair(grid.sort(a), keep);
  std::sort(out.begin(), out.end());
  return out;
}

/// Compares the finder with the brute force; returns the number of pairs compared.
std::size_t expect_same_pairs(const std::vector<Vec3>& a, const std::vector<Vec3>* b, const Vec3& L, double cutoff,
                              const std::string& what) {
  const std::vector<Found> ref = brute_force(a, b, L, cutoff), got = with_finder(a, b, L, cutoff);
  EXPECT_EQ(got.size(), ref.size()) << what;
  if (got.size() != ref.size()) return 0;
  const std::vector<Vec3>& other = b ? *b : a;
  for (std::size_t k = 0; k < ref.size(); ++k) {
    EXPECT_EQ(std::tie(got[k].i, got[k].j), std::tie(ref[k].i, ref[k].j)) << what << " pair " << k;
    if (std::tie(got[k].i, got[k].j) != std::tie(ref[k].i, ref[k].j)) return 0;
    EXPECT_EQ(got[k].dx, ref[k].dx) << what;
    EXPECT_EQ(got[k].dy, ref[k].dy) << what;
    EXPECT_EQ(got[k].dz, ref[k].dz) << what;
    // the reference itself: a minimum image of r_j − r_i
    const Vec3 d(ref[k].dx, ref[k].dy, ref[k].dz), raw = other[ref[k].j] - a[ref[k].i];
    for (int c = 0; c < 3; ++c) {
      EXPECT_LE(std::abs(d[c]), L[c] / 2 * (1 + 1e-12)) << what;
      const double turns = (raw[c] - d[c]) / L[c];
      EXPECT_NEAR(turns, std::round(turns), 1e-9) << what;
    }
  }
  return ref.size();
}

/// Positions anywhere in [−2L, 3L): a third uniform, a third on the box faces (0, ±L, 2L and
/// L⁻ = −1e−300, which wraps to L itself) and on the cell boundaries k·L/m of grids of m ≤ 12
/// cells, a third copies of earlier particles (coincident pairs, r = 0).
std::vector<Vec3> awkward_positions(std::size_t n, const Vec3& L, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec3> r;
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 p;
    const double kind = u(rng);
    for (int c = 0; c < 3; ++c) {
      if (kind < 0.34 || r.empty()) {
        p[c] = (5 * u(rng) - 2) * L[c];
      } else if (kind < 0.67) {
        const double faces[] = {0.0, L[c], -L[c], 2 * L[c], -1e-300};
        const int m = 1 + static_cast<int>(12 * u(rng));
        p[c] = u(rng) < 0.5 ? faces[static_cast<int>(5 * u(rng))] : L[c] * std::floor(m * u(rng)) / m;
      } else {
        p = r[static_cast<std::size_t>(u(rng) * static_cast<double>(r.size()))];
        break;
      }
    }
    r.push_back(p);
  }
  return r;
}

}  // namespace

TEST(PairSearch, SamePairsAndSeparationsAsTheBruteForceInRandomBoxes) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(0, 1);
  std::size_t compared = 0, cases = 0, cell_cases = 0;
  for (int box_case = 0; box_case < 40; ++box_case) {
    const Vec3 L(2 + 10 * u(rng), 2 + 10 * u(rng), 2 + 10 * u(rng));
    const std::size_t n = 2 + static_cast<std::size_t>(400 * u(rng));
    const std::vector<Vec3> r = awkward_positions(n, L, rng);
    const double half = L.minCoeff() / 2;
    // from a few cells per axis to half the smallest edge (the g(r) default), just below it, beyond
    // it (the g_∥/g_⊥ reach), and beyond half the largest edge (every pair is within reach)
    for (double c : {0.1 * half, 0.3 * half, 0.7 * half, half * (1 - 1e-12), half, 1.3 * half, 0.6 * L.maxCoeff(), L.norm()}) {
      const std::string what = "box " + std::to_string(box_case) + " cutoff " + std::to_string(c);
      compared += expect_same_pairs(r, nullptr, L, c, what);
      const std::size_t split = n / 3;
      const std::vector<Vec3> a(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(split)), b(r.begin() + static_cast<std::ptrdiff_t>(split), r.end());
      compared += expect_same_pairs(a, &b, L, c, what + " (unlike)");
      ++cases;
      if (PairGrid(L, c, n).cells().prod() > 1) ++cell_cases;
    }
  }
  std::printf("%zu cases (%zu with more than one cell), %zu pairs compared\n", cases, cell_cases, compared);
  EXPECT_GE(compared, 100000u);   // the comparison is not vacuous
  EXPECT_GE(cell_cases, cases / 4);  // and a good share of them go through real cell lists
}

TEST(PairSearch, ManyCellsWithPrunedStencilInAnElongatedBox) {
  // 3000 particles in a 10 × 40 × 7 box, cut-off 1.1: hundreds of cells, the stencil's corners pruned
  std::mt19937_64 rng(9);
  const Vec3 L(10, 40, 7);
  const std::vector<Vec3> r = awkward_positions(3000, L, rng);
  const PairGrid grid(L, 1.1, r.size());
  EXPECT_GT(grid.cells().prod(), 500);
  EXPECT_GT(expect_same_pairs(r, nullptr, L, 1.1, "elongated box"), 3000u);
}

TEST(PairSearch, NeighboursExactlyAtTheCutOffAreExcludedAsByTheBruteForce) {
  // simple cubic lattice, spacing 0.75 (exact in binary): first neighbours at exactly the cut-off 0.75
  std::vector<Vec3> r;
  const int n = 8;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) r.emplace_back(0.75 * i, 0.75 * j, 0.75 * k);
  const Vec3 L = Vec3::Constant(0.75 * n);
  EXPECT_EQ(expect_same_pairs(r, nullptr, L, 0.75, "lattice at the cut-off"), 0u);
  EXPECT_EQ(expect_same_pairs(r, nullptr, L, std::nextafter(0.75, 1.0), "lattice beyond the cut-off"), 3u * 512u);
  // at L/2 = 3 = 4 spacings: the lattice vectors of squared length 1 … 15 (in spacings), Σ r₃(n) = 250
  EXPECT_EQ(expect_same_pairs(r, nullptr, L, 3.0, "lattice at L/2"), 250u * 512u / 2);
}

TEST(PairSearch, ClosePairsAreOrderedAndEmptyInputsGiveNoPairs) {
  std::mt19937_64 rng(4);
  const Vec3 L(6, 5, 4);
  const std::vector<Vec3> r = awkward_positions(200, L, rng);
  const std::vector<ClosePair> p = close_pairs(r, Box(L), 1.5);
  const std::vector<Found> ref = brute_force(r, nullptr, L, 1.5);
  ASSERT_EQ(p.size(), ref.size());
  ASSERT_GT(p.size(), 100u);
  for (std::size_t k = 0; k < p.size(); ++k) {
    EXPECT_EQ(std::tie(p[k].i, p[k].j), std::tie(ref[k].i, ref[k].j));
    EXPECT_EQ(p[k].d, Vec3(ref[k].dx, ref[k].dy, ref[k].dz));
  }
  EXPECT_TRUE(close_pairs({}, Box(L), 1.0).empty());
  EXPECT_TRUE(close_pairs({Vec3(1, 1, 1)}, Box(L), 1.0).empty());
  EXPECT_TRUE(close_pairs(r, Box(L), 0.0).empty());
}

TEST(PairSearch, PlanarCandidatePairsAreThePairsWithinReach) {
  // open boundaries: points spread over negative and positive coordinates, a reach far below and
  // one beyond the spread; the distances may round differently from the caller's in the last bit
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-2, 3);
  std::vector<Point2> p(300);
  for (auto& q : p) q = {u(rng), 0.5 * u(rng)};
  for (double reach : {0.07, 0.4, 9.0}) {
    const auto pairs = planar_candidate_pairs(p, reach);
    EXPECT_EQ(planar_candidate_pairs(p, reach), pairs);  // the same order every time
    auto sorted = pairs;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end()) << "each pair once";
    std::vector<std::pair<std::size_t, std::size_t>> ref;
    for (std::size_t i = 0; i < p.size(); ++i)
      for (std::size_t j = i + 1; j < p.size(); ++j)
        if (std::hypot(p[j].x - p[i].x, p[j].y - p[i].y) < reach) ref.emplace_back(i, j);
    EXPECT_EQ(sorted, ref) << "reach " << reach;
  }
  EXPECT_TRUE(planar_candidate_pairs({}, 1.0).empty());
  EXPECT_TRUE(planar_candidate_pairs({{0, 0}}, 1.0).empty());
}

namespace {

/// DBSCAN written out with O(N²) region queries (Ester et al. 1996, the library's documented rule).
std::vector<int> brute_force_dbscan(const std::vector<Point2>& p, double eps, std::size_t min_pts) {
  constexpr int unvisited = -2;
  std::vector<int> label(p.size(), unvisited);
  auto region = [&](std::size_t i) {
    std::vector<std::size_t> out;
    for (std::size_t j = 0; j < p.size(); ++j) {
      const double dx = p[j].x - p[i].x, dy = p[j].y - p[i].y;
      if (dx * dx + dy * dy <= eps * eps) out.push_back(j);
    }
    return out;
  };
  int clusters = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (label[i] != unvisited) continue;
    std::vector<std::size_t> seeds = region(i);
    if (seeds.size() < min_pts) { label[i] = kDbscanNoise; continue; }
    const int c = clusters++;
    label[i] = c;
    while (!seeds.empty()) {
      const std::size_t q = seeds.back();
      seeds.pop_back();
      if (label[q] == kDbscanNoise) label[q] = c;
      if (label[q] != unvisited) continue;
      label[q] = c;
      const std::vector<std::size_t> more = region(q);
      if (more.size() >= min_pts) seeds.insert(seeds.end(), more.begin(), more.end());
    }
  }
  return label;
}

}  // namespace

TEST(PairSearch, DbscanNeighbourhoodsMatchABruteForceDbscan) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> g(0, 1);
  std::size_t clustered = 0, noise = 0;
  for (int trial = 0; trial < 12; ++trial) {
    std::vector<Point2> p;
    // blobs, a uniform background (some of it at negative coordinates) and points on an Eps lattice
    for (int b = 0; b < 4; ++b) {
      const double cx = 3 * u(rng) - 1, cy = 2 * u(rng), s = 0.02 + 0.1 * u(rng);
      for (int k = 0; k < 60; ++k) p.push_back({cx + s * g(rng), cy + s * g(rng)});
    }
    for (int k = 0; k < 150; ++k) p.push_back({3 * u(rng) - 1, 2 * u(rng)});
    const double eps = 0.05 + 0.1 * u(rng);
    for (int k = 0; k < 20; ++k) p.push_back({0.5 + eps * (k % 5), 2.5 + eps * (k / 5)});
    const std::size_t min_pts = 3 + static_cast<std::size_t>(10 * u(rng));
    const DbscanLabels got = dbscan(p, eps, min_pts);
    const std::vector<int> ref = brute_force_dbscan(p, eps, min_pts);
    EXPECT_EQ(got.label, ref) << "trial " << trial;
    for (int l : ref) (l >= 0 ? clustered : noise)++;
  }
  std::printf("DBSCAN: %zu clustered and %zu noise points compared\n", clustered, noise);
  EXPECT_GT(clustered, 1000u);
  EXPECT_GT(noise, 100u);
}
