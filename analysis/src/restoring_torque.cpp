#include "anisodyn/analysis/restoring_torque.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "anisodyn/analysis/bd_caps.hpp"
#include "anisodyn/core/error.hpp"

namespace anisodyn::analysis {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::size_t kMoments = 4;  // C₁, β⟨(û×û₀)·T̄⟩, C₂, β⟨3x (û×û₀)·T̄⟩
constexpr std::size_t kCurves = 4;   // βT_r, D_r(φ, t), D_r⁽²⁾(φ, t), C₁^rec

/// Rod axes û (body L) of the species' members, [frame][particle][xyz].
std::vector<double> rod_axes(const Trajectory& t, const std::vector<std::size_t>& members) {
  std::vector<double> u(3 * t.frames * t.particles, 0.0);
  for (std::size_t f = 0; f < t.frames; ++f)
    for (std::size_t i : members) {
      const Vec3 a = t.axis(f, i, 2);
      for (int d = 0; d < 3; ++d) u[3 * (f * t.particles + i) + d] = a[d];
    }
  return u;
}

}  // namespace

RestoringTorqueSettings parse_restoring_torque_settings(tool::ConfigNode& cfg) {
  RestoringTorqueSettings s;
  s.species = cfg.string("species", "");
  s.lags_per_decade = cfg.non_negative("lags_per_decade", s.lags_per_decade);
  s.max_origins = static_cast<std::size_t>(cfg.non_negative_integer("max_origins", 0));
  s.plateau_window = parse_lag_window(cfg, "plateau");
  cfg.reject_unless(!s.plateau_window, "plateau_correlation", "with a plateau {t_min, t_max}: the window is given");
  if (auto c = cfg.optional_object("plateau_correlation")) {
    s.plateau_floor = c->positive("floor", s.plateau_floor);
    s.plateau_ceiling = c->positive("ceiling", s.plateau_ceiling);
    if (!(s.plateau_ceiling <= 1.0)) c->fail("ceiling", "expected a value <= 1 (C1 starts at 1)");
    if (!(s.plateau_ceiling > s.plateau_floor)) c->fail("ceiling", "expected a value above floor");
  }
  return s;
}

RestoringTorqueAnalysis::RestoringTorqueAnalysis(RestoringTorqueSettings settings, std::size_t replicas)
    : s_(std::move(settings)), replicas_(replicas) {}

void RestoringTorqueAnalysis::accumulate(const Trajectory& t, int species_index) {
  if (t.element_width(kSystematicTorque) != 3)
    throw InputError(t.path, std::string("/particles/all/") + kSystematicTorque + "/value", "expected 3 torque components per particle");
  if (seen_ == 0) grid_ = make_lag_grid(t.time, s_.lags_per_decade, s_.max_origins);
  const double beta = 1.0 / t.units.kT();
  const auto members = t.members(species_index);
  const std::vector<double> u = rod_axes(t, members);
  const std::size_t nc = grid_.classes.size(), F = t.frames, N = t.particles, blocks = error_blocks(replicas_);
  std::vector<std::vector<double>> sums(blocks, std::vector<double>(kMoments * nc, 0.0));
  std::vector<std::vector<double>> counts(blocks, std::vector<double>(nc, 0.0));
  for (std::size_t c = 0; c < nc; ++c)
    for (const auto& [i0, j0] : grid_.classes[c].pairs) {
      const std::size_t b = origin_block(i0, F, blocks);
      double p1 = 0, s1 = 0, p2 = 0, s2 = 0;
      for (std::size_t i : members) {
        const double* u0 = &u[3 * (i0 * N + i)];
        const double* ut = &u[3 * (j0 * N + i)];
        const double* T = t.element(kSystematicTorque, j0, i);  // T̄ at the later time
        const double x = u0[0] * ut[0] + u0[1] * ut[1] + u0[2] * ut[2];
        const double cross_torque = (ut[1] * u0[2] - ut[2] * u0[1]) * T[0] + (ut[2] * u0[0] - ut[0] * u0[2]) * T[1] +
                                    (ut[0] * u0[1] - ut[1] * u0[0]) * T[2];  // (û(t)×û(0))·T̄
        p1 += x;
        s1 += beta * cross_torque;
        p2 += 1.5 * x * x - 0.5;
        s2 += beta * 3.0 * x * cross_torque;  // P₂′(x) = 3x
      }
      for (std::size_t m = 0; m < kMoments; ++m) sums[b][m * nc + c] += m == 0 ? p1 : m == 1 ? s1 : m == 2 ? p2 : s2;
      counts[b][c] += static_cast<double>(members.size());
    }
  lags_.add(grid_, t.time);
  for (std::size_t b = 0; b < blocks; ++b) {
    std::vector<double> sample(kMoments * nc, kNaN);
    for (std::size_t m = 0; m < kMoments; ++m)
      for (std::size_t c = 0; c < nc; ++c)
        if (counts[b][c] > 0) sample[m * nc + c] = sums[b][m * nc + c] / counts[b][c];
    samples_.add(std::move(sample));
  }
  if (const auto capped = capped_torque_steps(t)) {
    capped_known_ = true;
    capped_torques_ += *capped;
  }
  ++seen_;
}

std::vector<double> RestoringTorqueAnalysis::derived_curves(const std::vector<double>& m, const std::vector<double>& lag, double free_dr) {
  const std::size_t nc = lag.size();
  std::vector<double> out(kCurves * nc, kNaN);
  double integral = 0, previous_t = 0, previous_d = free_dr;  // D_r(φ, 0) = D_r: û(0)×û(0) = 0
  for (std::size_t c = 0; c < nc; ++c) {
    const double c1 = m[c], s1 = m[nc + c], c2 = m[2 * nc + c], s2 = m[3 * nc + c];
    const double beta_torque = s1 / c1;
    const double d1 = free_dr * (1.0 - 0.5 * beta_torque);
    out[c] = beta_torque;
    out[nc + c] = d1;
    out[2 * nc + c] = free_dr * (1.0 - s2 / (6.0 * c2));
    integral += 0.5 * (previous_d + d1) * (lag[c] - previous_t);
    out[3 * nc + c] = std::exp(-2.0 * integral);
    previous_t = lag[c];
    previous_d = d1;
  }
  return out;
}

std::vector<std::size_t> RestoringTorqueAnalysis::plateau_lags(const std::vector<double>& lag, const std::vector<double>& c1) const {
  std::vector<std::size_t> window;
  for (std::size_t c = 0; c < lag.size(); ++c) {
    const bool inside = s_.plateau_window
                            ? lag[c] >= s_.plateau_window->first * (1 - 1e-9) && lag[c] <= s_.plateau_window->second * (1 + 1e-9)
                            : c1[c] >= s_.plateau_floor && c1[c] <= s_.plateau_ceiling;
    if (inside) window.push_back(c);
  }
  return window;
}

RestoringTorqueResult RestoringTorqueAnalysis::compute(double free_dr) const {
  RestoringTorqueResult r;
  r.lag = lags_.mean();
  r.free_dr = free_dr;
  r.samples = samples_.count();
  r.capped_known = capped_known_;
  r.capped_torques = capped_torques_;
  const std::size_t nc = r.lag.size();
  const auto mean = samples_.mean(), se = samples_.standard_error();
  auto slice = [nc](const std::vector<double>& v, std::size_t k) {
    return std::vector<double>(v.begin() + static_cast<std::ptrdiff_t>(k * nc), v.begin() + static_cast<std::ptrdiff_t>((k + 1) * nc));
  };
  r.c1 = slice(mean, 0);
  r.c1_error = slice(se, 0);
  r.c2 = slice(mean, 2);
  r.c2_error = slice(se, 2);
  const auto curves = [&](const std::vector<double>& m) { return derived_curves(m, r.lag, free_dr); };
  const CurveEstimate derived = jackknife_curve(samples_, curves);
  r.beta_torque = slice(derived.value, 0);
  r.beta_torque_error = slice(derived.error, 0);
  r.dr1 = slice(derived.value, 1);
  r.dr1_error = slice(derived.error, 1);
  r.dr2 = slice(derived.value, 2);
  r.dr2_error = slice(derived.error, 2);
  r.c1_reconstructed = slice(derived.value, 3);
  r.c1_reconstructed_error = slice(derived.error, 3);

  const std::vector<std::size_t> window = plateau_lags(r.lag, r.c1);
  r.plateau_lags = window.size();
  r.plateau_t_min = window.empty() ? kNaN : r.lag[window.front()];
  r.plateau_t_max = window.empty() ? kNaN : r.lag[window.back()];
  // The plateau value: the mean of the curve over the plateau's lags weighted by 1/error² (the
  // errors of the whole sample, so the weights are fixed while the mean is jackknifed). The curves
  // divide by C_n, so their noise grows tenfold across a window where C_1 falls from 0.5 to 0.05; an
  // unweighted mean let the last, noisiest lags decide it. Where a lag has no positive finite error
  // (free rods: the curve is exact), the lags count equally.
  auto plateau_weights = [&](std::size_t curve) {
    std::vector<double> w(window.size(), 1.0);
    for (std::size_t k = 0; k < window.size(); ++k) {
      const double e = derived.error[curve * nc + window[k]];
      if (!(std::isfinite(e) && e > 0)) return std::vector<double>(window.size(), 1.0);
      w[k] = 1.0 / (e * e);
    }
    return w;
  };
  auto plateau_of = [&](std::size_t curve) {
    const std::vector<double> w = plateau_weights(curve);
    return jackknife(samples_, [&](const std::vector<double>& m) {
      if (window.empty()) return kNaN;
      const std::vector<double> d = curves(m);
      double sum = 0, weight = 0;
      for (std::size_t k = 0; k < window.size(); ++k) {
        sum += w[k] * d[curve * nc + window[k]];
        weight += w[k];
      }
      return sum / weight;
    });
  };
  r.beta_torque_plateau = plateau_of(0);
  r.dr1_plateau = plateau_of(1);
  r.dr2_plateau = plateau_of(2);
  return r;
}

}  // namespace anisodyn::analysis
