#pragma once
// Mean and standard error of a correlated time series. Two estimates are made and the larger is
// reported, because each one fails quietly in its own way when the run is short:
//   - block averaging (Flyvbjerg & Petersen, J. Chem. Phys. 91, 461, 1989): the series is halved
//     by pair-averaging until fewer than `min_blocks` blocks remain; the largest error over the
//     levels is the plateau value once blocks outlast the correlation time, and too small before;
//   - the integrated autocorrelation time τ_int with Sokal's automatic window (smallest W with
//     W ≥ 5 τ_int(W)), error = σ √(τ_int / n), computed on the series averaged down to at most
//     2048 points so that it stays O(n).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace anisodyn {

struct MeanError {
  double mean = 0.0;
  double error = 0.0;           // standard error of the mean: max(error_blocking, error_autocorrelation)
  double error_blocking = 0.0;
  double error_autocorrelation = 0.0;
  double tau_int = 0.5;         // integrated autocorrelation time, in samples of the input series
  std::size_t samples = 0;      // length of the series
  std::size_t blocks = 0;       // number of blocks at the level that gave error_blocking
};

namespace statistics_detail {

inline double mean_of(const std::vector<double>& x) {
  double s = 0.0;
  for (double v : x) s += v;
  return x.empty() ? 0.0 : s / static_cast<double>(x.size());
}

/// τ_int of x (in samples of x) with Sokal's window.
inline double integrated_autocorrelation_time(const std::vector<double>& x) {
  const std::size_t n = x.size();
  if (n < 4) return 0.5;
  const double m = mean_of(x);
  double c0 = 0.0;
  for (double v : x) c0 += (v - m) * (v - m);
  if (c0 <= 0.0) return 0.5;
  double tau = 0.5;
  for (std::size_t w = 1; w < n / 2; ++w) {
    double c = 0.0;
    for (std::size_t i = 0; i + w < n; ++i) c += (x[i] - m) * (x[i + w] - m);
    tau += c / c0 * static_cast<double>(n) / static_cast<double>(n - w);
    if (static_cast<double>(w) >= 5.0 * tau) break;
  }
  return std::max(tau, 0.5);
}

}  // namespace statistics_detail

inline MeanError block_average(std::vector<double> x, std::size_t min_blocks = 16) {
  using namespace statistics_detail;
  MeanError out;
  out.samples = x.size();
  if (x.empty()) return out;
  out.mean = mean_of(x);
  out.blocks = x.size();

  // Autocorrelation estimate on the series coarsened to ≤ 2048 points (block means of length b).
  std::size_t b = 1;
  while (x.size() / b > 2048) b *= 2;
  std::vector<double> coarse(x.size() / b);
  for (std::size_t i = 0; i < coarse.size(); ++i) {
    double s = 0.0;
    for (std::size_t k = 0; k < b; ++k) s += x[i * b + k];
    coarse[i] = s / static_cast<double>(b);
  }
  if (coarse.size() >= 4) {
    const double tau_coarse = integrated_autocorrelation_time(coarse);
    const double cm = mean_of(coarse);
    double var = 0.0;
    for (double v : coarse) var += (v - cm) * (v - cm);
    var /= static_cast<double>(coarse.size() - 1);
    out.error_autocorrelation = std::sqrt(var * 2.0 * tau_coarse / static_cast<double>(coarse.size()));
    // Back to input samples: σ²_mean = var_x · 2τ_int / n defines τ_int for the full series.
    double var_x = 0.0;
    for (double v : x) var_x += (v - out.mean) * (v - out.mean);
    var_x /= static_cast<double>(x.size() - 1);
    if (var_x > 0.0)
      out.tau_int = out.error_autocorrelation * out.error_autocorrelation * static_cast<double>(x.size()) / (2.0 * var_x);
  }

  while (x.size() >= min_blocks && x.size() >= 2) {
    const double n = static_cast<double>(x.size());
    const double m = mean_of(x);
    double c0 = 0.0;
    for (double v : x) c0 += (v - m) * (v - m);
    c0 /= n;
    const double se = std::sqrt(c0 / (n - 1.0));
    if (se >= out.error_blocking) { out.error_blocking = se; out.blocks = x.size(); }
    std::vector<double> half(x.size() / 2);
    for (std::size_t i = 0; i < half.size(); ++i) half[i] = 0.5 * (x[2 * i] + x[2 * i + 1]);
    x.swap(half);
  }
  out.error = std::max(out.error_blocking, out.error_autocorrelation);
  return out;
}

/// Mean and standard error of independent samples (one per particle, say): error = sample
/// standard deviation / √n; no correlation analysis.
inline MeanError mean_of_independent(const std::vector<double>& x) {
  MeanError m;
  m.samples = x.size();
  m.mean = statistics_detail::mean_of(x);
  if (x.size() < 2) return m;
  double q = 0.0;
  for (double v : x) q += (v - m.mean) * (v - m.mean);
  m.error = std::sqrt(q / static_cast<double>(x.size() - 1) / static_cast<double>(x.size()));
  return m;
}

}  // namespace anisodyn
