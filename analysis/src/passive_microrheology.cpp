#include "anisodyn/analysis/passive_microrheology.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "anisodyn/analysis/fitting.hpp"
#include "anisodyn/analysis/polygamma.hpp"
#include "anisodyn/core/error.hpp"

namespace anisodyn::analysis {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = std::numbers::pi;

/// Lags within the fit window [t_min, t_max] (relative tolerance as in MsdAnalysis).
std::vector<std::size_t> window_indices(const std::vector<double>& t, double t_min, double t_max) {
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k] >= t_min * (1 - 1e-9) && t[k] <= t_max * (1 + 1e-9)) out.push_back(k);
  return out;
}

/// D_long = slope of the 3-D MSD over the window / 6 (spec 50 A3), as MsdAnalysis computes it.
double long_time_diffusion(const std::vector<double>& t, const std::vector<double>& msd, const std::vector<std::size_t>& window) {
  if (window.size() < 2) return kNaN;
  std::vector<double> x, y;
  for (std::size_t k : window) { x.push_back(t[k]); y.push_back(msd[k]); }
  return fit_line(x, y).slope / 6.0;
}

/// Number of leading lags with t ≤ t_last (at least 2, else InputError).
std::size_t lags_up_to(const std::vector<double>& t, double t_last, const std::string& config_file) {
  std::size_t n = 0;
  while (n < t.size() && t[n] <= t_last * (1 + 1e-9)) ++n;
  if (n < 2) throw InputError(config_file, "evans_t_max", "expected at least 2 MSD lags up to t_N = " + std::to_string(t_last));
  return n;
}

}  // namespace

namespace {

/// s·L{MSD}(s) at s = iω divided by MSD(1/ω), for MSD(t) = MSD(1/ω) exp(α u + β u²/2), u = ln(ωt):
/// Γ(1 + α) e^{−iπα/2} for the power law (first order); the second order adds the curvature to first
/// order in β, (β/2) ∂²_α[Γ(1 + α)(iω/ω)^{−α}] = (β/2) Γ(1 + α) e^{−iπα/2} [(ψ(1 + α) − iπ/2)² + ψ₁(1 + α)],
/// because ∫ e^{−st} t^α ln²(ωt) dt is the second α-derivative of ∫ e^{−st} t^α dt.
std::complex<double> gser_transform_factor(double alpha, double curvature, GserOrder order) {
  const std::complex<double> power_law = std::tgamma(1.0 + alpha) * std::exp(std::complex<double>(0.0, -kPi * alpha / 2.0));
  if (order == GserOrder::First) return power_law;
  const std::complex<double> k1 = digamma(1.0 + alpha) - std::complex<double>(0.0, kPi / 2.0);
  return power_law * (1.0 + 0.5 * curvature * (k1 * k1 + trigamma(1.0 + alpha)));
}

}  // namespace

Moduli mason_moduli(const std::vector<double>& t, const std::vector<double>& msd, double radius, double kT,
                    double half_width_decades, GserOrder order) {
  Moduli m;
  const std::size_t n = t.size();
  m.omega.assign(n, kNaN);
  m.storage.assign(n, kNaN);
  m.loss.assign(n, kNaN);
  m.alpha.assign(n, kNaN);
  m.curvature.assign(n, kNaN);
  for (std::size_t k = 0; k < n; ++k) {
    if (!(t[k] > 0)) continue;
    m.omega[k] = 1.0 / t[k];
    LogQuadratic fit;
    if (!(msd[k] > 0) || !local_log_quadratic(t, msd, t[k], half_width_decades, fit)) continue;
    // G* = k_BT / (π a · s L{MSD}(s)) at s = iω; the measured MSD at the grid point t = 1/ω, the local
    // fit supplies only the log derivatives.
    const std::complex<double> g = kT / (kPi * radius * msd[k] * gser_transform_factor(fit.slope, fit.curvature, order));
    m.alpha[k] = fit.slope;
    m.curvature[k] = fit.curvature;
    m.storage[k] = g.real();
    m.loss[k] = g.imag();
  }
  return m;
}

Moduli evans_moduli(const std::vector<double>& t, const std::vector<double>& msd, double radius, double kT, double d_long,
                    const std::vector<double>& omega) {
  Moduli m;
  m.omega = omega;
  m.storage.assign(omega.size(), kNaN);
  m.loss.assign(omega.size(), kNaN);
  const std::size_t n = t.size();
  if (n == 0 || !(t[0] > 0) || std::isnan(d_long)) return m;
  const double scale = kPi * radius / kT;  // J = scale · MSD
  const double inv_eta_inf = scale * 6.0 * d_long;
  for (std::size_t w = 0; w < omega.size(); ++w) {
    const double om = omega[w];
    if (!(om > 0)) continue;
    auto phase = [om](double time) { return std::exp(std::complex<double>(0.0, -om * time)); };
    // J(0) = 0: the first segment is the ramp from the origin to (t_1, J_1)
    std::complex<double> sum = (1.0 - phase(t[0])) * (scale * msd[0] / t[0]);
    sum += inv_eta_inf * phase(t[n - 1]);
    bool finite = std::isfinite(msd[0]);
    for (std::size_t k = 1; k < n; ++k) {
      const double slope = scale * (msd[k] - msd[k - 1]) / (t[k] - t[k - 1]);
      finite = finite && std::isfinite(slope);
      sum += slope * (phase(t[k - 1]) - phase(t[k]));
    }
    if (!finite || std::abs(sum) == 0.0) continue;
    const std::complex<double> g = std::complex<double>(0.0, om) / sum;
    m.storage[w] = g.real();
    m.loss[w] = g.imag();
  }
  return m;
}

PassiveMicrorheologySettings parse_passive_microrheology_settings(tool::ConfigNode& cfg) {
  PassiveMicrorheologySettings s;
  s.species = cfg.string("species");
  if (cfg.has("radius") && cfg.has("tracer_diameter")) cfg.fail("tracer_diameter", "expected either 'radius' or 'tracer_diameter', not both");
  if (cfg.has("radius")) s.radius = cfg.positive("radius");
  if (cfg.has("tracer_diameter")) s.radius = 0.5 * cfg.positive("tracer_diameter");
  s.kT = cfg.positive("kT", 1.0);
  s.half_width_decades = cfg.positive("alpha_fit_decades", kMasonHalfWidthDecades);
  if (cfg.has("evans_t_max")) s.evans_t_max = cfg.positive("evans_t_max");
  s.msd.species = s.species;
  s.msd.lags_per_decade = cfg.non_negative("lags_per_decade", s.msd.lags_per_decade);
  s.msd.max_origins = static_cast<std::size_t>(cfg.non_negative_integer("max_origins", 0));
  s.msd.fit_window = parse_lag_window(cfg, "fit");
  return s;
}

double resolve_tracer_radius(const PassiveMicrorheologySettings& settings, const SpeciesTable& table,
                             const std::string& config_file) {
  if (settings.radius > 0) return settings.radius;
  for (const auto& sp : table)
    if (sp.name == settings.species) {
      if (sp.shape.kind == ShapeKind::Sphere && sp.shape.diameter > 0) return 0.5 * sp.shape.diameter;
      throw InputError(config_file, "radius",
                       "expected the tracer radius ('radius' or 'tracer_diameter'): species '" + settings.species + "' is not a sphere");
    }
  throw InputError(config_file, "species", "unknown tracer species '" + settings.species + "'");
}

PassiveMicrorheology::PassiveMicrorheology(PassiveMicrorheologySettings settings, std::size_t replicas, std::string config_file)
    : s_(std::move(settings)), config_file_(std::move(config_file)), msd_(s_.msd, replicas, config_file_) {
  if (s_.species.empty()) throw InputError(config_file_, "species", "expected the tracer species");
  if (!(s_.radius > 0)) throw InputError(config_file_, "radius", "expected a positive tracer radius");
  if (!(s_.kT > 0)) throw InputError(config_file_, "kT", "expected a positive k_BT");
}

void PassiveMicrorheology::accumulate(const Trajectory& t) {
  const int species = t.species_index(s_.species, config_file_, "species");
  const std::vector<std::size_t> tracers = t.members(species);
  if (tracers.empty()) throw InputError(config_file_, "species", "tracer species '" + s_.species + "' has no particles in " + t.path);
  if (tracers_ == 0) tracers_ = tracers.size();
  msd_.accumulate(t, species);
}

PassiveResult PassiveMicrorheology::compute() const {
  PassiveResult r;
  const MsdResult m = msd_.compute();
  const MsdComponent& tot = m.component("tot");
  r.time = m.lag;
  r.msd = tot.msd;
  r.msd_error = tot.msd_error;
  r.d_long = tot.diffusion;
  r.fit_t_min = m.fit_t_min;
  r.fit_t_max = m.fit_t_max;
  r.fit_mean_beta = m.fit_mean_beta;
  r.fit_window_automatic = m.fit_window_automatic;
  r.radius = s_.radius;
  r.kT = s_.kT;
  const CurveSamples samples = msd_.samples_of("tot");
  r.samples = samples.count();
  r.tracers = tracers_;
  const std::size_t n = r.time.size();
  const auto window = window_indices(r.time, r.fit_t_min, r.fit_t_max);
  std::vector<double> omega(n, kNaN);
  for (std::size_t k = 0; k < n; ++k)
    if (r.time[k] > 0) omega[k] = 1.0 / r.time[k];

  // Every modulus as one function of an MSD curve, for the value and its jackknife (D_long refitted).
  // Evans: the lags up to the end of the D_long window (or evans_t_max); beyond it J continues with the
  // slope η_∞⁻¹ — the meaning of the e^{−iωt_N} term — instead of summing the noisy increments of
  // lags with few independent origins, which would add their noise to every ω.
  const std::size_t evans_n = lags_up_to(r.time, s_.evans_t_max ? *s_.evans_t_max : r.fit_t_max, config_file_);
  r.evans_t_max = r.time[evans_n - 1];
  const std::vector<double> evans_t(r.time.begin(), r.time.begin() + static_cast<std::ptrdiff_t>(evans_n));
  auto moduli_of = [&](const std::vector<double>& msd, Moduli& mason, Moduli& mason2, Moduli& evans) {
    mason = mason_moduli(r.time, msd, s_.radius, s_.kT, s_.half_width_decades, GserOrder::First);
    mason2 = mason_moduli(r.time, msd, s_.radius, s_.kT, s_.half_width_decades, GserOrder::Second);
    const std::vector<double> evans_msd(msd.begin(), msd.begin() + static_cast<std::ptrdiff_t>(evans_n));
    evans = evans_moduli(evans_t, evans_msd, s_.radius, s_.kT, long_time_diffusion(r.time, msd, window), omega);
  };
  moduli_of(r.msd, r.mason, r.mason2, r.evans);
  const auto stacked = jackknife_curve(samples, [&](const std::vector<double>& msd) {
    Moduli a, a2, b;
    moduli_of(msd, a, a2, b);
    std::vector<double> out;
    for (const auto* v : {&a.storage, &a.loss, &a2.storage, &a2.loss, &b.storage, &b.loss, &a2.alpha, &a2.curvature})
      out.insert(out.end(), v->begin(), v->end());
    return out;
  });
  auto part = [&](std::size_t p) {
    if (stacked.error.size() < (p + 1) * n) return std::vector<double>(n, kNaN);
    return std::vector<double>(stacked.error.begin() + static_cast<std::ptrdiff_t>(p * n),
                               stacked.error.begin() + static_cast<std::ptrdiff_t>((p + 1) * n));
  };
  r.mason_error = Moduli{omega, part(0), part(1), part(6), part(7)};
  r.mason2_error = Moduli{omega, part(2), part(3), part(6), part(7)};
  r.evans_error = Moduli{omega, part(4), part(5), {}, {}};
  return r;
}

}  // namespace anisodyn::analysis
