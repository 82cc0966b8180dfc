#include "anisodyn/analysis/replica_statistics.hpp"

#include <algorithm>

namespace anisodyn::analysis {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::size_t longest(const std::vector<std::vector<double>>& curves) {
  std::size_t n = 0;
  for (const auto& c : curves) n = std::max(n, c.size());
  return n;
}
}  // namespace

std::vector<double> mean_curve(const std::vector<std::vector<double>>& curves) {
  const std::size_t m = longest(curves);
  std::vector<double> sum(m, 0.0), count(m, 0.0);
  for (const auto& c : curves)
    for (std::size_t k = 0; k < c.size(); ++k)
      if (!std::isnan(c[k])) { sum[k] += c[k]; count[k] += 1.0; }
  for (std::size_t k = 0; k < m; ++k) sum[k] = count[k] > 0 ? sum[k] / count[k] : kNaN;
  return sum;
}

std::vector<double> CurveSamples::mean() const { return mean_curve(samples_); }

std::vector<double> CurveSamples::standard_error() const {
  const std::size_t m = longest(samples_);
  const auto mu = mean();
  std::vector<double> out(m, kNaN);
  for (std::size_t k = 0; k < m; ++k) {
    double ss = 0.0, n = 0.0;
    for (const auto& c : samples_)
      if (k < c.size() && !std::isnan(c[k])) { ss += (c[k] - mu[k]) * (c[k] - mu[k]); n += 1.0; }
    if (n >= 2) out[k] = std::sqrt(ss / (n - 1.0) / n);
  }
  return out;
}

Estimate mean_and_error(const std::vector<double>& x) {
  Estimate e;
  if (x.empty()) return e;
  double s = 0.0;
  for (double v : x) s += v;
  e.value = s / static_cast<double>(x.size());
  if (x.size() < 2) return e;
  double ss = 0.0;
  for (double v : x) ss += (v - e.value) * (v - e.value);
  e.error = std::sqrt(ss / static_cast<double>(x.size() - 1) / static_cast<double>(x.size()));
  return e;
}

Estimate jackknife(const CurveSamples& samples, const std::function<double(const std::vector<double>&)>& f) {
  Estimate e;
  const auto& all = samples.samples();
  if (all.empty()) return e;
  e.value = f(mean_curve(all));
  const std::size_t n = all.size();
  if (n < 2) return e;
  std::vector<double> leave_one_out;
  for (std::size_t k = 0; k < n; ++k) {
    std::vector<std::vector<double>> others;
    for (std::size_t j = 0; j < n; ++j)
      if (j != k) others.push_back(all[j]);
    leave_one_out.push_back(f(mean_curve(others)));
  }
  double mean = 0.0;
  for (double v : leave_one_out) mean += v / static_cast<double>(n);
  double ss = 0.0;
  for (double v : leave_one_out) ss += (v - mean) * (v - mean);
  e.error = std::sqrt(static_cast<double>(n - 1) / static_cast<double>(n) * ss);
  return e;
}

CurveEstimate jackknife_curve(const CurveSamples& samples,
                              const std::function<std::vector<double>(const std::vector<double>&)>& g) {
  CurveEstimate e;
  const auto& all = samples.samples();
  if (all.empty()) return e;
  e.value = g(mean_curve(all));
  e.error.assign(e.value.size(), kNaN);
  const std::size_t n = all.size();
  if (n < 2) return e;
  // leave-one-out means from the total sum, so the cost is O(n · length)
  const std::size_t m = longest(all);
  std::vector<double> sum(m, 0.0), count(m, 0.0);
  for (const auto& c : all)
    for (std::size_t k = 0; k < c.size(); ++k)
      if (!std::isnan(c[k])) { sum[k] += c[k]; count[k] += 1.0; }
  std::vector<std::vector<double>> loo;
  for (const auto& c : all) {
    std::vector<double> mean(m, kNaN);
    for (std::size_t k = 0; k < m; ++k) {
      const bool has = k < c.size() && !std::isnan(c[k]);
      const double s = sum[k] - (has ? c[k] : 0.0), cnt = count[k] - (has ? 1.0 : 0.0);
      if (cnt > 0) mean[k] = s / cnt;
    }
    loo.push_back(g(mean));
  }
  for (std::size_t k = 0; k < e.value.size(); ++k) {
    double mu = 0, cnt = 0;
    for (const auto& l : loo)
      if (!std::isnan(l[k])) { mu += l[k]; cnt += 1; }
    if (cnt < 2) continue;
    mu /= cnt;
    double ss = 0;
    for (const auto& l : loo)
      if (!std::isnan(l[k])) ss += (l[k] - mu) * (l[k] - mu);
    e.error[k] = std::sqrt((cnt - 1.0) / cnt * ss);
  }
  return e;
}

}  // namespace anisodyn::analysis
