#include "anisodyn/analysis/order_relaxation.hpp"

#include <cmath>

#include "anisodyn/core/error.hpp"

namespace anisodyn::analysis {

namespace {
const std::vector<std::string> kDecayKeys{"noise_from", "noise_factor"};
const std::vector<std::string> kRegressionKeys{"lags_per_decade", "max_origins"};

void parse_fit_band(tool::ConfigNode& cfg, OrderRelaxationSettings& s) {
  if (!cfg.has("fit_band")) {
    cfg.mark_used("fit_band");
    return;
  }
  const std::vector<double> band = cfg.numbers("fit_band");
  const double top = s.method == RelaxationMethod::Decay ? 2.0 / 3.0 : 1.0;  // δS_zz ≤ 2/3; C/C(0) ≤ 1
  if (band.size() != 2 || !(band[0] > 0) || !(band[1] > band[0]) || !(band[1] <= top))
    cfg.fail("fit_band", std::string("expected [low, high] with 0 < low < high <= ") + (top < 1 ? "2/3 (bounds of delta S_zz)" : "1 (bounds of C/C(0))"));
  s.band_low = band[0];
  s.band_high = band[1];
}
}  // namespace

OrderRelaxationSettings parse_order_relaxation_settings(tool::ConfigNode& cfg) {
  OrderRelaxationSettings s;
  s.species = cfg.string("species", "");
  const std::string method = cfg.choice("method", {"decay", "regression"});
  s.method = method == "decay" ? RelaxationMethod::Decay : RelaxationMethod::Regression;
  const bool decay = s.method == RelaxationMethod::Decay;
  if (!decay) {
    s.band_low = 0.05;
    s.band_high = 0.5;
  }
  parse_fit_band(cfg, s);
  for (const auto& key : kDecayKeys) cfg.reject_unless(decay, key, "unless method is \"decay\" (the noise level bounds Method A's fit window)");
  for (const auto& key : kRegressionKeys) cfg.reject_unless(!decay, key, "unless method is \"regression\" (the lag grid of C(t))");
  if (decay) {
    s.noise_from = cfg.number("noise_from", -INFINITY);
    s.noise_factor = cfg.positive("noise_factor", s.noise_factor);
  } else {
    s.lags_per_decade = cfg.non_negative("lags_per_decade", s.lags_per_decade);
    s.max_origins = static_cast<std::size_t>(cfg.non_negative_integer("max_origins", 0));
  }
  return s;
}

std::string order_tensor_observable(const std::string& species) { return "order_tensor_" + species; }

double full_contraction(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2.0 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5]);
}

IndexWindow decay_window(std::size_t start, std::size_t n, const std::function<bool(std::size_t)>& below_top,
                         const std::function<bool(std::size_t)>& above_bottom) {
  IndexWindow w{n, n};
  for (std::size_t k = start; k < n; ++k)
    if (below_top(k)) {
      w.first = k;
      break;
    }
  w.last = w.first;
  while (w.last < n && above_bottom(w.last)) ++w.last;
  return w;
}

double collective_rate(const std::vector<double>& x, const std::vector<double>& y, const IndexWindow& window) {
  if (window.size() < 2) return std::nan("");
  const auto begin = static_cast<std::ptrdiff_t>(window.first), end = static_cast<std::ptrdiff_t>(window.last);
  const std::vector<double> xs(x.begin() + begin, x.begin() + end), ys(y.begin() + begin, y.begin() + end);
  // S relaxes as exp(−6 D_r^coll t) (spec 20 §7): the rank-2 decay rate l(l + 1) D with l = 2.
  return -fit_exponential(xs, ys).slope / 6.0;
}

const ObservableSeries& order_tensor_rows(const Trajectory& t, const std::string& species) {
  const std::string name = order_tensor_observable(species), where = "/observables/" + name;
  const auto it = t.observables.find(name);
  if (it == t.observables.end())
    throw InputError(t.path, where, "no " + name + " observable (anisodyn-bd records it for every rod species, every observe_every steps)");
  if (it->second.width != 6) throw InputError(t.path, where + "/value", "expected 6 columns (xx, yy, zz, xy, xz, yz)");
  if (it->second.time.size() < 3) throw InputError(t.path, where, "expected at least 3 rows to fit a decay");
  return it->second;
}

OrderRelaxationAnalysis::OrderRelaxationAnalysis(OrderRelaxationSettings settings, std::size_t replicas, std::string config_file)
    : s_(std::move(settings)), config_file_(std::move(config_file)), replicas_(replicas) {}

void OrderRelaxationAnalysis::accumulate(const Trajectory& t, int species_index) {
  const std::string& species = t.species_table.at(static_cast<std::size_t>(species_index)).name;
  const ObservableSeries& s = order_tensor_rows(t, species);
  if (seen_ == 0) {
    rows_ = s.time.size();
    first_path_ = t.path;
    time_sum_.assign(rows_, 0.0);
  }
  // Replicas are averaged row by row (decay) or share one lag grid (regression).
  if (s.time.size() != rows_)
    throw InputError(t.path, "/observables/" + order_tensor_observable(species),
                     "mismatched replicas: " + std::to_string(s.time.size()) + " rows, " + first_path_ + " has " + std::to_string(rows_));
  for (std::size_t k = 0; k < rows_; ++k) time_sum_[k] += s.time[k];
  if (s_.method == RelaxationMethod::Decay) {
    times_.push_back(s.time);
    tensors_.push_back(s.value);
  } else {
    add_correlation_samples(s);
  }
  ++seen_;
}

}  // namespace anisodyn::analysis
