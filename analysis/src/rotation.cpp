#include "anisodyn/analysis/rotation.hpp"
#include "anisodyn/geometry/body_axes.hpp"

#include <cmath>
#include <limits>

#include "anisodyn/analysis/fitting.hpp"
#include "anisodyn/analysis/rotation_vectors.hpp"

namespace anisodyn::analysis {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

int axis_from_name(tool::ConfigNode& cfg, const std::string& name, const std::string& key) {
  const int k = body_axis_index(name);
  if (k < 0) cfg.fail(key, "expected body axes from T, W, L (or x, y, z)");
  return k;
}
}  // namespace

RotationSettings parse_rotation_settings(tool::ConfigNode& cfg) {
  RotationSettings s;
  s.species = cfg.string("species", "");
  if (cfg.has("axes")) {
    s.axes.clear();
    for (const auto& a : cfg.strings("axes")) s.axes.push_back(axis_from_name(cfg, a, "axes"));
    if (s.axes.empty()) cfg.fail("axes", "expected at least one body axis");
  }
  s.lags_per_decade = cfg.non_negative("lags_per_decade", s.lags_per_decade);
  s.max_origins = static_cast<std::size_t>(cfg.non_negative_integer("max_origins", 0));
  s.fit_window = parse_lag_window(cfg, "fit");
  s.correlation_floor = cfg.positive("correlation_floor", s.correlation_floor);
  s.correlation_ceiling = cfg.positive("correlation_ceiling", s.correlation_ceiling);
  if (!(s.correlation_ceiling <= 1.0)) cfg.fail("correlation_ceiling", "expected a value <= 1 (C_n starts at 1)");
  if (!(s.correlation_ceiling > s.correlation_floor)) cfg.fail("correlation_ceiling", "expected a value above correlation_floor");
  return s;
}

RotationAnalysis::RotationAnalysis(RotationSettings settings, std::size_t replicas)
    : s_(std::move(settings)), replicas_(replicas) {
  violations_.assign(s_.axes.size(), 0);
  intervals_.assign(s_.axes.size(), 0);
  exact_.assign(s_.axes.size(), false);
}

void RotationAnalysis::accumulate(const Trajectory& t, int species_index) {
  if (seen_ == 0) {
    grid_ = make_lag_grid(t.time, s_.lags_per_decade, s_.max_origins);
  }
  const auto members = t.members(species_index);
  const std::size_t nc = grid_.classes.size(), na = s_.axes.size(), F = t.frames, N = t.particles;
  const std::size_t blocks = error_blocks(replicas_);
  std::vector<std::vector<double>> sums(blocks, std::vector<double>(3 * na * nc, 0.0));
  std::vector<std::vector<double>> counts(blocks, std::vector<double>(nc, 0.0));
  for (std::size_t k = 0; k < na; ++k) {
    const int axis = s_.axes[k];
    const RotationVectorPath path = rotation_vector_path(t, axis);
    exact_[k] = path.exact;
    violations_[k] += path.violations;
    intervals_[k] += path.intervals;
    std::vector<double> u(3 * F * N);
    for (std::size_t f = 0; f < F; ++f)
      for (std::size_t i : members) {
        const Vec3 a = t.axis(f, i, axis);
        for (int d = 0; d < 3; ++d) u[3 * (f * N + i) + d] = a[d];
      }
    for (std::size_t c = 0; c < nc; ++c)
      for (const auto& [i0, j0] : grid_.classes[c].pairs) {
        const std::size_t b = origin_block(i0, F, blocks);
        double msad = 0, p1 = 0, p2 = 0;
        for (std::size_t i : members) {
          const double* a = &path.phi[3 * (i0 * N + i)];
          const double* z = &path.phi[3 * (j0 * N + i)];
          msad += (z[0] - a[0]) * (z[0] - a[0]) + (z[1] - a[1]) * (z[1] - a[1]) + (z[2] - a[2]) * (z[2] - a[2]);
          const double* ua = &u[3 * (i0 * N + i)];
          const double* ub = &u[3 * (j0 * N + i)];
          const double x = ua[0] * ub[0] + ua[1] * ub[1] + ua[2] * ub[2];
          p1 += x;
          p2 += 1.5 * x * x - 0.5;
        }
        sums[b][(3 * k) * nc + c] += msad;
        sums[b][(3 * k + 1) * nc + c] += p1;
        sums[b][(3 * k + 2) * nc + c] += p2;
        if (k == 0) counts[b][c] += static_cast<double>(members.size());
      }
  }
  lags_.add(grid_, t.time);
  for (std::size_t b = 0; b < blocks; ++b) {
    std::vector<double> sample(3 * na * nc, kNaN);
    for (std::size_t m = 0; m < 3 * na; ++m)
      for (std::size_t c = 0; c < nc; ++c)
        if (counts[b][c] > 0) sample[m * nc + c] = sums[b][m * nc + c] / counts[b][c];
    samples_.add(std::move(sample));
  }
  ++seen_;
}

RotationResult RotationAnalysis::compute() const {
  RotationResult r;
  const std::size_t nc = grid_.classes.size();
  r.lag = lags_.mean();
  r.samples = samples_.count();
  const auto mean = samples_.mean(), se = samples_.standard_error();
  auto slice = [nc](const std::vector<double>& v, std::size_t m) {
    return std::vector<double>(v.begin() + static_cast<std::ptrdiff_t>(m * nc), v.begin() + static_cast<std::ptrdiff_t>((m + 1) * nc));
  };
  if (s_.fit_window) {
    r.fit_t_min = s_.fit_window->first;
    r.fit_t_max = s_.fit_window->second;
  } else if (!r.lag.empty()) {
    r.fit_t_min = r.lag.front();
    r.fit_t_max = r.lag.back() / 20.0;
    if (r.fit_t_max <= r.fit_t_min) r.fit_t_max = r.lag.back();
  }
  for (std::size_t k = 0; k < s_.axes.size(); ++k) {
    AxisRotation a;
    a.axis = s_.axes[k];
    a.msad = slice(mean, 3 * k);
    a.msad_error = slice(se, 3 * k);
    a.c1 = slice(mean, 3 * k + 1);
    a.c1_error = slice(se, 3 * k + 1);
    a.c2 = slice(mean, 3 * k + 2);
    a.c2_error = slice(se, 3 * k + 2);
    a.exact_rotation_vectors = exact_[k];
    a.violations = violations_[k];
    a.intervals = intervals_[k];
    const double t0 = r.fit_t_min, t1 = r.fit_t_max;
    a.D_msad = jackknife(samples_, [&](const std::vector<double>& m) {
      std::vector<double> x, y;
      for (std::size_t c = 0; c < nc; ++c)
        if (r.lag[c] >= t0 * (1 - 1e-9) && r.lag[c] <= t1 * (1 + 1e-9)) { x.push_back(r.lag[c]); y.push_back(m[3 * k * nc + c]); }
      return x.size() >= 2 ? fit_line(x, y).slope / 4.0 : kNaN;
    });
    // ln C_n over the lags where the mean C_n is well above noise and past the short-time
    // transient: D_r = −slope / (n(n+1)). The window ends where C_n first falls below the floor:
    // later lags that come back above it are noise of the few long intervals (a sphere's C_1 of
    // 0.18 ± 0.03 at 560 τ after 0.24 at 36 τ, two runs of 1000 τ), not the decay.
    for (int n = 1; n <= 2; ++n) {
      const std::vector<double>& cn = n == 1 ? a.c1 : a.c2;
      std::vector<std::size_t> window;
      for (std::size_t c = 0; c < nc && cn[c] >= s_.correlation_floor; ++c)
        if (cn[c] < s_.correlation_ceiling) window.push_back(c);
      CorrelationFitWindow& used = n == 1 ? a.window_c1 : a.window_c2;
      used.lags = window.size();
      used.t_min = window.empty() ? kNaN : r.lag[window.front()];
      used.t_max = window.empty() ? kNaN : r.lag[window.back()];
      Estimate e = jackknife(samples_, [&](const std::vector<double>& m) {
        std::vector<double> x, y;
        for (std::size_t c : window) { x.push_back(r.lag[c]); y.push_back(m[(3 * k + static_cast<std::size_t>(n)) * nc + c]); }
        return x.size() >= 2 ? -fit_exponential(x, y).slope / (n * (n + 1)) : kNaN;
      });
      (n == 1 ? a.D_c1 : a.D_c2) = e;
    }
    r.axes.push_back(std::move(a));
  }
  return r;
}

}  // namespace anisodyn::analysis
