#include "anisodyn/analysis/dipolar_clusters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "anisodyn/core/error.hpp"

namespace anisodyn::analysis {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// Display rule of spec 50 §5.5: probabilities below this are left blank (written as NaN).
constexpr double kBlankProbability = 1e-6;

std::string number_text(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

}  // namespace

// ---- E4 -----------------------------------------------------------------------------------------

ChainStatistics chain_statistics(const std::vector<double>& counts, double cubes) {
  double chains = 0, in_chains = 0, second = 0;
  for (std::size_t k = 1; k < counts.size(); ++k) {
    const double l = static_cast<double>(k + 1);
    chains += counts[k];
    in_chains += l * counts[k];
    second += l * l * counts[k];
  }
  ChainStatistics s;
  s.chain_fraction = cubes > 0 ? in_chains / cubes : kNaN;
  s.mean_length = chains > 0 ? in_chains / chains : kNaN;
  s.weight_mean_length = in_chains > 0 ? second / in_chains : kNaN;
  return s;
}

// ---- E6 -----------------------------------------------------------------------------------------

double wertheim_fraction(double p, double l) { return (1 - p) * (1 - p) * std::pow(p, l - 1); }

namespace {

double wertheim_chi2(const std::vector<double>& x, const std::vector<double>& w, double p) {
  double c = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double r = x[k] - wertheim_fraction(p, static_cast<double>(k + 1));
    c += w[k] * r * r;
  }
  return c;
}

/// argmin over p ∈ (0, 1) of the weighted residual: a grid scan guards against the secondary minima
/// that a sum of non-monotonic terms (1 − p)² p^{l−1} can have; golden section refines the best cell.
double minimise_wertheim(const std::vector<double>& x, const std::vector<double>& w) {
  constexpr int kScan = 400;
  int best = 0;
  double best_c = std::numeric_limits<double>::infinity();
  for (int k = 0; k < kScan; ++k) {
    const double c = wertheim_chi2(x, w, (k + 0.5) / kScan);
    if (c < best_c) { best_c = c; best = k; }
  }
  double a = std::max(1e-15, static_cast<double>(best - 1) / kScan), b = std::min(1 - 1e-15, static_cast<double>(best + 2) / kScan);
  const double g = (std::sqrt(5.0) - 1) / 2;
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = wertheim_chi2(x, w, c), fd = wertheim_chi2(x, w, d);
  for (int it = 0; it < 200 && b - a > 1e-14; ++it) {
    if (fc < fd) {
      b = d; d = c; fd = fc;
      c = b - g * (b - a); fc = wertheim_chi2(x, w, c);
    } else {
      a = c; c = d; fc = fd;
      d = a + g * (b - a); fd = wertheim_chi2(x, w, d);
    }
  }
  return 0.5 * (a + b);
}

double wertheim_slope(double p, double l) {
  // ∂/∂p (1 − p)² p^{l−1}
  const double first = -2 * (1 - p) * std::pow(p, l - 1);
  return l > 1 ? first + (l - 1) * (1 - p) * (1 - p) * std::pow(p, l - 2) : first;
}

}  // namespace

WertheimFit fit_wertheim(const std::vector<double>& x_in, const std::vector<double>& var) {
  WertheimFit f;
  std::size_t n = 0;
  for (std::size_t k = 0; k < x_in.size(); ++k)
    if (x_in[k] > 0) n = k + 1;
  if (n == 0) {
    f.p_b = f.error = f.error_curvature = f.chi2 = kNaN;
    f.method = "no clusters: nothing to fit";
    return f;
  }
  double floor = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < n; ++k)
    if (k < var.size() && var[k] > 0 && std::isfinite(var[k])) floor = std::min(floor, var[k]);
  const bool weighted = std::isfinite(floor);
  for (std::size_t k = 0; k < n; ++k) {
    const double v = k < var.size() && var[k] > 0 && std::isfinite(var[k]) ? var[k] : floor;
    f.length.push_back(static_cast<double>(k + 1));
    f.value.push_back(std::isnan(x_in[k]) ? 0.0 : x_in[k]);
    f.variance.push_back(weighted ? v : kNaN);
    f.weight.push_back(weighted ? 1.0 / v : 1.0);
  }
  f.p_b = minimise_wertheim(f.value, f.weight);
  double info = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double m = wertheim_fraction(f.p_b, f.length[k]);
    f.model.push_back(m);
    f.residual.push_back(f.value[k] - m);
    f.normalised_residual.push_back(weighted ? (f.value[k] - m) * std::sqrt(f.weight[k]) : kNaN);
    const double j = wertheim_slope(f.p_b, f.length[k]);
    info += f.weight[k] * j * j;
  }
  f.chi2 = wertheim_chi2(f.value, f.weight, f.p_b);
  if (weighted) {
    f.error_curvature = 1.0 / std::sqrt(info);
    f.method = "weighted least squares, weights 1/Var (zero variances floored at the smallest positive one)";
  } else {
    f.error_curvature = n > 1 ? std::sqrt(f.chi2 / static_cast<double>(n - 1) / info) : kNaN;
    f.method = "unweighted least squares (no variances), error from the residual variance";
  }
  f.error = f.error_curvature;
  return f;
}

WertheimFit fit_wertheim(const CurveSamples& samples) {
  const std::vector<double> mean = samples.mean(), se = samples.standard_error();
  std::vector<double> var(se.size());
  for (std::size_t k = 0; k < se.size(); ++k) var[k] = se[k] * se[k];
  WertheimFit f = fit_wertheim(mean, var);
  if (std::isnan(f.p_b) || samples.count() < 2) return f;
  const std::size_t n = f.value.size();
  const Estimate jk = jackknife(samples, [&](const std::vector<double>& m) {
    std::vector<double> x(n);
    for (std::size_t k = 0; k < n; ++k) x[k] = k < m.size() && !std::isnan(m[k]) ? m[k] : 0.0;
    return minimise_wertheim(x, f.weight);  // weights held fixed
  });
  f.error = jk.error;
  f.method += "; error: jackknife over " + std::to_string(samples.count()) + " samples with the weights held fixed";
  return f;
}

// ---- settings -------------------------------------------------------------------------------------

DipolarClusterSettings parse_dipolar_cluster_settings(tool::ConfigNode& cfg) {
  DipolarClusterSettings s;
  s.species = cfg.string("species", "");
  s.rule = parse_dipolar_bond_rule(cfg, true);
  if (cfg.has("transition_times")) {
    s.transition_times = cfg.numbers("transition_times");
    for (double t : s.transition_times)
      if (!(t >= 0)) cfg.fail("transition_times", "expected non-negative times t_1");
  }
  s.transition_at_x2_maximum = cfg.boolean("transition_at_x2_maximum", false);
  s.transition_lag = cfg.positive("transition_lag", 0.3);
  s.transition_window = cfg.non_negative("transition_window", 0.05);
  s.lag_tolerance = cfg.positive("transition_lag_tolerance", 0.1);
  s.plateau_fraction = cfg.positive("plateau_fraction", 0.25);
  if (!(s.plateau_fraction <= 1)) cfg.fail("plateau_fraction", "expected a fraction in (0, 1]");
  s.max_chain_length = static_cast<std::size_t>(cfg.non_negative_integer("max_chain_length", 0));
  return s;
}

// ---- the stage ------------------------------------------------------------------------------------

DipolarChainAnalysis::DipolarChainAnalysis(DipolarClusterSettings settings, std::string config_file)
    : s_(std::move(settings)), config_file_(std::move(config_file)) {
  if (!(s_.rule.bu_max < 0)) throw InputError(config_file_, "bu_max", "the bond threshold must be negative");
  if (!(s_.rule.gamma > 0)) throw InputError(config_file_, "gamma", "the dipolar coupling must be positive");
  if (!(s_.rule.field.norm() > 0)) throw InputError(config_file_, "field_direction", "expected a non-zero direction");
  s_.rule.field.normalize();
  for (double t1 : s_.transition_times) transitions_.push_back({t1, "given", kNaN, kNaN, 0, {}});
}

std::size_t DipolarChainAnalysis::size_class(std::size_t l) const {
  return s_.max_chain_length > 0 ? std::min(l, s_.max_chain_length) : l;
}

std::vector<std::vector<std::size_t>> DipolarChainAnalysis::cluster_sizes(const Trajectory& t,
                                                                         const std::vector<std::size_t>& members,
                                                                         const std::vector<std::size_t>& frames) const {
  std::vector<std::vector<std::size_t>> out;
  std::vector<Vec3> r(members.size());
  for (std::size_t f : frames) {
    for (std::size_t m = 0; m < members.size(); ++m) r[m] = t.pos(f, members[m]);
    out.push_back(dipolar_clusters(r, Box(t.box_edges(f)), s_.rule).size_of_each());
  }
  return out;
}

std::vector<std::pair<std::size_t, std::size_t>> DipolarChainAnalysis::transition_frames(const Trajectory& t, double t1, const std::string& key) const {
  const auto& time = t.time;
  auto nearest = [&](double x) {
    const auto it = std::lower_bound(time.begin(), time.end(), x);
    std::size_t k = static_cast<std::size_t>(it - time.begin());
    if (k == time.size()) return time.size() - 1;
    if (k > 0 && x - time[k - 1] < time[k] - x) --k;
    return k;
  };
  std::vector<std::size_t> origins;
  for (std::size_t f = 0; f < time.size(); ++f)
    if (std::abs(time[f] - t1) <= s_.transition_window * t1) origins.push_back(f);
  const std::size_t n1 = nearest(t1);
  if (std::find(origins.begin(), origins.end(), n1) == origins.end()) origins.push_back(n1);
  std::sort(origins.begin(), origins.end());
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t f1 : origins) {
    const double target = time[f1] + s_.transition_lag;
    const std::size_t f2 = nearest(target);
    if (f2 > f1 && std::abs(time[f2] - target) <= s_.lag_tolerance * s_.transition_lag) pairs.emplace_back(f1, f2);
  }
  if (pairs.empty()) {
    std::ostringstream o;
    o << "no pair of frames (t_1, t_1 + " << s_.transition_lag << ") within a lag tolerance of " << s_.lag_tolerance * 100
      << "% near t_1 = " << t1 << " in " << t.path << " (its frames nearest t_1 are at " << time[n1]
      << (n1 + 1 < time.size() ? ", " + number_text(time[n1 + 1]) : std::string()) << "; frames span [" << time.front() << ", "
      << time.back() << "])";
    throw InputError(config_file_, key, o.str());
  }
  return pairs;
}

void DipolarChainAnalysis::count_transitions(const Trajectory& t, const std::vector<std::size_t>& members, TransitionCounts& tc,
                                             const std::function<const std::vector<std::size_t>&(std::size_t)>& sizes_at) const {
  std::map<std::pair<std::size_t, std::size_t>, double> counts;
  const std::string key = tc.source == "given" ? "transition_times" : "transition_at_x2_maximum";
  for (const auto& [f1, f2] : transition_frames(t, tc.t1, key)) {
    const auto& a = sizes_at(f1);
    const auto& b = sizes_at(f2);
    for (std::size_t m = 0; m < members.size(); ++m) counts[{size_class(a[m]), size_class(b[m])}] += 1.0;  // per cube
    tc.window_min = std::isnan(tc.window_min) ? t.time[f1] : std::min(tc.window_min, t.time[f1]);
    tc.window_max = std::isnan(tc.window_max) ? t.time[f1] : std::max(tc.window_max, t.time[f1]);
    ++tc.frame_pairs;
  }
  tc.per_replica.push_back(std::move(counts));
}

void DipolarChainAnalysis::accumulate(const Trajectory& t, int species_index) {
  const std::vector<std::size_t> members = t.members(species_index);
  if (members.empty()) throw InputError(t.path, "", "no particles of the selected species");
  cubes_ = members.size();
  std::vector<std::size_t> frames(t.frames);
  for (std::size_t f = 0; f < t.frames; ++f) frames[f] = f;
  const auto sizes = cluster_sizes(t, members, frames);

  Replica rep;
  rep.time = t.time;
  for (std::size_t f = 0; f < t.frames; ++f) {
    // N(l) = (cubes in clusters of size l) / l, exactly
    std::vector<std::size_t> cubes_in(1, 0);
    for (std::size_t m = 0; m < members.size(); ++m) {
      const std::size_t l = sizes[f][m];
      if (cubes_in.size() < l) cubes_in.resize(l, 0);
      ++cubes_in[l - 1];
    }
    largest_ = std::max(largest_, cubes_in.size());
    std::vector<double> exact(cubes_in.size()), lumped(size_class(cubes_in.size()), 0.0);
    for (std::size_t k = 0; k < cubes_in.size(); ++k) {
      exact[k] = static_cast<double>(cubes_in[k] / (k + 1));
      lumped[size_class(k + 1) - 1] += exact[k];
    }
    const ChainStatistics cs = chain_statistics(exact, static_cast<double>(cubes_));
    rep.stats.push_back({cs.chain_fraction, cs.mean_length, cs.weight_mean_length});
    rep.counts.push_back(std::move(lumped));
  }
  replicas_.push_back(std::move(rep));
  for (auto& tc : transitions_)
    if (tc.source == "given") count_transitions(t, members, tc, [&](std::size_t f) -> const std::vector<std::size_t>& { return sizes[f]; });
}

void DipolarChainAnalysis::accumulate_transitions(const Trajectory& t, int species_index, double t1, const std::string& source) {
  auto it = std::find_if(transitions_.begin(), transitions_.end(), [&](const TransitionCounts& c) { return c.source == source; });
  if (it == transitions_.end()) {
    transitions_.push_back({t1, source, kNaN, kNaN, 0, {}});
    it = transitions_.end() - 1;
  }
  const std::vector<std::size_t> members = t.members(species_index);
  const auto pairs = transition_frames(t, t1, "transition_at_x2_maximum");
  std::vector<std::size_t> frames;
  for (const auto& [a, b] : pairs) frames.insert(frames.end(), {a, b});
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  const auto sizes = cluster_sizes(t, members, frames);
  for (const auto& s : sizes)
    for (std::size_t l : s) largest_ = std::max(largest_, l);
  count_transitions(t, members, *it, [&](std::size_t f) -> const std::vector<std::size_t>& {
    return sizes[static_cast<std::size_t>(std::lower_bound(frames.begin(), frames.end(), f) - frames.begin())];
  });
}

std::vector<double> DipolarChainAnalysis::common_grid() const {
  std::vector<std::vector<double>> times;
  for (const auto& r : replicas_) times.push_back(r.time);
  return mean_curve(times);
}

namespace {

/// y(t) of one replica at the grid times, linear between its frames, the end values beyond them.
double interpolate(const std::vector<double>& t, const std::vector<double>& y, double x) {
  if (x <= t.front()) return y.front();
  if (x >= t.back()) return y.back();
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), x) - t.begin());
  const double a = (x - t[k - 1]) / (t[k] - t[k - 1]);
  if (a == 0) return y[k - 1];
  return (1 - a) * y[k - 1] + a * y[k];
}

std::vector<double> on_grid(const std::vector<double>& t, const std::vector<double>& y, const std::vector<double>& grid) {
  std::vector<double> out(grid.size());
  for (std::size_t f = 0; f < grid.size(); ++f) out[f] = interpolate(t, y, grid[f]);
  return out;
}

/// Response time (spec 50 E4, Decision): first time at which X_c reaches 95% of the plateau,
/// linearly interpolated between the frames that straddle it.
double response_time(const std::vector<double>& grid, const std::vector<double>& xc, double plateau) {
  if (!(plateau > 0)) return kNaN;
  const double target = 0.95 * plateau;
  for (std::size_t f = 0; f < xc.size(); ++f) {
    if (!(xc[f] >= target)) continue;
    if (f == 0) return grid[0];
    const double a = (target - xc[f - 1]) / (xc[f] - xc[f - 1]);
    return grid[f - 1] + a * (grid[f] - grid[f - 1]);
  }
  return kNaN;
}

double window_mean(const std::vector<double>& y, std::size_t first) {
  double s = 0, n = 0;
  for (std::size_t f = first; f < y.size(); ++f)
    if (!std::isnan(y[f])) { s += y[f]; n += 1; }
  return n > 0 ? s / n : kNaN;
}

}  // namespace

double DipolarChainAnalysis::time_of_x2_maximum() const {
  const auto grid = common_grid();
  std::vector<std::vector<double>> curves;
  for (const auto& r : replicas_) {
    std::vector<double> x2(r.time.size());
    for (std::size_t f = 0; f < r.time.size(); ++f) x2[f] = (r.counts[f].size() > 1 ? r.counts[f][1] : 0.0) / static_cast<double>(cubes_);
    curves.push_back(on_grid(r.time, x2, grid));
  }
  const auto mean = mean_curve(curves);
  if (mean.empty()) return kNaN;
  return grid[static_cast<std::size_t>(std::max_element(mean.begin(), mean.end()) - mean.begin())];
}

DipolarChainResult DipolarChainAnalysis::compute() const {
  DipolarChainResult r;
  r.replicas = replicas_.size();
  r.cubes = cubes_;
  if (replicas_.empty()) return r;
  r.time = common_grid();
  const std::size_t F = r.time.size();
  const std::size_t L = s_.max_chain_length > 0 ? s_.max_chain_length : largest_;
  r.sizes = L;

  // time series on the common grid, one sample per replica
  CurveSamples x, xc, ln, lw;
  std::vector<std::vector<double>> x_rep;  // [replica] → [frame × L]
  for (const auto& rep : replicas_) {
    std::vector<double> flat(F * L, 0.0);
    for (std::size_t l = 0; l < L; ++l) {
      std::vector<double> y(rep.time.size());
      for (std::size_t f = 0; f < y.size(); ++f) y[f] = (l < rep.counts[f].size() ? rep.counts[f][l] : 0.0) / static_cast<double>(cubes_);
      const auto g = on_grid(rep.time, y, r.time);
      for (std::size_t f = 0; f < F; ++f) flat[f * L + l] = g[f];
    }
    x.add(flat);
    x_rep.push_back(std::move(flat));
    std::vector<double> a(rep.time.size()), b(a.size()), c(a.size());
    for (std::size_t f = 0; f < a.size(); ++f) { a[f] = rep.stats[f][0]; b[f] = rep.stats[f][1]; c[f] = rep.stats[f][2]; }
    xc.add(on_grid(rep.time, a, r.time));
    ln.add(on_grid(rep.time, b, r.time));
    lw.add(on_grid(rep.time, c, r.time));
  }
  r.x = x.mean();
  r.x_error = x.standard_error();
  r.chain_fraction = xc.mean();
  r.chain_fraction_error = xc.standard_error();
  r.mean_length = ln.mean();
  r.mean_length_error = ln.standard_error();
  r.weight_mean_length = lw.mean();
  r.weight_mean_length_error = lw.standard_error();

  // plateau: the last plateau_fraction of the run (in time)
  const double t_start = r.time.front(), t_end = r.time.back();
  r.plateau_t_min = t_end - s_.plateau_fraction * (t_end - t_start);
  std::size_t first = 0;
  while (first + 1 < F && r.time[first] < r.plateau_t_min - 1e-12 * std::abs(t_end)) ++first;
  r.plateau = jackknife(xc, [&](const std::vector<double>& m) { return window_mean(m, first); });
  r.response_time = jackknife(xc, [&](const std::vector<double>& m) { return response_time(r.time, m, window_mean(m, first)); });

  // stationary X(l): per replica the mean over the plateau frames (10 blocks of them for one replica)
  CurveSamples stationary;
  const std::size_t plateau_frames = F - first;
  const std::size_t blocks = replicas_.size() > 1 ? 1 : std::min<std::size_t>(10, plateau_frames);
  for (const auto& flat : x_rep)
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::size_t lo = first + b * plateau_frames / blocks, hi = first + (b + 1) * plateau_frames / blocks;
      std::vector<double> m(L, 0.0);
      for (std::size_t f = lo; f < hi; ++f)
        for (std::size_t l = 0; l < L; ++l) m[l] += flat[f * L + l] / static_cast<double>(hi - lo);
      // a lumped last class (sizes ≥ max_chain_length) does not follow X_eq(l): leave it out
      if (s_.max_chain_length > 0 && largest_ > s_.max_chain_length) m.pop_back();
      stationary.add(std::move(m));
    }
  r.wertheim = fit_wertheim(stationary);
  if (blocks > 1) r.wertheim.method += " (one replica: samples are " + std::to_string(blocks) + " blocks of plateau frames)";

  // transition matrices
  for (const auto& tc : transitions_) {
    TransitionMatrix m;
    m.t1 = tc.t1;
    m.source = tc.source;
    m.window_min = tc.window_min;
    m.window_max = tc.window_max;
    m.frame_pairs = tc.frame_pairs;
    m.sizes = L;
    CurveSamples counts;
    m.row_count.assign(L, 0.0);
    for (const auto& rc : tc.per_replica) {
      std::vector<double> c(L * L, 0.0);
      for (const auto& [key, n] : rc) {
        c[(key.first - 1) * L + (key.second - 1)] += n;
        m.row_count[key.first - 1] += n;
      }
      counts.add(std::move(c));
    }
    const auto normalise_rows = [L](const std::vector<double>& c) {
      std::vector<double> p(L * L, kNaN);
      for (std::size_t a = 0; a < L; ++a) {
        double row = 0;
        for (std::size_t b = 0; b < L; ++b) row += c[a * L + b];
        if (row > 0)
          for (std::size_t b = 0; b < L; ++b) p[a * L + b] = c[a * L + b] / row;
      }
      return p;
    };
    const CurveEstimate est = jackknife_curve(counts, normalise_rows);
    m.probability = est.value;
    m.error = est.error;
    for (std::size_t k = 0; k < m.probability.size(); ++k)
      if (!(m.probability[k] >= kBlankProbability)) m.probability[k] = m.error[k] = kNaN;
    r.transitions.push_back(std::move(m));
  }
  return r;
}

}  // namespace anisodyn::analysis
