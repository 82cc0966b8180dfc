// KeyedRandom (core/keyed_random.hpp), PairNoise (core/pair_noise.hpp) and NodeNoise
// (core/node_noise.hpp): draws addressed by key and counter, the pair symmetry, the same values for
// any thread count and batch, PairNoise's and NodeNoise's generator against Random123's
// Philox4x32-10, and the distribution of the normals and uniforms against their closed-form
// moments (tolerances 4 standard errors of each estimator) and a Kolmogorov–Smirnov bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "anisodyn/core/keyed_random.hpp"
#include "anisodyn/core/node_noise.hpp"
#include "anisodyn/core/pair_noise.hpp"

using namespace anisodyn;

TEST(KeyedRandom, ADrawDependsOnlyOnItsKeyAndCounter) {
  const KeyedRandom r(2026, 1), same(2026, 1), other_purpose(2026, 2), other_seed(2027, 1);
  std::vector<double> batch(11);
  r.normals(5, 17, 3, batch.data(), batch.size());
  for (std::uint64_t k = 0; k < batch.size(); ++k) {
    EXPECT_EQ(batch[k], r.normal(5, 17, 3, k)) << k;
    EXPECT_EQ(batch[k], same.normal(5, 17, 3, k)) << k;
    EXPECT_NE(batch[k], other_purpose.normal(5, 17, 3, k)) << k;
    EXPECT_NE(batch[k], other_seed.normal(5, 17, 3, k)) << k;
  }
  // Each counter word matters.
  EXPECT_NE(r.normal(5, 17, 3, 0), r.normal(6, 17, 3, 0));
  EXPECT_NE(r.normal(5, 17, 3, 0), r.normal(5, 18, 3, 0));
  EXPECT_NE(r.normal(5, 17, 3, 0), r.normal(5, 17, 4, 0));
  EXPECT_NE(r.normal(5, 17, 3, 0), r.normal(5, 17, 3, 4));
  EXPECT_EQ(r.uniform(9, 1, 2, 6), r.uniform(9, 1, 2, 6));
}

TEST(PairNoise, PairDrawsAreSymmetric) {
  const PairNoise r(7, 3);
  for (std::uint32_t i = 0; i < 50; ++i)
    for (std::uint32_t j = 0; j < 50; ++j) ASSERT_EQ(r(11, i, j), r(11, j, i));
  EXPECT_NE(r(11, 1, 2), r(11, 1, 3));
  EXPECT_NE(r(11, 1, 2), r(12, 1, 2));
  EXPECT_NE(r(11, 1, 2), r(11ULL + (1ULL << 32), 1, 2));  // the high word of the step counts
  EXPECT_NE(r(11, 1, 2), PairNoise(8, 3)(11, 1, 2));
}

TEST(PairNoise, TheGeneratorIsRandom123sPhilox4x32) {
  // The uniform behind θ, rebuilt from r123::Philox4x32 (10 rounds) on counter (step low, step
  // high, min id, max id) and PairNoise's key: the 53 bits of words 0 and 1, then the quantile.
  const PairNoise r(2026, 9);
  const r123::Philox4x32::key_type key = {{r.key(0), r.key(1)}};
  r123::Philox4x32 philox;
  for (std::uint64_t step : {0ULL, 1ULL, 123456789ULL, (7ULL << 32) + 5ULL})
    for (std::uint32_t i : {0u, 3u, 99999u, 4000000000u}) {
      const std::uint32_t j = i ^ 0x5a5au;
      const r123::Philox4x32::ctr_type ctr = {{static_cast<std::uint32_t>(step), static_cast<std::uint32_t>(step >> 32), std::min(i, j), std::max(i, j)}};
      const auto w = philox(ctr, key);
      const std::uint64_t bits = (static_cast<std::uint64_t>(w[0]) << 21) | (w[1] >> 11);
      EXPECT_EQ(r(step, i, j), KeyedRandom::normal_quantile((static_cast<double>(bits) + 0.5) * 0x1.0p-53)) << step << " " << i;
    }
}

TEST(PairNoise, ABatchGivesTheBitsOfSinglePairs) {
  const PairNoise r(5, 1);
  for (std::size_t n : {1u, 7u, 16u, 17u, 100u}) {
    std::vector<std::uint32_t> a(n), b(n);
    for (std::size_t m = 0; m < n; ++m) a[m] = static_cast<std::uint32_t>(31 * m + 7), b[m] = static_cast<std::uint32_t>(1000 - 3 * m);
    std::vector<double> out(n);
    r.normals(42, a.data(), b.data(), n, out.data());
    for (std::size_t m = 0; m < n; ++m) ASSERT_EQ(out[m], r(42, a[m], b[m])) << n << " " << m;
  }
}

TEST(PairNoise, ValuesDoNotDependOnTheThreadCount) {
  // Pair noise of a pair list filled in parallel, in whatever order the threads take the pairs.
  const PairNoise r(99, 5);
  const std::int64_t pairs = 20000;
  auto fill = [&](int threads) {
    std::vector<double> theta(static_cast<std::size_t>(pairs));
#pragma omp parallel for num_threads(threads) schedule(dynamic, 7)
    for (std::int64_t p = 0; p < pairs; ++p)
      theta[static_cast<std::size_t>(p)] = r(42, static_cast<std::uint32_t>(p % 997), static_cast<std::uint32_t>(p / 997 + 1000));
    return theta;
  };
  const auto one = fill(1);
  EXPECT_EQ(one, fill(2));
  EXPECT_EQ(one, fill(3));
}

namespace {

struct Moments {
  double mean = 0, var = 0, m4 = 0;
};

Moments moments(const std::vector<double>& x) {
  Moments m;
  for (double v : x) m.mean += v;
  m.mean /= static_cast<double>(x.size());
  for (double v : x) {
    const double d = v - m.mean;
    m.var += d * d;
    m.m4 += d * d * d * d;
  }
  m.var /= static_cast<double>(x.size() - 1);
  m.m4 /= static_cast<double>(x.size());
  return m;
}

/// sup |F_n − F| for a sample against the cumulative distribution cdf.
template <class Cdf>
double ks_statistic(std::vector<double> x, Cdf cdf) {
  std::sort(x.begin(), x.end());
  const double n = static_cast<double>(x.size());
  double d = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double f = cdf(x[i]);
    d = std::max({d, f - static_cast<double>(i) / n, static_cast<double>(i + 1) / n - f});
  }
  return d;
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s / static_cast<double>(a.size());
}

}  // namespace

TEST(KeyedRandom, NormalsHaveTheMomentsAndDistributionOfAStandardNormal) {
  const KeyedRandom r(123456789, 7);
  const std::size_t steps = 100000;
  // Four draws per counter (one Philox block: both Box–Muller branches of two pairs).
  std::vector<std::vector<double>> z(4, std::vector<double>(steps));
  for (std::size_t s = 0; s < steps; ++s) {
    double b[4];
    r.normals(s, 12, 34, b, 4);
    for (int k = 0; k < 4; ++k) z[static_cast<std::size_t>(k)][s] = b[k];
  }
  std::vector<double> all;
  for (const auto& v : z) all.insert(all.end(), v.begin(), v.end());
  const double n = static_cast<double>(all.size());
  const Moments m = moments(all);
  EXPECT_LT(std::abs(m.mean), 4.0 / std::sqrt(n));               // SE of the mean: 1/√n
  EXPECT_LT(std::abs(m.var - 1.0), 4.0 * std::sqrt(2.0 / n));    // Var(z²) = 2
  EXPECT_LT(std::abs(m.m4 - 3.0), 4.0 * std::sqrt(96.0 / n));    // Var(z⁴) = 105 − 9
  // Kolmogorov–Smirnov: P(√n D > 1.95) ≈ 0.001.
  EXPECT_LT(std::sqrt(n) * ks_statistic(all, [](double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }), 1.95);
  // The cosine and sine branch of one pair, the two pairs of a block and neighbouring steps are
  // uncorrelated (SE of a correlation of independent unit normals: 1/√steps).
  const double se = 1.0 / std::sqrt(static_cast<double>(steps));
  EXPECT_LT(std::abs(correlation(z[0], z[1])), 4.0 * se);
  EXPECT_LT(std::abs(correlation(z[0], z[2])), 4.0 * se);
  EXPECT_LT(std::abs(correlation(z[1], z[3])), 4.0 * se);
  std::vector<double> next(z[0].begin() + 1, z[0].end()), prev(z[0].begin(), z[0].end() - 1);
  EXPECT_LT(std::abs(correlation(prev, next)), 4.0 * se);
  // Squares too: Box–Muller pairs share a radius, which a linear correlation would not see.
  std::vector<double> a2(steps), b2(steps);
  for (std::size_t s = 0; s < steps; ++s) {
    a2[s] = z[0][s] * z[0][s] - 1.0;
    b2[s] = z[1][s] * z[1][s] - 1.0;
  }
  EXPECT_LT(std::abs(correlation(a2, b2)), 4.0 * std::sqrt(2.0 * 2.0) * se);  // Var(z² − 1) = 2
}

TEST(KeyedRandom, UniformsAreUniform) {
  const KeyedRandom r(5, 9);
  std::vector<double> u;
  for (std::uint64_t s = 0; s < 200000; ++s) u.push_back(r.uniform(s, 1, 2, s % 8));
  const double n = static_cast<double>(u.size());
  const Moments m = moments(u);
  EXPECT_LT(std::abs(m.mean - 0.5), 4.0 * std::sqrt(1.0 / 12.0 / n));
  EXPECT_LT(std::abs(m.var - 1.0 / 12.0), 4.0 * std::sqrt((1.0 / 80.0 - 1.0 / 144.0) / n));
  EXPECT_LT(std::sqrt(n) * ks_statistic(u, [](double x) { return x; }), 1.95);
  EXPECT_GE(*std::min_element(u.begin(), u.end()), 0.0);
  EXPECT_LT(*std::max_element(u.begin(), u.end()), 1.0);
}

namespace {
/// Relative error of x = Φ⁻¹(p), from the error of the smaller tail probability it gives (Φ(x)
/// against p below ½, erfc(x/√2)/2 against 1 − p, exact in floating point, above) divided by the
/// density: δx = δp/φ(x); relative to |x| away from the centre, absolute near it.
double tail_error(double p) {
  const double x = KeyedRandom::normal_quantile(p);
  const double dp = p <= 0.5 ? 0.5 * std::erfc(-x / std::sqrt(2.0)) - p : 0.5 * std::erfc(x / std::sqrt(2.0)) - (1.0 - p);
  const double density = std::exp(-0.5 * x * x) / std::sqrt(2.0 * M_PI);
  return std::abs(dp) / density / std::max(std::abs(x), 1e-3);
}
}  // namespace

TEST(KeyedRandom, NormalQuantileInvertsTheNormalCdf) {
  // Φ(Φ⁻¹(p)) = p, with Φ from std::erfc (independent of the rational approximation), across the
  // central region, both tails and the switch points 0.02425 and 0.97575; erfc's own error (a few
  // ulp) is far below the bound except in the outer tail, where φ is tiny.
  double worst = 0.0;
  for (double p : {1e-15, 1e-9, 1e-5, 1e-3, 0.01, 0.02425, 0.0243, 0.1, 0.3, 0.5, 0.7, 0.9, 0.97575, 0.9758, 0.999, 1 - 1e-9}) {
    worst = std::max(worst, tail_error(p));
  }
  for (int k = 1; k < 10000; ++k) worst = std::max(worst, tail_error(k / 10000.0));
  std::printf("largest relative error of the quantile (Acklam: 1.15e-9): %.2e\n", worst);
  EXPECT_LT(worst, 2e-9);
  EXPECT_EQ(KeyedRandom::normal_quantile(0.5), 0.0);
  EXPECT_NEAR(KeyedRandom::normal_quantile(0.975), 1.959963984540054, 1e-8);  // the two-sided 95% point
}

TEST(PairNoise, PairNormalsHaveTheMomentsAndDistributionOfAStandardNormal) {
  const PairNoise r(2024, 11);
  std::vector<double> x, next;
  for (std::uint32_t k = 0; k < 400000; ++k) {
    x.push_back(r(3, k % 1000, 1000 + k / 1000));
    next.push_back(r(4, k % 1000, 1000 + k / 1000));
  }
  const double n = static_cast<double>(x.size());
  const Moments m = moments(x);
  EXPECT_LT(std::abs(m.mean), 4.0 / std::sqrt(n));
  EXPECT_LT(std::abs(m.var - 1.0), 4.0 * std::sqrt(2.0 / n));
  EXPECT_LT(std::abs(m.m4 - 3.0), 4.0 * std::sqrt(96.0 / n));
  EXPECT_LT(std::sqrt(n) * ks_statistic(x, [](double v) { return 0.5 * std::erfc(-v / std::sqrt(2.0)); }), 1.95);
  EXPECT_LT(std::abs(correlation(x, next)), 4.0 / std::sqrt(n));  // a new draw each step
}

TEST(NodeNoise, TheGeneratorIsRandom123sPhilox4x32) {
  // Draw k of a node, rebuilt from r123::Philox4x32 (10 rounds) on counter (step low, step high,
  // node, k / 4) and the key NodeNoise draws from (seed, purpose): word k mod 4, then the quantile.
  const NodeNoise r(2026, 9);
  const std::uint64_t k64 = KeyedRandom(2026, 9).block(0, 0, 0, 0)[0];
  const r123::Philox4x32::key_type key = {{static_cast<std::uint32_t>(k64), static_cast<std::uint32_t>(k64 >> 32)}};
  r123::Philox4x32 philox;
  for (std::uint64_t step : {0ULL, 1ULL, 123456789ULL, (7ULL << 32) + 5ULL})
    for (std::uint32_t node : {0u, 3u, 99999u, 4000000000u})
      for (int k : {0, 1, 3, 4, 14}) {
        const r123::Philox4x32::ctr_type ctr = {{static_cast<std::uint32_t>(step), static_cast<std::uint32_t>(step >> 32), node, static_cast<std::uint32_t>(k / 4)}};
        const auto w = philox(ctr, key);
        // Its own vectorised logarithm in the tails: the same value to a few ulp of the quantile.
        const double expected = KeyedRandom::normal_quantile((static_cast<double>(w[k % 4]) + 0.5) * 0x1.0p-32);
        EXPECT_NEAR(r(step, node, k), expected, 1e-14 * std::max(1.0, std::abs(expected))) << step << " " << node << " " << k;
      }
}

TEST(NodeNoise, TailDrawsMatchTheLibraryQuantile) {
  // The words that land in the tails (p < 0.02425 or p > 0.97575), down to the extremes 0 and
  // 2³² − 1: the vectorised logarithm against std::log's quantile.
  const NodeNoise r(1, 2);
  std::vector<double> draws(16 * 4000);
  r.normals(9, 0, 4000, 16, draws.data(), 4000);
  int tails = 0;
  for (double x : draws) {
    const double p = 0.5 * std::erfc(-x / std::sqrt(2.0));
    if (p > KeyedRandom::kQuantileCentral && p < 1.0 - KeyedRandom::kQuantileCentral) continue;
    ++tails;
    EXPECT_NEAR(x, KeyedRandom::normal_quantile(p), 1e-8 * std::abs(x));  // erfc round trip: 1e-9
  }
  EXPECT_GT(tails, 2000);  // 4.85% of 64000
  for (double w : {0.0, 1.0, 12345.0, 4294967295.0}) {
    const double p = (w + 0.5) * 0x1.0p-32;
    const double x = KeyedRandom::normal_quantile(p);
    EXPECT_TRUE(std::isfinite(x));
    EXPECT_LT(std::abs(x), 6.34);
  }
}

TEST(NodeNoise, ABatchGivesTheBitsOfSingleNodes) {
  const NodeNoise r(5, 1);
  for (std::size_t count : {1u, 7u, 16u, 17u, 100u}) {
    const std::size_t stride = count + 3;
    std::vector<double> out(15 * stride, -99.0);
    r.normals(42, 1000, count, 15, out.data(), stride);
    for (std::size_t m = 0; m < count; ++m)
      for (int k = 0; k < 15; ++k) ASSERT_EQ(out[static_cast<std::size_t>(k) * stride + m], r(42, static_cast<std::uint32_t>(1000 + m), k)) << count << " " << m << " " << k;
    for (int k = 0; k < 15; ++k) EXPECT_EQ(out[static_cast<std::size_t>(k) * stride + count], -99.0);  // nothing past count
  }
}

TEST(NodeNoise, NodeNormalsHaveTheMomentsAndDistributionOfAStandardNormal) {
  // Fifteen draws per node, as the LB fluid takes them: together, and draw by draw uncorrelated
  // with the next draw of the node and with the same draw of the next node and the next step.
  const NodeNoise r(2024, 11);
  const std::size_t nodes = 30000;
  std::vector<double> batch(15 * nodes), later(15 * nodes);
  r.normals(3, 0, nodes, 15, batch.data(), nodes);
  r.normals(4, 0, nodes, 15, later.data(), nodes);
  const double n = static_cast<double>(batch.size());
  const Moments m = moments(batch);
  EXPECT_LT(std::abs(m.mean), 4.0 / std::sqrt(n));
  EXPECT_LT(std::abs(m.var - 1.0), 4.0 * std::sqrt(2.0 / n));
  EXPECT_LT(std::abs(m.m4 - 3.0), 4.0 * std::sqrt(96.0 / n));
  EXPECT_LT(std::sqrt(n) * ks_statistic(batch, [](double v) { return 0.5 * std::erfc(-v / std::sqrt(2.0)); }), 1.95);
  EXPECT_LT(std::abs(correlation(batch, later)), 4.0 / std::sqrt(n));
  const double se = 1.0 / std::sqrt(static_cast<double>(nodes));
  for (int k = 0; k + 1 < 15; ++k) {
    const std::vector<double> a(batch.begin() + k * static_cast<long>(nodes), batch.begin() + (k + 1) * static_cast<long>(nodes));
    const std::vector<double> b(batch.begin() + (k + 1) * static_cast<long>(nodes), batch.begin() + (k + 2) * static_cast<long>(nodes));
    EXPECT_LT(std::abs(correlation(a, b)), 4.0 * se) << k;
    std::vector<double> next_node(a.begin() + 1, a.end()), this_node(a.begin(), a.end() - 1);
    EXPECT_LT(std::abs(correlation(this_node, next_node)), 4.0 * se) << k;
  }
}
