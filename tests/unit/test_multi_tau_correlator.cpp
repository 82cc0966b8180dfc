// The multiple-tau correlator against its definition computed by brute force: level k is the
// series averaged over consecutive, non-overlapping runs of m^k samples, and C at lag j m^k is the
// mean of y_k(t) y_k(t + j) over every origin t with both samples present. Plus the block split, an
// exponential correlation's integral, and a checkpoint that resumes bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "anisodyn/core/multi_tau_correlator.hpp"

using anisodyn::MultiTauCorrelator;

namespace {

/// The series averaged over non-overlapping runs of `width` samples (an incomplete last run dropped).
std::vector<double> coarse(const std::vector<double>& x, std::size_t width) {
  std::vector<double> out;
  for (std::size_t s = 0; s + width <= x.size(); s += width) {
    double sum = 0.0;
    for (std::size_t i = s; i < s + width; ++i) sum += x[i];
    out.push_back(sum / static_cast<double>(width));
  }
  return out;
}

struct Brute {
  double mean = 0.0;
  std::int64_t count = 0;
};

Brute brute_force(const std::vector<double>& y, std::size_t lag) {
  Brute b;
  double sum = 0.0;
  for (std::size_t t = 0; t + lag < y.size(); ++t, ++b.count) sum += y[t] * y[t + lag];
  b.mean = b.count > 0 ? sum / static_cast<double>(b.count) : 0.0;
  return b;
}

std::vector<double> gaussian_ar1(std::size_t n, double phi, unsigned seed) {
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> normal;
  std::vector<double> x(n);
  double v = 0.0;
  for (std::size_t i = 0; i < n; ++i) x[i] = v = phi * v + std::sqrt(1.0 - phi * phi) * normal(gen);
  return x;
}

}  // namespace

TEST(MultiTauCorrelator, EveryLagEqualsTheBruteForceDefinition) {
  const int p = 8, m = 2, levels = 5;
  const std::vector<double> a = gaussian_ar1(1000, 0.9, 1), b = gaussian_ar1(1000, 0.5, 2);
  MultiTauCorrelator c(2, p, m, levels, 1);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double v[2] = {a[i], b[i]};
    c.add(v, 0);
  }
  const auto lags = c.lags();
  const auto corr = c.correlation(0);
  const auto counts = c.counts(0);
  ASSERT_EQ(lags.size(), static_cast<std::size_t>(p + (levels - 1) * (p - p / m)));
  std::size_t row = 0;
  std::size_t width = 1;
  for (int k = 0; k < levels; ++k, width *= m) {
    const auto ya = coarse(a, width), yb = coarse(b, width);
    for (int j = k == 0 ? 0 : p / m; j < p; ++j, ++row) {
      EXPECT_EQ(lags[row], static_cast<std::int64_t>(width) * j);
      const Brute ra = brute_force(ya, static_cast<std::size_t>(j)), rb = brute_force(yb, static_cast<std::size_t>(j));
      EXPECT_EQ(counts[row], ra.count) << "level " << k << " j " << j;
      EXPECT_NEAR(corr[2 * row], ra.mean, 1e-13) << "level " << k << " j " << j;
      EXPECT_NEAR(corr[2 * row + 1], rb.mean, 1e-13) << "level " << k << " j " << j;
    }
  }
}

TEST(MultiTauCorrelator, BlocksSplitTheSumsByTheLaterSample) {
  const std::vector<double> x = gaussian_ar1(600, 0.8, 3);
  MultiTauCorrelator whole(1, 4, 2, 4, 1), split(1, 4, 2, 4, 3);
  for (std::size_t i = 0; i < x.size(); ++i) {
    whole.add(&x[i], 0);
    split.add(&x[i], static_cast<int>(i / 200));
  }
  const auto total = whole.correlation(0);
  const auto total_counts = whole.counts(0);
  for (std::size_t r = 0; r < total.size(); ++r) {
    double sum = 0.0;
    std::int64_t n = 0;
    for (int blk = 0; blk < 3; ++blk) {
      sum += split.correlation(blk)[r] * static_cast<double>(split.counts(blk)[r]);
      n += split.counts(blk)[r];
    }
    EXPECT_EQ(n, total_counts[r]);
    EXPECT_NEAR(sum / static_cast<double>(n), total[r], 1e-12);
  }
  // Lag 0 of the middle block: exactly its own 200 samples.
  EXPECT_EQ(split.counts(1)[0], 200);
}

TEST(MultiTauCorrelator, IntegralOfAnExponentialCorrelation) {
  // AR(1) with φ = exp(−1/τ): C(t) = exp(−t/τ), whose sum over lags 0, 1, 2, … is 1/(1 − φ).
  const double tau = 20.0, phi = std::exp(-1.0 / tau);
  const std::vector<double> x = gaussian_ar1(400000, phi, 4);
  MultiTauCorrelator c(1, 16, 2, 10, 1);
  for (const double& v : x) c.add(&v, 0);
  const auto lags = c.lags();
  const auto corr = c.correlation(0);
  // Trapezoid on the lag grid, plus the half of C(0) that a sum over lags counts beyond the integral.
  double integral = 0.5 * corr[0];
  for (std::size_t r = 1; r < lags.size() && lags[r] <= 10 * static_cast<std::int64_t>(tau); ++r)
    integral += 0.5 * (corr[r] + corr[r - 1]) * static_cast<double>(lags[r] - lags[r - 1]);
  const double exact = 1.0 / (1.0 - phi);
  // Statistical error of the integrated correlation ≈ exact · √(4τ/n) ≈ 1.4%; allow 4 of those.
  EXPECT_NEAR(integral / exact, 1.0, 0.06);
}

TEST(MultiTauCorrelator, ACheckpointResumesBitForBit) {
  const std::vector<double> x = gaussian_ar1(777, 0.7, 5);
  MultiTauCorrelator straight(1, 8, 2, 6, 2), first(1, 8, 2, 6, 2);
  for (std::size_t i = 0; i < x.size(); ++i) straight.add(&x[i], i < 400 ? 0 : 1);
  for (std::size_t i = 0; i < 333; ++i) first.add(&x[i], 0);
  MultiTauCorrelator resumed(1, 8, 2, 6, 2);
  resumed.restore(nlohmann::json::parse(first.to_json().dump()));
  for (std::size_t i = 333; i < x.size(); ++i) resumed.add(&x[i], i < 400 ? 0 : 1);
  for (int blk = 0; blk < 2; ++blk) {
    EXPECT_EQ(straight.correlation(blk), resumed.correlation(blk));
    EXPECT_EQ(straight.counts(blk), resumed.counts(blk));
  }
  MultiTauCorrelator other(2, 8, 2, 6, 2);
  EXPECT_THROW(other.restore(first.to_json()), std::invalid_argument);
}
