#include "anisodyn/analysis/msd.hpp"
#include "anisodyn/io/body_axis_choice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "anisodyn/analysis/fitting.hpp"
#include "anisodyn/core/error.hpp"
#include "anisodyn/system/order.hpp"

namespace anisodyn::analysis {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

int body_axis_index(tool::ConfigNode& cfg, const std::string& key) { return io::choose_body_axis(cfg, key, "auto", true, {"auto"}); }
}  // namespace

MsdSettings parse_msd_settings(tool::ConfigNode& cfg) {
  MsdSettings s;
  s.species = cfg.string("species", "");
  const std::string ref = cfg.choice("reference", {"axes", "director", "field", "vector", "particle_axis"}, "axes");
  if (ref == "director") s.reference = MsdReference::Director;
  if (ref == "particle_axis") s.reference = MsdReference::ParticleAxis;
  cfg.reject_unless(ref == "field" || ref == "vector", "direction", "unless \"reference\" is \"field\" or \"vector\" (it is their direction)");
  cfg.reject_unless(ref == "director" || ref == "particle_axis", "axis",
                    "unless \"reference\" is \"director\" or \"particle_axis\" (it picks the body axis they use)");
  if (ref == "field" || ref == "vector") {
    s.reference = MsdReference::Vector;
    const Vec3 d = cfg.vec3("direction");
    if (!(d.norm() > 0)) cfg.fail("direction", "expected a non-zero direction vector");
    s.direction = d.normalized();
  }
  s.axis = body_axis_index(cfg, "axis");
  cfg.reject_unless(s.reference == MsdReference::Director, "director_species",
                    "unless \"reference\" is \"director\" (it names the species whose director spheres use)");
  s.director_species = cfg.string("director_species", "");
  if (s.reference == MsdReference::ParticleAxis && s.axis < 0) s.axis = 2;
  s.lags_per_decade = cfg.non_negative("lags_per_decade", s.lags_per_decade);
  s.max_origins = static_cast<std::size_t>(cfg.non_negative_integer("max_origins", 0));
  s.body_frame = cfg.boolean("body_frame", false);
  s.fit_window = parse_lag_window(cfg, "fit");
  s.ngp_constant = cfg.choice("ngp_constant", {"auto", "isotropic", "anisotropic"}, "auto");
  s.beta_half_width = cfg.positive("beta_smoothing_decades", s.beta_half_width);
  return s;
}

const MsdComponent& MsdResult::component(const std::string& name) const {
  for (const auto& c : components)
    if (c.name == name) return c;
  throw RuntimeFailure("no MSD component " + name);
}

Vec3 run_averaged_director(const Trajectory& t, const std::vector<std::size_t>& members, int& axis, double& order) {
  std::array<Mat3, 3> q{Mat3::Zero(), Mat3::Zero(), Mat3::Zero()};
  std::vector<Vec3> axes(members.size());
  for (std::size_t f = 0; f < t.frames; ++f)
    for (int k = 0; k < 3; ++k) {
      for (std::size_t m = 0; m < members.size(); ++m) axes[m] = t.axis(f, members[m], k);
      q[static_cast<std::size_t>(k)] += q_tensor(axes) / static_cast<double>(t.frames);
    }
  int best = axis;
  if (best < 0) {
    best = 0;
    for (int k = 1; k < 3; ++k)
      if (uniaxial_order(q[static_cast<std::size_t>(k)]).order > uniaxial_order(q[static_cast<std::size_t>(best)]).order) best = k;
  }
  const UniaxialOrder u = uniaxial_order(q[static_cast<std::size_t>(best)]);
  axis = best;
  order = u.order;
  return u.director;
}

int director_species_of(const Trajectory& t, int analysed, const std::string& director_species, const std::string& config_file) {
  const auto anisotropic = [&](int s) { return t.species_table[static_cast<std::size_t>(s)].shape.is_anisotropic(); };
  if (analysed < 0 || anisotropic(analysed)) {
    if (!director_species.empty())
      throw InputError(config_file, "director_species",
                       "no director_species for an anisotropic species: it is its own reference (director_species only serves spheres)");
    return analysed;
  }
  if (!director_species.empty()) {
    const int s = t.species_index(director_species, config_file, "director_species");
    if (!anisotropic(s)) throw InputError(config_file, "director_species", "species '" + director_species + "' is a sphere: it has no director");
    return s;
  }
  std::vector<int> candidates;
  std::string names;
  for (std::size_t s = 0; s < t.species_table.size(); ++s)
    if (anisotropic(static_cast<int>(s))) {
      candidates.push_back(static_cast<int>(s));
      names += (names.empty() ? "" : ", ") + t.species_table[s].name;
    }
  if (candidates.empty())
    throw InputError(config_file, "reference", "a director was requested for spheres but " + t.path +
                                                   " has no anisotropic species to take it from; use \"reference\": \"axes\"");
  if (candidates.size() > 1)
    throw InputError(config_file, "director_species", t.path + " has several anisotropic species (" + names +
                                                          "): name the one whose director the spheres use");
  return candidates.front();
}

MsdAnalysis::MsdAnalysis(MsdSettings settings, std::size_t replicas, std::string config_file)
    : s_(std::move(settings)), replicas_(replicas), config_file_(std::move(config_file)) {
  names_ = {"tot", "x", "y", "z"};
  dims_ = {3, 1, 1, 1};
  if (s_.reference != MsdReference::Axes) {
    names_.insert(names_.end(), {"par", "perp"});
    dims_.insert(dims_.end(), {1, 2});
  }
  if (s_.body_frame) {
    names_.insert(names_.end(), {"body_x", "body_y", "body_z"});
    dims_.insert(dims_.end(), {1, 1, 1});
  }
}

namespace {

/// Cumulative body-frame displacement X_k(f) = Σ δr·ū_k over frame intervals, ū_k the normalised
/// mean of the body axis at both ends (spec 50 §1.2), [F × N × 3].
std::vector<double> body_frame_path(const Trajectory& t) {
  if (t.elements.count("body_displacement")) return t.elements.at("body_displacement").second;
  std::vector<double> x(3 * t.frames * t.particles, 0.0);
  for (std::size_t f = 1; f < t.frames; ++f)
    for (std::size_t i = 0; i < t.particles; ++i) {
      const Vec3 dr = t.pos(f, i) - t.pos(f - 1, i);
      const Mat3 a = t.quat(f - 1, i).toRotationMatrix(), b = t.quat(f, i).toRotationMatrix();
      for (int k = 0; k < 3; ++k) {
        Vec3 u = a.col(k) + b.col(k);
        u = u.norm() > 0 ? u.normalized() : a.col(k);
        x[3 * (f * t.particles + i) + k] = x[3 * ((f - 1) * t.particles + i) + k] + dr.dot(u);
      }
    }
  return x;
}

}  // namespace

void MsdAnalysis::accumulate(const Trajectory& t, int species_index) {
  if (replicas_seen_ == 0) {
    grid_ = make_lag_grid(t.time, s_.lags_per_decade, s_.max_origins);
    lag_sum_.assign(grid_.classes.size(), 0.0);
    origin_count_.assign(grid_.classes.size(), 0.0);
    meta_.uniform_frames = grid_.uniform;
  }
  const std::vector<std::size_t> members = t.members(species_index);
  const std::size_t nc = grid_.classes.size(), ncomp = names_.size(), F = t.frames, N = t.particles;
  const std::size_t blocks = error_blocks(replicas_, std::max<std::size_t>(s_.single_replica_blocks, 1));

  Vec3 e = s_.direction;
  if (s_.reference == MsdReference::Director) {
    int axis = s_.axis;
    double order = 0;
    const int source = director_species_of(t, species_index, s_.director_species, config_file_);
    e = run_averaged_director(t, source == species_index ? members : t.members(source), axis, order);
    if (source != species_index) meta_.director_species = t.species_table[static_cast<std::size_t>(source)].name;
    if (!(order > s_.director_threshold))
      throw InputError(config_file_, "reference",
                       "a director was requested but " + t.path + " has no orientational order: the largest order parameter " +
                           "is U = " + std::to_string(order) + " ≤ " + std::to_string(s_.director_threshold) +
                           " (isotropic); use \"reference\": \"axes\" for isotropic phases");
    meta_.directors.push_back(e);
    meta_.director_order.push_back(order);
  }
  std::vector<double> axes0;  // particle axis at each frame, for the particle_axis reference
  if (s_.reference == MsdReference::ParticleAxis) {
    axes0.resize(3 * F * N);
    for (std::size_t f = 0; f < F; ++f)
      for (std::size_t i : members) {
        const Vec3 u = t.axis(f, i, s_.axis);
        for (int a = 0; a < 3; ++a) axes0[3 * (f * N + i) + a] = u[a];
      }
  }
  const std::vector<double> body = s_.body_frame ? body_frame_path(t) : std::vector<double>{};

  // sums[b][(comp·2 + moment)·nc + c]
  std::vector<std::vector<double>> sums(blocks, std::vector<double>(2 * ncomp * nc, 0.0));
  std::vector<std::vector<double>> counts(blocks, std::vector<double>(nc, 0.0));
  const bool has_ref = s_.reference != MsdReference::Axes;
  for (std::size_t c = 0; c < nc; ++c) {
    const LagClass& lc = grid_.classes[c];
    double lag_sum = 0;
    for (const auto& [i0, j0] : lc.pairs) {
      lag_sum += t.time[j0] - t.time[i0];
      const std::size_t b = origin_block(i0, F, blocks);
      double acc[18] = {0};
      const double* ri = &t.position[3 * i0 * N];
      const double* rj = &t.position[3 * j0 * N];
      for (std::size_t i : members) {
        const double dx = rj[3 * i] - ri[3 * i], dy = rj[3 * i + 1] - ri[3 * i + 1], dz = rj[3 * i + 2] - ri[3 * i + 2];
        const double x2 = dx * dx, y2 = dy * dy, z2 = dz * dz, r2 = x2 + y2 + z2;
        acc[0] += r2; acc[1] += r2 * r2;
        acc[2] += x2; acc[3] += x2 * x2;
        acc[4] += y2; acc[5] += y2 * y2;
        acc[6] += z2; acc[7] += z2 * z2;
        std::size_t k = 8;
        if (has_ref) {
          double ex = e.x(), ey = e.y(), ez = e.z();
          if (!axes0.empty()) {
            const double* u = &axes0[3 * (i0 * N + i)];
            ex = u[0]; ey = u[1]; ez = u[2];
          }
          const double p = dx * ex + dy * ey + dz * ez, p2 = p * p, q2 = r2 - p2;
          acc[k] += p2; acc[k + 1] += p2 * p2; acc[k + 2] += q2; acc[k + 3] += q2 * q2;
          k += 4;
        }
        if (!body.empty()) {
          const double* xi = &body[3 * (i0 * N + i)];
          const double* xj = &body[3 * (j0 * N + i)];
          for (int a = 0; a < 3; ++a) {
            const double d2 = (xj[a] - xi[a]) * (xj[a] - xi[a]);
            acc[k] += d2; acc[k + 1] += d2 * d2;
            k += 2;
          }
        }
      }
      for (std::size_t m = 0; m < 2 * ncomp; ++m) sums[b][m * nc + c] += acc[m];
      counts[b][c] += static_cast<double>(members.size());
    }
    lag_sum_[c] += lag_sum / static_cast<double>(lc.pairs.size());
    origin_count_[c] += static_cast<double>(lc.pairs.size() * members.size());
  }
  for (std::size_t b = 0; b < blocks; ++b) {
    std::vector<double> sample(2 * ncomp * nc, kNaN);
    for (std::size_t m = 0; m < 2 * ncomp; ++m)
      for (std::size_t c = 0; c < nc; ++c)
        if (counts[b][c] > 0) sample[m * nc + c] = sums[b][m * nc + c] / counts[b][c];
    samples_.add(std::move(sample));
  }
  ++replicas_seen_;
}

MsdResult MsdAnalysis::compute() const {
  MsdResult r = meta_;
  const std::size_t nc = grid_.classes.size(), ncomp = names_.size();
  const double reps = static_cast<double>(std::max<std::size_t>(replicas_seen_, 1));
  for (std::size_t c = 0; c < nc; ++c) {
    r.lag.push_back(lag_sum_[c] / reps);
    r.origins.push_back(origin_count_[c] / reps);
  }
  r.samples = samples_.count();
  auto slice = [nc](const std::vector<double>& v, std::size_t m) {
    return std::vector<double>(v.begin() + static_cast<std::ptrdiff_t>(m * nc), v.begin() + static_cast<std::ptrdiff_t>((m + 1) * nc));
  };
  const auto mean = samples_.mean(), se = samples_.standard_error();
  const std::size_t par = ncomp > 4 && names_[4] == "par" ? 4 : 0;
  const bool anisotropic = s_.ngp_constant == "anisotropic" || (s_.ngp_constant == "auto" && s_.reference == MsdReference::Director);
  r.ngp_constant = anisotropic ? "anisotropic (spec 50 §1.5 c'_2,3)" : "isotropic (1 + 2/d)";
  if (anisotropic && par == 0) throw InputError(config_file_, "ngp_constant", "the anisotropic constant needs a reference direction");
  for (std::size_t k = 0; k < ncomp; ++k) {
    MsdComponent comp;
    comp.name = names_[k];
    comp.dimension = dims_[k];
    comp.msd = slice(mean, 2 * k);
    comp.msd_error = slice(se, 2 * k);
    comp.msd4 = slice(mean, 2 * k + 1);
    const double d = comp.dimension;
    const bool use_aniso = anisotropic && k == 0;
    const auto ngp = jackknife_curve(samples_, [&](const std::vector<double>& m) {
      std::vector<double> out(nc, kNaN);
      for (std::size_t c = 0; c < nc; ++c) {
        const double m2 = m[2 * k * nc + c], m4 = m[(2 * k + 1) * nc + c];
        double cst = 1.0 + 2.0 / d;
        if (use_aniso) {
          const double dp = m[2 * par * nc + c], dq = m[2 * (par + 1) * nc + c] / 2.0;  // per-component variances
          cst = (3 * dp * dp + 8 * dq * dq + 4 * dp * dq) / (dp * dp + 4 * dq * dq + 4 * dp * dq);
        }
        if (m2 > 0) out[c] = m4 / (cst * m2 * m2) - 1.0;
      }
      return out;
    });
    comp.ngp = ngp.value;
    comp.ngp_error = ngp.error;
    CurveSamples betas;
    for (const auto& smp : samples_.samples()) betas.add(local_log_slope(r.lag, slice(smp, 2 * k), s_.beta_half_width));
    comp.beta = local_log_slope(r.lag, comp.msd, s_.beta_half_width);
    comp.beta_error = betas.standard_error();
    r.components.push_back(std::move(comp));
  }
  // fit window: the given one, or the last decade of lags with ≥ 20 independent origins (spec 50 §1.3)
  if (s_.fit_window) {
    r.fit_window_automatic = false;
    r.fit_t_min = s_.fit_window->first;
    r.fit_t_max = s_.fit_window->second;
  } else if (!r.lag.empty()) {
    const double run = r.lag.back();
    double t_max = 0;
    for (double l : r.lag)
      if (l <= run / 20.0 * (1 + 1e-9)) t_max = l;
    if (t_max == 0) t_max = r.lag.back();
    r.fit_t_max = t_max;
    r.fit_t_min = t_max / 10.0;
  }
  std::vector<std::size_t> window;
  for (std::size_t c = 0; c < r.lag.size(); ++c)
    if (r.lag[c] >= r.fit_t_min * (1 - 1e-9) && r.lag[c] <= r.fit_t_max * (1 + 1e-9)) window.push_back(c);
  double beta_sum = 0, beta_count = 0;
  for (std::size_t c : window)
    if (!std::isnan(r.components[0].beta[c])) { beta_sum += r.components[0].beta[c]; beta_count += 1; }
  r.fit_mean_beta = beta_count > 0 ? beta_sum / beta_count : kNaN;
  for (std::size_t k = 0; k < ncomp; ++k) {
    const double two_d = 2.0 * dims_[k];
    auto slope_over_window = [&](const std::vector<double>& m) {
      std::vector<double> x, y;
      for (std::size_t c : window) { x.push_back(r.lag[c]); y.push_back(m[2 * k * nc + c]); }
      return fit_line(x, y).slope / two_d;
    };
    r.components[k].diffusion = window.size() >= 2 ? jackknife(samples_, slope_over_window) : Estimate{};
  }
  // D_∥/D_⊥ (lab frame to the axis at the origin; body frame: body_z over the mean of body_x and
  // body_y), a ratio of slopes with its own jackknife (spec 30 §9, the C5 plot against p).
  auto index_of = [&](const std::string& name) -> std::ptrdiff_t {
    const auto it = std::find(names_.begin(), names_.end(), name);
    return it == names_.end() ? -1 : it - names_.begin();
  };
  auto slope_of = [&](const std::vector<double>& m, std::ptrdiff_t k) {
    std::vector<double> x, y;
    for (std::size_t c : window) { x.push_back(r.lag[c]); y.push_back(m[2 * static_cast<std::size_t>(k) * nc + c]); }
    return fit_line(x, y).slope;
  };
  const std::ptrdiff_t lab_par = index_of("par"), lab_perp = index_of("perp"), bx = index_of("body_x"), by = index_of("body_y"), bz = index_of("body_z");
  if (window.size() >= 2 && lab_par >= 0 && lab_perp >= 0)
    r.par_over_perp = jackknife(samples_, [&](const std::vector<double>& m) { return slope_of(m, lab_par) / slope_of(m, lab_perp); });
  if (window.size() >= 2 && bx >= 0 && by >= 0 && bz >= 0)
    r.body_par_over_perp = jackknife(samples_, [&](const std::vector<double>& m) {
      return 2.0 * slope_of(m, bz) / (slope_of(m, bx) + slope_of(m, by));
    });
  return r;
}

CurveSamples MsdAnalysis::samples_of(const std::string& name) const {
  const auto it = std::find(names_.begin(), names_.end(), name);
  if (it == names_.end()) throw RuntimeFailure("no MSD component " + name);
  // a sample holds (component, moment) blocks of nc values; the MSD is moment 0
  const std::size_t nc = grid_.classes.size(), first = 2 * static_cast<std::size_t>(it - names_.begin()) * nc;
  CurveSamples out;
  for (const auto& s : samples_.samples())
    out.add(std::vector<double>(s.begin() + static_cast<std::ptrdiff_t>(first), s.begin() + static_cast<std::ptrdiff_t>(first + nc)));
  return out;
}

}  // namespace anisodyn::analysis
