#include "anisodyn/analysis/lag_grid.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace anisodyn::analysis {

std::optional<std::pair<double, double>> parse_lag_window(tool::ConfigNode& cfg, const std::string& key) {
  auto w = cfg.optional_object(key);
  if (!w) return std::nullopt;
  const double a = w->positive("t_min"), b = w->positive("t_max");
  if (!(b > a)) w->fail("t_max", "expected t_max > t_min");
  return std::make_pair(a, b);
}

void ReplicaMeanLags::add(const LagGrid& grid, const std::vector<double>& time) {
  sum_.resize(grid.classes.size(), 0.0);
  for (std::size_t c = 0; c < grid.classes.size(); ++c) {
    double lag = 0;
    for (const auto& [i0, j0] : grid.classes[c].pairs) lag += time[j0] - time[i0];
    sum_[c] += lag / static_cast<double>(grid.classes[c].pairs.size());
  }
  ++replicas_;
}

std::vector<double> ReplicaMeanLags::mean() const {
  std::vector<double> out;
  for (double s : sum_) out.push_back(s / static_cast<double>(std::max<std::size_t>(replicas_, 1)));
  return out;
}

bool uniformly_spaced(const std::vector<double>& time, double rel_tol) {
  if (time.size() < 3) return true;
  const double dt = (time.back() - time.front()) / static_cast<double>(time.size() - 1);
  for (std::size_t f = 1; f < time.size(); ++f)
    if (std::abs(time[f] - time[f - 1] - dt) > rel_tol * dt) return false;
  return true;
}

std::vector<std::size_t> log_spaced_lags(std::size_t max_lag, double per_decade) {
  std::vector<std::size_t> lags;
  if (max_lag == 0) return lags;
  if (per_decade <= 0) {
    for (std::size_t k = 1; k <= max_lag; ++k) lags.push_back(k);
    return lags;
  }
  for (double e = 0;; e += 1.0) {
    const auto k = static_cast<std::size_t>(std::llround(std::pow(10.0, e / per_decade)));
    if (k > max_lag) break;
    if (lags.empty() || k > lags.back()) lags.push_back(k);
  }
  if (lags.back() != max_lag) lags.push_back(max_lag);
  return lags;
}

namespace {

/// Keeps at most `keep` elements, evenly spread, always including the first.
void thin(std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs, std::size_t keep) {
  if (keep == 0 || pairs.size() <= keep) return;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  out.reserve(keep);
  for (std::size_t k = 0; k < keep; ++k) out.push_back(pairs[k * pairs.size() / keep]);
  pairs.swap(out);
}

}  // namespace

LagGrid make_lag_grid(const std::vector<double>& time, double per_decade, std::size_t max_origins) {
  LagGrid grid;
  const std::size_t frames = time.size();
  if (frames < 2) return grid;
  grid.uniform = uniformly_spaced(time);
  if (grid.uniform) {
    grid.frame_spacing = (time.back() - time.front()) / static_cast<double>(frames - 1);
    for (std::size_t k : log_spaced_lags(frames - 1, per_decade)) {
      LagClass c;
      double sum = 0;
      for (std::size_t i = 0; i + k < frames; ++i) {
        c.pairs.emplace_back(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i + k));
        sum += time[i + k] - time[i];
      }
      c.lag = sum / static_cast<double>(c.pairs.size());
      thin(c.pairs, max_origins);
      grid.classes.push_back(std::move(c));
    }
    return grid;
  }
  const double bins = per_decade > 0 ? per_decade : 20.0;
  std::map<long, LagClass> by_bin;
  std::map<long, double> sums;
  for (std::size_t i = 0; i < frames; ++i)
    for (std::size_t j = i + 1; j < frames; ++j) {
      const double lag = time[j] - time[i];
      const long b = std::lround(std::floor(std::log10(lag) * bins + 1e-9));
      by_bin[b].pairs.emplace_back(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
      sums[b] += lag;
    }
  for (auto& [b, c] : by_bin) {
    c.lag = sums[b] / static_cast<double>(c.pairs.size());
    thin(c.pairs, max_origins);
    grid.classes.push_back(std::move(c));
  }
  return grid;
}

std::size_t nearest_lag_class(const LagGrid& grid, double t) {
  std::size_t best = 0;
  double dist = INFINITY;
  for (std::size_t c = 0; c < grid.classes.size(); ++c) {
    const double d = std::abs(std::log(grid.classes[c].lag / t));
    if (d < dist) { dist = d; best = c; }
  }
  return best;
}

}  // namespace anisodyn::analysis
