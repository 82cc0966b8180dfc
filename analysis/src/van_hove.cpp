#include "anisodyn/analysis/van_hove.hpp"
#include "anisodyn/geometry/body_axes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "anisodyn/analysis/rotation_vectors.hpp"

namespace anisodyn::analysis {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

int component_dimension(const std::string& c) { return c == "tot" ? 3 : c == "perp" ? 2 : 1; }

/// ∫ v_d over [r, r + w]: the measure of the bin in the normalisation of spec 50 A6 / B2.
double bin_measure(int d, double r, double w) {
  if (d == 1) return 2.0 * w;
  if (d == 2) return M_PI * ((r + w) * (r + w) - r * r);
  return 4.0 * M_PI / 3.0 * ((r + w) * (r + w) * (r + w) - r * r * r);
}

/// Cumulative radial distribution P(|ρ| < r) of an isotropic d-dimensional Gaussian with ⟨ρ²⟩ = m2.
double gaussian_radial_cdf(int d, double r, double m2) {
  const double x = r / std::sqrt(2.0 * m2 / d);
  if (d == 1) return std::erf(x);
  if (d == 2) return 1.0 - std::exp(-x * x);
  return std::erf(x) - 2.0 / std::sqrt(M_PI) * x * std::exp(-x * x);
}

double squared_component(const std::string& c, const Vec3& d, const Vec3& e) {
  if (c == "tot") return d.squaredNorm();
  if (c == "x") return d.x() * d.x();
  if (c == "y") return d.y() * d.y();
  if (c == "z") return d.z() * d.z();
  const double p = d.dot(e);
  return c == "par" ? p * p : d.squaredNorm() - p * p;
}
}  // namespace

VanHoveSettings parse_van_hove_settings(tool::ConfigNode& cfg) {
  VanHoveSettings s;
  s.species = cfg.string("species", "");
  s.times = cfg.numbers("times");
  if (s.times.empty()) cfg.fail("times", "expected at least one lag time");
  for (double t : s.times)
    if (!(t > 0)) cfg.fail("times", "expected positive lag times");
  if (cfg.has("components")) {
    s.components = cfg.strings("components");
    for (const auto& c : s.components)
      if (c != "tot" && c != "x" && c != "y" && c != "z" && c != "par" && c != "perp")
        cfg.fail("components", "expected components from tot, x, y, z, par, perp");
  }
  const bool projected = std::any_of(s.components.begin(), s.components.end(), [](const std::string& c) { return c == "par" || c == "perp"; });
  cfg.reject_unless(projected, "direction", "without par or perp in components (it is their reference direction)");
  for (const char* key : {"angular_bin_width", "angular_dimension"})
    cfg.reject_unless(cfg.has("angular_axes"), key, "without angular_axes (it shapes the angular van Hove function)");
  if (cfg.has("direction")) {
    const Vec3 d = cfg.vec3("direction");
    if (!(d.norm() > 0)) cfg.fail("direction", "expected a non-zero vector");
    s.direction = d.normalized();
  }
  if (cfg.has("bin_width")) s.bin_width = cfg.positive("bin_width");
  s.bins = static_cast<std::size_t>(cfg.positive_integer("bins", 500));
  if (cfg.has("angular_axes"))
    for (const auto& a : cfg.strings("angular_axes")) {
      const int k = body_axis_index(a, false);
      if (k < 0) cfg.fail("angular_axes", "expected body axes from T, W, L");
      s.angular_axes.push_back(k);
    }
  s.angular_bin_width = cfg.positive("angular_bin_width", s.angular_bin_width);
  s.angular_dimension = static_cast<int>(cfg.positive_integer("angular_dimension", 2));
  if (s.angular_dimension > 3) cfg.fail("angular_dimension", "expected 1, 2 or 3");
  s.lags_per_decade = cfg.non_negative("lags_per_decade", s.lags_per_decade);
  s.max_origins = static_cast<std::size_t>(cfg.non_negative_integer("max_origins", 0));
  return s;
}

VanHoveAnalysis::VanHoveAnalysis(VanHoveSettings settings, std::size_t replicas) : s_(std::move(settings)), replicas_(replicas) {}

void VanHoveAnalysis::add_channel_counts(const Trajectory& t, const std::vector<std::size_t>& members, const Channel& ch,
                                         const std::vector<double>* phi, std::vector<std::vector<double>>& hist,
                                         std::vector<double>& m2, std::vector<double>& count) const {
  const std::size_t N = t.particles, blocks = hist.size();
  for (const auto& [i0, j0] : grid_.classes[ch.lag_class].pairs) {
    const std::size_t b = origin_block(i0, t.frames, blocks);
    for (std::size_t i : members) {
      double sq;
      if (phi) {
        const double* a = &(*phi)[3 * (i0 * N + i)];
        const double* z = &(*phi)[3 * (j0 * N + i)];
        sq = (z[0] - a[0]) * (z[0] - a[0]) + (z[1] - a[1]) * (z[1] - a[1]) + (z[2] - a[2]) * (z[2] - a[2]);
      } else {
        sq = squared_component(ch.component, t.pos(j0, i) - t.pos(i0, i), s_.direction);
      }
      m2[b] += sq;
      count[b] += 1;
      const auto bin = static_cast<std::size_t>(std::sqrt(sq) / ch.width);
      hist[b][std::min(bin, s_.bins)] += 1;  // the last slot counts the overflow
    }
  }
}

void VanHoveAnalysis::accumulate(const Trajectory& t, int species_index) {
  const auto members = t.members(species_index);
  if (seen_ == 0) {
    grid_ = make_lag_grid(t.time, s_.lags_per_decade, s_.max_origins);
    for (double time : s_.times) {
      const std::size_t c = nearest_lag_class(grid_, time);
      for (const auto& comp : s_.components) channels_.push_back({comp, component_dimension(comp), -1, c, 0});
      for (int a : s_.angular_axes)
        channels_.push_back({std::string("phi_") + "TWL"[a], s_.angular_dimension, a, c, s_.angular_bin_width});
    }
    samples_.resize(channels_.size());
    lag_sum_.assign(channels_.size(), 0.0);
  }
  std::vector<std::vector<double>> phis(3);
  for (int a : s_.angular_axes) phis[static_cast<std::size_t>(a)] = rotation_vector_path(t, a).phi;
  const std::size_t blocks = error_blocks(replicas_);
  for (std::size_t k = 0; k < channels_.size(); ++k) {
    Channel& ch = channels_[k];
    const std::vector<double>* phi = ch.axis >= 0 ? &phis[static_cast<std::size_t>(ch.axis)] : nullptr;
    if (seen_ == 0 && ch.width == 0) {
      // bin width from the first replica's rms displacement at this lag (Decision: 0.02 ⟨Δr²⟩^{1/2})
      if (s_.bin_width) {
        ch.width = *s_.bin_width;
      } else {
        double sum = 0, n = 0;
        for (const auto& [i0, j0] : grid_.classes[ch.lag_class].pairs)
          for (std::size_t i : members) { sum += squared_component(ch.component, t.pos(j0, i) - t.pos(i0, i), s_.direction); n += 1; }
        ch.width = 0.02 * std::sqrt(sum / std::max(n, 1.0));
        if (!(ch.width > 0)) ch.width = 1e-12;
      }
    }
    std::vector<std::vector<double>> hist(blocks, std::vector<double>(s_.bins + 1, 0.0));
    std::vector<double> m2(blocks, 0.0), count(blocks, 0.0);
    add_channel_counts(t, members, ch, phi, hist, m2, count);
    for (std::size_t b = 0; b < blocks; ++b) {
      std::vector<double> sample(s_.bins + 2, kNaN);
      if (count[b] > 0) {
        for (std::size_t j = 0; j < s_.bins; ++j) sample[j] = hist[b][j] / (count[b] * bin_measure(ch.dimension, j * ch.width, ch.width));
        sample[s_.bins] = m2[b] / count[b];
        sample[s_.bins + 1] = hist[b][s_.bins] / count[b];
      }
      samples_[k].add(std::move(sample));
    }
    double lag = 0;
    for (const auto& [i0, j0] : grid_.classes[ch.lag_class].pairs) lag += t.time[j0] - t.time[i0];
    lag_sum_[k] += lag / static_cast<double>(grid_.classes[ch.lag_class].pairs.size());
  }
  ++seen_;
}

std::vector<VanHoveCurve> VanHoveAnalysis::compute() const {
  std::vector<VanHoveCurve> out;
  for (std::size_t k = 0; k < channels_.size(); ++k) {
    const Channel& ch = channels_[k];
    const auto mean = samples_[k].mean(), se = samples_[k].standard_error();
    VanHoveCurve c;
    c.component = ch.component;
    c.dimension = ch.dimension;
    c.time = lag_sum_[k] / static_cast<double>(std::max<std::size_t>(seen_, 1));
    c.mean_square = mean[s_.bins];
    c.overflow = mean[s_.bins + 1];
    for (std::size_t j = 0; j < s_.bins; ++j) {
      const double r0 = j * ch.width, r1 = r0 + ch.width, mid = r0 + 0.5 * ch.width;
      c.r.push_back(mid);
      c.g.push_back(mean[j]);
      c.g_error.push_back(se[j]);
      // the reference in the same normalisation: bin average of P_d(ρ) / (measure density at the bin)
      const double p = gaussian_radial_cdf(ch.dimension, r1, c.mean_square) - gaussian_radial_cdf(ch.dimension, r0, c.mean_square);
      const double measure = ch.axis >= 0 ? 4.0 / 3.0 * M_PI * (r1 * r1 * r1 - r0 * r0 * r0) : bin_measure(ch.dimension, r0, ch.width);
      c.gaussian.push_back(p / measure);
      if (ch.axis >= 0) {  // angular: normalised with 4πφ² whatever the dimension of the reference
        c.g.back() = mean[j] * bin_measure(ch.dimension, r0, ch.width) / measure;
        c.g_error.back() = se[j] * bin_measure(ch.dimension, r0, ch.width) / measure;
      }
    }
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace anisodyn::analysis
