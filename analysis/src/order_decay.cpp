// Method A of spec 20 §7: the decay of δS_zz = S_zz − 1/3 from the aligned start, averaged over
// decays (replicas) on the common time grid, fitted in its late, near-equilibrium part.
#include <cmath>

#include "anisodyn/analysis/order_parameters.hpp"
#include "anisodyn/analysis/order_relaxation.hpp"
#include "anisodyn/core/error.hpp"

namespace anisodyn::analysis {

namespace {

/// One diagonal component (0 xx, 1 yy, 2 zz) of a replica's rows.
std::vector<double> component(const std::vector<double>& rows, std::size_t c) {
  std::vector<double> out;
  for (std::size_t k = c; k < rows.size(); k += 6) out.push_back(rows[k]);
  return out;
}

std::vector<double> slice(const std::vector<double>& v, std::size_t part, std::size_t n) {
  return {v.begin() + static_cast<std::ptrdiff_t>(part * n), v.begin() + static_cast<std::ptrdiff_t>((part + 1) * n)};
}

std::vector<double> minus_isotropic(std::vector<double> s_zz) {
  for (double& v : s_zz) v -= 1.0 / 3.0;
  return s_zz;
}

}  // namespace

OrderDecayResult OrderRelaxationAnalysis::decay() const {
  OrderDecayResult r;
  r.replicas = seen_;
  for (double t : time_sum_) r.time.push_back(t / static_cast<double>(seen_));
  const std::size_t n = r.time.size();
  // Each decay onto the common grid of mean row times (spec 50 §0, non-equilibrium averages).
  CurveSamples curves;
  for (std::size_t rep = 0; rep < seen_; ++rep) {
    std::vector<double> sample;
    for (std::size_t c = 0; c < 3; ++c) {
      const auto on_grid = interpolate_onto(times_[rep], component(tensors_[rep], c), r.time);
      sample.insert(sample.end(), on_grid.begin(), on_grid.end());
    }
    curves.add(std::move(sample));
  }
  const auto mean = curves.mean(), se = curves.standard_error();
  r.s_xx = slice(mean, 0, n), r.s_xx_error = slice(se, 0, n);
  r.s_yy = slice(mean, 1, n), r.s_yy_error = slice(se, 1, n);
  r.s_zz = slice(mean, 2, n), r.s_zz_error = slice(se, 2, n);
  r.ds_zz = minus_isotropic(r.s_zz);

  // The equilibrium noise level: rms of the mean δS_zz about its isotropic value 0 over the late rows
  // (default: the last quarter of the time span), so a decay that has not finished raises it.
  r.noise_from = std::isfinite(s_.noise_from) ? s_.noise_from : r.time.front() + 0.75 * (r.time.back() - r.time.front());
  double ss = 0;
  for (std::size_t k = 0; k < n; ++k)
    if (r.time[k] >= r.noise_from) {
      ss += r.ds_zz[k] * r.ds_zz[k];
      ++r.noise_rows;
    }
  if (r.noise_rows < 2)
    throw InputError(config_file_, "noise_from", "expected at least 2 order-tensor rows at t >= " + std::to_string(r.noise_from) +
                                                     " (the rows end at t = " + std::to_string(r.time.back()) + ")");
  r.noise = std::sqrt(ss / static_cast<double>(r.noise_rows));
  r.threshold = std::max(s_.band_low, s_.noise_factor * r.noise);

  RelaxationFit& fit = r.fit;
  fit.window = decay_window(0, n, [&](std::size_t k) { return r.ds_zz[k] < s_.band_high; },
                            [&](std::size_t k) { return r.ds_zz[k] > r.threshold; });
  if (fit.window.size() > 0) {
    fit.t_min = r.time[fit.window.first];
    fit.t_max = r.time[fit.window.last - 1];
  }
  if (seen_ >= 2) {
    fit.rate = jackknife(curves, [&](const std::vector<double>& m) { return collective_rate(r.time, minus_isotropic(slice(m, 2, n)), fit.window); });
    fit.error_method = "jackknife over replicas (decays)";
  } else {
    // One decay has no replica scatter: the fit's own error (residuals, which are correlated in time).
    fit.rate.value = collective_rate(r.time, r.ds_zz, fit.window);
    if (fit.window.size() >= 3) {
      const auto b = static_cast<std::ptrdiff_t>(fit.window.first), e = static_cast<std::ptrdiff_t>(fit.window.last);
      fit.rate.error = fit_exponential({r.time.begin() + b, r.time.begin() + e}, {r.ds_zz.begin() + b, r.ds_zz.begin() + e}).slope_error / 6.0;
    }
    fit.error_method = "one decay: least-squares error of the slope from the residuals (correlated in time, so a lower bound)";
  }
  return r;
}

}  // namespace anisodyn::analysis
