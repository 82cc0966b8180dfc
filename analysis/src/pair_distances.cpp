#include "anisodyn/analysis/pair_distances.hpp"

#include <cmath>
#include <limits>

#include "anisodyn/core/error.hpp"

namespace anisodyn::analysis {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The histogram row of a replica: the observable's only row (the engine writes it once, at the end).
const ObservableSeries& histogram_of(const Trajectory& t) {
  const std::string where = "/observables/" + kPairDistanceObservable;
  const auto it = t.observables.find(kPairDistanceObservable);
  if (it == t.observables.end())
    throw InputError(t.path, where, "no " + kPairDistanceObservable + " observable: anisodyn-bd writes it only with the rod potential (\"potential\": {\"type\": \"overlap_volume\"})");
  if (it->second.time.size() != 1)
    throw InputError(t.path, where, "expected one row (the histogram summed over the run), found " + std::to_string(it->second.time.size()));
  return it->second;
}
}  // namespace

std::vector<double> bin_centres(std::size_t bins) {
  std::vector<double> x(bins);
  for (std::size_t b = 0; b < bins; ++b) x[b] = (static_cast<double>(b) + 0.5) / static_cast<double>(bins);
  return x;
}

HistogramMoments histogram_moments(const std::vector<double>& counts) {
  HistogramMoments m;
  const std::vector<double> x = bin_centres(counts.size());
  double sx = 0, sxx = 0;
  for (std::size_t b = 0; b < counts.size(); ++b) {
    m.pairs += counts[b];
    sx += counts[b] * x[b];
    sxx += counts[b] * x[b] * x[b];
  }
  const double dx = 1.0 / static_cast<double>(counts.size());
  m.density.assign(counts.size(), kNaN);
  if (!(m.pairs > 0)) {
    m.mean_x = m.sigma_x = kNaN;
    return m;
  }
  for (std::size_t b = 0; b < counts.size(); ++b) m.density[b] = counts[b] / (m.pairs * dx);
  m.mean_x = sx / m.pairs;
  m.sigma_x = std::sqrt(std::max(0.0, sxx / m.pairs - m.mean_x * m.mean_x));
  return m;
}

double study_box_edge(double rod_length, double effective_diameter) {
  return std::cbrt(250.0 * M_PI * rod_length * rod_length * effective_diameter);
}

PairDistanceAnalysis::PairDistanceAnalysis(double diameter, double length) : diameter_(diameter), length_(length) {}

void PairDistanceAnalysis::accumulate(const Trajectory& t) {
  const ObservableSeries& h = histogram_of(t);
  const std::string where = "/observables/" + kPairDistanceObservable + "/value";
  if (bins_ == 0) {
    bins_ = h.width;
    total_counts_.assign(bins_, 0.0);
  }
  if (h.width != bins_)
    throw InputError(t.path, where, std::to_string(h.width) + " bins, the first replica has " + std::to_string(bins_));
  const HistogramMoments m = histogram_moments(h.value);
  if (!(m.pairs > 0)) throw InputError(t.path, where, "no interacting pair was counted: P_d(x) and D_eff are undefined");
  for (std::size_t b = 0; b < bins_; ++b) total_counts_[b] += h.value[b];
  std::vector<double> sample{m.mean_x, m.sigma_x};
  sample.insert(sample.end(), m.density.begin(), m.density.end());
  samples_.add(std::move(sample));
  pairs_.push_back(m.pairs);
}

PairDistanceResult PairDistanceAnalysis::compute() const {
  PairDistanceResult r;
  r.diameter = diameter_;
  r.length = length_;
  r.x = bin_centres(bins_);
  r.counts = total_counts_;
  r.replica_pairs = pairs_;
  const auto mean = samples_.mean(), se = samples_.standard_error();
  r.mean_x = {mean[0], se[0]};
  r.sigma_x = {mean[1], se[1]};
  r.density.assign(mean.begin() + 2, mean.end());
  r.density_error.assign(se.begin() + 2, se.end());
  r.effective_diameter = {diameter_ * r.mean_x.value, diameter_ * r.mean_x.error};
  // The edge is a non-linear function of the mean D_eff: a jackknife over replicas (spec 50 §0).
  r.box_edge = jackknife(samples_, [&](const std::vector<double>& m) { return study_box_edge(length_, diameter_ * m[0]); });
  return r;
}

}  // namespace anisodyn::analysis
