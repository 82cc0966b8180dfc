#include "anisodyn/analysis/observable_summary.hpp"

#include <cmath>

#include "anisodyn/core/error.hpp"
#include "anisodyn/analysis/replica_statistics.hpp"
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

/// A sample's sums as one vector (n, Σt, Σt², Σx, Σtx), the form of the shared jackknife
/// (replica_statistics.hpp); the mean and the slope are the same for the mean of samples as for
/// their total.
std::vector<double> flatten(const Sums& s) {
  std::vector<double> v{s.n, s.t, s.tt};
  v.insert(v.end(), s.x.begin(), s.x.end());
  v.insert(v.end(), s.tx.begin(), s.tx.end());
  return v;
}

Sums unflatten(const std::vector<double>& v) {
  Sums s;
  s.n = v[0], s.t = v[1], s.tt = v[2];
  const std::size_t width = (v.size() - 3) / 2;
  s.x.assign(v.begin() + 3, v.begin() + 3 + static_cast<std::ptrdiff_t>(width));
  s.tx.assign(v.begin() + 3 + static_cast<std::ptrdiff_t>(width), v.end());
  return s;
}

/// The statistic of every component of the pooled samples, with the jackknife error over them.
std::vector<Estimate> pooled(const std::vector<Sums>& parts, const std::function<double(const Sums&, std::size_t)>& stat) {
  CurveSamples samples;
  for (const Sums& s : parts) samples.add(flatten(s));
  const auto curve = jackknife_curve(samples, [&](const std::vector<double>& mean) {
    const Sums s = unflatten(mean);
    std::vector<double> out(s.x.size());
    for (std::size_t k = 0; k < out.size(); ++k) out[k] = stat(s, k);
    return out;
  });
  std::vector<Estimate> out(curve.value.size());
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = {curve.value[k], curve.error[k]};
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
  for (std::size_t k = 0; k < out.size(); ++k) {
    std::vector<double> slopes;
    for (const Sums& s : each) slopes.push_back(s.slope(k));
    out[k] = mean_and_error(slopes);
  }
  return out;
}

}  // namespace anisodyn::analysis
