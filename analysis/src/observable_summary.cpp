#include "anisodyn/analysis/observable_summary.hpp"

#include <cmath>

#include "anisodyn/core/error.hpp"
#include "anisodyn/io/h5md.hpp"

namespace anisodyn::analysis {

namespace {

/// Sums that both statistics pool over rows: n, Σt, Σt², and per component Σx, Σtx.
struct Sums {
  double n = 0, t = 0, tt = 0;
  std::vector<double> x, tx;
  void add(double time, const double* v, std::size_t width) {
    x.resize(width, 0.0), tx.resize(width, 0.0);
    n += 1, t += time, tt += time * time;
    for (std::size_t k = 0; k < width; ++k) x[k] += v[k], tx[k] += time * v[k];
  }
  void add(const Sums& o) {
    x.resize(o.x.size(), 0.0), tx.resize(o.tx.size(), 0.0);
    n += o.n, t += o.t, tt += o.tt;
    for (std::size_t k = 0; k < o.x.size(); ++k) x[k] += o.x[k], tx[k] += o.tx[k];
  }
  double mean(std::size_t k) const { return x[k] / n; }
  double slope(std::size_t k) const { return (n * tx[k] - t * x[k]) / (n * tt - t * t); }
};

/// The samples: one per run, or `blocks` of a single run's rows.
std::vector<Sums> samples(const std::vector<ObservableRows>& runs, std::size_t blocks) {
  std::vector<Sums> out;
  const std::size_t parts = runs.size() == 1 ? blocks : 1;
  for (const ObservableRows& r : runs) {
    const std::size_t rows = r.time.size();
    for (std::size_t b = 0; b < parts; ++b) {
      Sums s;
      for (std::size_t row = rows * b / parts; row < rows * (b + 1) / parts; ++row) s.add(r.time[row], &r.value[row * r.width], r.width);
      out.push_back(s);
    }
  }
  return out;
}

/// The statistic of the pooled samples, with the jackknife error over them.
std::vector<Estimate> pooled(const std::vector<Sums>& parts, const std::function<double(const Sums&, std::size_t)>& stat) {
  Sums all;
  for (const Sums& s : parts) all.add(s);
  std::vector<Estimate> out(all.x.size());
  const double n = static_cast<double>(parts.size());
  for (std::size_t k = 0; k < out.size(); ++k) {
    out[k].value = stat(all, k);
    std::vector<double> loo;
    for (std::size_t leave = 0; leave < parts.size(); ++leave) {
      Sums rest;
      for (std::size_t s = 0; s < parts.size(); ++s)
        if (s != leave) rest.add(parts[s]);
      loo.push_back(stat(rest, k));
    }
    double mean = 0.0, sum = 0.0;
    for (double v : loo) mean += v / n;
    for (double v : loo) sum += (v - mean) * (v - mean);
    out[k].error = n > 1 ? std::sqrt((n - 1.0) / n * sum) : NAN;
  }
  return out;
}

}  // namespace

ObservableRows read_rows(const std::string& path, const std::string& name, const std::function<bool(double)>& keep) {
  const io::H5mdReader r(path);
  if (!r.has_observable(name)) throw InputError(path, "/observables/" + name, "expected the observable " + name);
  const auto s = r.read_observable(name);
  ObservableRows out;
  out.width = s.width;
  out.units = r.observable_attribute(name, "units").value_or("");
  for (std::size_t row = 0; row < s.rows(); ++row) {
    if (!keep(s.time[row])) continue;
    out.time.push_back(s.time[row]);
    out.value.insert(out.value.end(), s.value.begin() + static_cast<std::ptrdiff_t>(row * s.width),
                     s.value.begin() + static_cast<std::ptrdiff_t>((row + 1) * s.width));
  }
  if (out.time.size() < 2) throw InputError(path, "/observables/" + name, "expected at least 2 rows in the window, got " + std::to_string(out.time.size()));
  return out;
}

std::vector<Estimate> observable_means(const std::vector<ObservableRows>& runs, std::size_t blocks) {
  return pooled(samples(runs, blocks), [](const Sums& s, std::size_t k) { return s.mean(k); });
}

std::vector<Estimate> observable_drifts(const std::vector<ObservableRows>& runs, std::size_t blocks) {
  const auto slope = [](const Sums& s, std::size_t k) { return s.slope(k); };
  if (runs.size() == 1) return pooled(samples(runs, blocks), slope);  // one line, jackknife over blocks
  // Replicas have their own levels (a total energy differs between them): one line each, then the
  // mean of the slopes and its standard error.
  const std::vector<Sums> each = samples(runs, 1);
  std::vector<Estimate> out(each.front().x.size());
  const double n = static_cast<double>(each.size());
  for (std::size_t k = 0; k < out.size(); ++k) {
    double mean = 0.0, sum = 0.0;
    for (const Sums& s : each) mean += s.slope(k) / n;
    for (const Sums& s : each) sum += (s.slope(k) - mean) * (s.slope(k) - mean);
    out[k] = {mean, std::sqrt(sum / (n - 1.0) / n)};
  }
  return out;
}

}  // namespace anisodyn::analysis
