// Method B of spec 20 §7: Onsager regression of the equilibrium order-tensor fluctuations,
// C(t) = ⟨δS(t0 + t) : δS(t0)⟩ with δS = S − ⟨S⟩, over every time origin of the observable rows.
#include <cmath>
#include <limits>

#include "anisodyn/analysis/order_relaxation.hpp"

namespace anisodyn::analysis {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// δS = S − ⟨S⟩, the replica's own mean over its rows.
std::vector<double> fluctuations(const ObservableSeries& s) {
  const std::size_t rows = s.time.size();
  double mean[6] = {0, 0, 0, 0, 0, 0};
  for (std::size_t k = 0; k < rows; ++k)
    for (std::size_t c = 0; c < 6; ++c) mean[c] += s.value[6 * k + c] / static_cast<double>(rows);
  std::vector<double> d(s.value);
  for (std::size_t k = 0; k < rows; ++k)
    for (std::size_t c = 0; c < 6; ++c) d[6 * k + c] -= mean[c];
  return d;
}
}  // namespace

void OrderRelaxationAnalysis::add_correlation_samples(const ObservableSeries& s) {
  const std::size_t rows = s.time.size();
  if (seen_ == 0) {
    grid_ = make_lag_grid(s.time, s_.lags_per_decade, s_.max_origins);
    lag_sum_.assign(grid_.classes.size() + 1, 0.0);
    origin_count_.assign(grid_.classes.size() + 1, 0.0);
  }
  const std::size_t nc = grid_.classes.size() + 1;  // lag 0, then the grid's classes
  const std::vector<double> d = fluctuations(s);
  const std::size_t blocks = error_blocks(replicas_);
  std::vector<std::vector<double>> sums(blocks, std::vector<double>(nc, 0.0)), counts(blocks, std::vector<double>(nc, 0.0));
  for (std::size_t k = 0; k < rows; ++k) {
    const std::size_t b = origin_block(k, rows, blocks);
    sums[b][0] += full_contraction(&d[6 * k], &d[6 * k]);
    counts[b][0] += 1;
  }
  origin_count_[0] += static_cast<double>(rows);
  for (std::size_t c = 1; c < nc; ++c) {
    const LagClass& lc = grid_.classes[c - 1];
    double lag = 0;
    for (const auto& [i0, j0] : lc.pairs) {
      const std::size_t b = origin_block(i0, rows, blocks);
      sums[b][c] += full_contraction(&d[6 * i0], &d[6 * j0]);
      counts[b][c] += 1;
      lag += s.time[j0] - s.time[i0];
    }
    lag_sum_[c] += lag / static_cast<double>(lc.pairs.size());
    origin_count_[c] += static_cast<double>(lc.pairs.size());
  }
  for (std::size_t b = 0; b < blocks; ++b) {
    std::vector<double> sample(nc, kNaN);
    for (std::size_t c = 0; c < nc; ++c)
      if (counts[b][c] > 0) sample[c] = sums[b][c] / counts[b][c];
    correlations_.add(std::move(sample));
  }
}

OrderRegressionResult OrderRelaxationAnalysis::regression() const {
  OrderRegressionResult r;
  r.replicas = seen_;
  r.rows = rows_;
  r.samples = correlations_.count();
  for (double l : lag_sum_) r.lag.push_back(l / static_cast<double>(seen_));
  r.origins = origin_count_;
  r.correlation = correlations_.mean();
  r.correlation_error = correlations_.standard_error();
  const CurveEstimate normalised = jackknife_curve(correlations_, [](const std::vector<double>& m) {
    std::vector<double> out(m.size());
    for (std::size_t k = 0; k < m.size(); ++k) out[k] = m[k] / m[0];
    return out;
  });
  r.normalised = normalised.value;
  r.normalised_error = normalised.error;
  RelaxationFit& fit = r.fit;
  fit.window = decay_window(1, r.lag.size(), [&](std::size_t k) { return r.normalised[k] <= s_.band_high; },
                            [&](std::size_t k) { return r.normalised[k] >= s_.band_low; });
  if (fit.window.size() > 0) {
    fit.t_min = r.lag[fit.window.first];
    fit.t_max = r.lag[fit.window.last - 1];
  }
  // C(0) only shifts ln C: the slope of ln C equals that of ln C/C(0).
  fit.rate = jackknife(correlations_, [&](const std::vector<double>& m) { return collective_rate(r.lag, m, fit.window); });
  fit.error_method = seen_ >= 2 ? "jackknife over replicas" : "jackknife over 10 blocks of time origins (one replica)";
  return r;
}

}  // namespace anisodyn::analysis
