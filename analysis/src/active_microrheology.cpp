#include "anisodyn/analysis/active_microrheology.hpp"
#include "anisodyn/io/body_axis_choice.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "anisodyn/core/box.hpp"
#include "anisodyn/core/error.hpp"
#include "anisodyn/system/order.hpp"

namespace anisodyn::analysis {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr const char* kPathObservable = "tracer_position";

int axis_letter_index(tool::ConfigNode& cfg, const std::string& key, const std::string& fallback) {
  return io::choose_body_axis(cfg, key, fallback, true, {"none"});
}

/// The box axis and sign of an axis-aligned direction; −1 if it is not along a box axis.
int box_axis_of(const Vec3& d, double& sign) {
  int axis = -1, nonzero = 0;
  for (int k = 0; k < 3; ++k)
    if (d[k] != 0.0) { axis = k; ++nonzero; }
  if (nonzero != 1) return -1;
  sign = d[axis] > 0 ? 1.0 : -1.0;
  return axis;
}

const Species* find_species(const SpeciesTable& table, const std::string& name) {
  for (const auto& sp : table)
    if (sp.name == name) return &sp;
  return nullptr;
}

/// Drift of a random walk sampled at (x_k, y_k), k in [first, last]: the end-to-end slope, which is
/// its maximum-likelihood estimate, and the error from the scatter of the increments about it.
struct Drift {
  double slope = kNaN, error = kNaN, rise = kNaN, run = kNaN;
};
Drift end_to_end_drift(const std::vector<double>& x, const std::vector<double>& y, std::size_t first, std::size_t last) {
  Drift d;
  d.rise = y[last] - y[first];
  d.run = x[last] - x[first];
  if (!(d.run > 0.0)) return d;
  d.slope = d.rise / d.run;
  const std::size_t n = last - first;  // increments
  if (n < 2) return d;
  double sq = 0.0;
  for (std::size_t k = first; k < last; ++k) {
    const double residual = (y[k + 1] - y[k]) - d.slope * (x[k + 1] - x[k]);
    sq += residual * residual;
  }
  const double sigma2 = sq / d.run * static_cast<double>(n) / static_cast<double>(n - 1);  // per unit time
  d.error = std::sqrt(sigma2 / d.run);
  return d;
}

/// Distance behind the tracer (Δz < 0) where the on-axis profile first reaches `threshold`, walking
/// away from the tracer bin by bin and interpolating linearly between bin centres; the first bin's
/// centre distance if it already reaches it (the resolution), NaN if it never does.
double wake_length_of(const std::vector<double>& profile, const DensityMapGrid& g, double threshold) {
  double prev_distance = kNaN, prev_value = kNaN;
  for (std::size_t k = g.nz / 2; k-- > 0;) {
    const double distance = -g.dz_centre(k), value = profile[k];
    if (std::isnan(value)) continue;
    if (value >= threshold) {
      if (std::isnan(prev_value)) return distance;
      return prev_distance + (threshold - prev_value) / (value - prev_value) * (distance - prev_distance);
    }
    prev_distance = distance;
    prev_value = value;
  }
  return kNaN;
}

}  // namespace

double DensityMapGrid::ring_volume(std::size_t m) const {
  const double r0 = static_cast<double>(m) * drho, r1 = r0 + drho;
  return std::numbers::pi * (r1 * r1 - r0 * r0) * dz;
}

ActiveMicrorheologySettings parse_active_microrheology_settings(tool::ConfigNode& cfg) {
  ActiveMicrorheologySettings s;
  s.species = cfg.string("species");
  const int forces = static_cast<int>(cfg.has("beta_force")) + static_cast<int>(cfg.has("force")) + static_cast<int>(cfg.has("pe"));
  if (forces > 1) cfg.fail("beta_force", "expected one of 'beta_force', 'force' (with kT) and 'pe', not several");
  cfg.reject_unless(cfg.has("force"), "kT", "without 'force' (it converts force into beta_force = force / kT)");
  const double kT = cfg.positive("kT", 1.0);
  for (const char* key : {"radius", "tracer_diameter"})
    cfg.reject_unless(!cfg.has("beta_force") && !cfg.has("force"), key, "with 'beta_force' or 'force' (the radius converts pe into beta_force)");
  if (cfg.has("beta_force")) s.beta_force = cfg.non_negative("beta_force");
  if (cfg.has("force")) s.beta_force = cfg.non_negative("force") / kT;
  if (cfg.has("pe")) s.peclet = cfg.non_negative("pe");
  if (cfg.has("radius") && cfg.has("tracer_diameter")) cfg.fail("tracer_diameter", "expected either 'radius' or 'tracer_diameter', not both");
  if (cfg.has("radius")) s.radius = cfg.positive("radius");
  if (cfg.has("tracer_diameter")) s.radius = 0.5 * cfg.positive("tracer_diameter");
  if (cfg.has("D_s")) s.D_s = cfg.positive("D_s");
  if (cfg.has("direction")) {
    s.direction = cfg.vec3("direction");
    s.direction_given = true;
    double sign = 1;
    if (box_axis_of(s.direction, sign) < 0) cfg.fail("direction", "expected a direction along a box axis, e.g. [0, 0, 1]");
  }
  if (cfg.has("steady_distance") && cfg.has("steady_from"))
    cfg.fail("steady_distance", "expected either steady_distance or steady_from: with steady_from the distance has no effect");
  s.steady_distance_given = cfg.has("steady_distance");
  s.steady_distance = cfg.positive("steady_distance", s.steady_distance);
  if (cfg.has("steady_from")) s.steady_from = cfg.non_negative("steady_from");
  const std::string source = cfg.choice("position_source", {"auto", "frames", "observable"}, "auto");
  s.source = source == "frames" ? TracerPathSource::Frames : source == "observable" ? TracerPathSource::Observable : TracerPathSource::Auto;
  s.density_map = cfg.boolean("density_map", true);
  for (const char* key : {"bath_species", "bin_width", "dz_bin", "rho_bin", "on_axis_radius", "wake_threshold", "order_axis"})
    cfg.reject_unless(s.density_map, key, "with density_map false (it shapes the density map)");
  cfg.reject_unless(!(cfg.has("dz_bin") && cfg.has("rho_bin")), "bin_width", "with both dz_bin and rho_bin given (it is their default)");
  s.bath_species = cfg.string("bath_species", "");
  const double bin = cfg.positive("bin_width", 0.25);
  s.dz_bin = cfg.positive("dz_bin", bin);
  s.rho_bin = cfg.positive("rho_bin", bin);
  s.on_axis_radius = cfg.positive("on_axis_radius", s.on_axis_radius);
  s.wake_threshold = cfg.positive("wake_threshold", s.wake_threshold);
  s.order_axis = axis_letter_index(cfg, "order_axis", "L");
  return s;
}

void resolve_active_defaults(ActiveMicrorheologySettings& s, const SpeciesTable& table, const nlohmann::json& run_parameters,
                             const std::string& config_file, nlohmann::json& details) {
  const Species* tracer = find_species(table, s.species);
  if (!tracer) throw InputError(config_file, "species", "unknown tracer species '" + s.species + "'");
  const bool sphere = tracer->shape.kind == ShapeKind::Sphere && tracer->shape.diameter > 0;
  const nlohmann::json* run_tracer = run_parameters.is_object() && run_parameters.contains("tracer") && run_parameters["tracer"].is_object()
                                         ? &run_parameters["tracer"] : nullptr;
  if (!s.direction_given && run_tracer && run_tracer->contains("axis") && (*run_tracer)["axis"].is_string()) {
    const std::string a = (*run_tracer)["axis"];
    if (a == "x" || a == "y" || a == "z") {
      s.direction = Vec3::Unit(a[0] - 'x');
      details["direction_source"] = "the run's tracer.axis";
    }
  }
  if (std::isnan(s.beta_force)) {
    if (std::isnan(s.peclet) && run_tracer && run_tracer->contains("pe") && (*run_tracer)["pe"].is_number()) {
      s.peclet = (*run_tracer)["pe"].get<double>();
      details["pe_source"] = "the run's tracer.pe";
    }
    if (!std::isnan(s.peclet)) {
      if (!(s.radius > 0) && sphere) s.radius = 0.5 * tracer->shape.diameter;
      if (!(s.radius > 0)) throw InputError(config_file, "radius", "expected the tracer radius to convert pe into beta_force = pe / a");
      s.beta_force = s.peclet / s.radius;
      details["beta_force_source"] = "pe / a (spec 10 section 4.5)";
      details["pe"] = s.peclet;
      details["radius"] = s.radius;
    }
  } else {
    details["beta_force_source"] = "configuration";
  }
  if (!(s.beta_force >= 0))
    throw InputError(config_file, "beta_force", "expected the force: 'beta_force', 'force' (with kT) or 'pe', or a trajectory whose run parameters give tracer.pe");
  if (s.beta_force == 0.0) {
    // Pe = 0: a passive reference run. Nothing drifts, so there is no transient to wait for.
    if (s.steady_distance_given)
      throw InputError(config_file, "steady_distance", "has no effect at zero force (Pe = 0): the tracer does not drift; "
                                                       "the steady part is the whole run unless steady_from is given");
    if (!s.steady_from) s.steady_from = 0.0;
    details["steady_part"] = "the whole run from steady_from (zero force: no transient)";
  }
  if (std::isnan(s.D_s)) {
    const Vec3 D = tracer->D_trans;
    if (!sphere || !(D.minCoeff() > 0) || D.maxCoeff() != D.minCoeff())
      throw InputError(config_file, "D_s", "expected the tracer's free translational diffusion coefficient D_s (species '" + s.species +
                                               "' is not a sphere with one positive D in the species table)");
    s.D_s = D.x();
    details["D_s_source"] = "species table";
  } else {
    details["D_s_source"] = "configuration";
  }
}

SteadyVelocity steady_velocity(const std::vector<double>& time, const std::vector<double>& displacement, double steady_distance,
                               std::optional<double> steady_from) {
  SteadyVelocity v;
  const std::size_t n = time.size();
  std::size_t first = n;
  for (std::size_t k = 0; k < n; ++k)
    if (steady_from ? time[k] >= *steady_from : displacement[k] >= steady_distance) { first = k; break; }
  if (first == n) return v;
  const Drift d = end_to_end_drift(time, displacement, first, n - 1);
  v.first = first;
  v.points = n - first;
  v.t_start = time[first];
  v.t_end = time[n - 1];
  v.displacement = d.rise;
  v.velocity = d.slope;
  v.velocity_error = d.error;
  return v;
}

ActiveMicrorheology::ActiveMicrorheology(ActiveMicrorheologySettings settings, std::size_t replicas, std::string config_file)
    : s_(std::move(settings)), replicas_(replicas), config_file_(std::move(config_file)) {
  if (s_.species.empty()) throw InputError(config_file_, "species", "expected the tracer species");
  axis_ = box_axis_of(s_.direction, sign_);
  if (axis_ < 0) throw InputError(config_file_, "direction", "expected a direction along a box axis");
  if (!(s_.beta_force >= 0)) throw InputError(config_file_, "beta_force", "expected a beta_force >= 0");
  if (!(s_.D_s > 0)) throw InputError(config_file_, "D_s", "expected a positive D_s");
}

ActiveMicrorheology::PathSeries ActiveMicrorheology::tracer_path(const Trajectory& t, std::size_t tracer) {
  const bool has_obs = t.observables.count(kPathObservable) > 0;
  if (s_.source == TracerPathSource::Observable && !has_obs)
    throw InputError(config_file_, "position_source", t.path + " has no observable '" + kPathObservable + "'");
  const bool use_obs = has_obs && s_.source != TracerPathSource::Frames;
  const std::string used = use_obs ? std::string("observable ") + kPathObservable : "frames (unwrapped tracer position)";
  if (source_used_.empty()) source_used_ = used;
  else if (source_used_ != used) source_used_ = "mixed (observable where present, else frames)";
  PathSeries p;
  if (use_obs) {
    const ObservableSeries& o = t.observables.at(kPathObservable);
    if (o.width != 3) throw InputError(t.path, std::string("observables/") + kPathObservable, "expected 3 columns (x, y, z)");
    p.time = o.time;
    for (std::size_t k = 0; k < o.time.size(); ++k) p.displacement.push_back(sign_ * (o.value[3 * k + axis_] - o.value[static_cast<std::size_t>(axis_)]));
  } else {
    p.time = t.time;
    for (std::size_t f = 0; f < t.frames; ++f) p.displacement.push_back(sign_ * (t.pos(f, tracer)[axis_] - t.pos(0, tracer)[axis_]));
  }
  return p;
}

void ActiveMicrorheology::add_velocity_samples(const PathSeries& p, const SteadyVelocity& v) {
  // A sample is (displacement, elapsed time), so that pooling sums both: Σ Δz / Σ Δt.
  if (replicas_ > 1) {
    velocity_samples_.add({v.displacement, v.duration()});
    return;
  }
  // A single replica: consecutive blocks of the steady part stand in for replicas (spec 50 §0); they
  // share their end points, so together they span the whole steady part.
  const std::size_t increments = v.points - 1;
  const std::size_t blocks = std::max<std::size_t>(1, std::min(s_.single_replica_blocks, increments / 2));
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t a = v.first + b * increments / blocks, e = v.first + (b + 1) * increments / blocks;
    const Drift d = end_to_end_drift(p.time, p.displacement, a, e);
    velocity_samples_.add({d.rise, d.run});
  }
}

std::vector<std::size_t> ActiveMicrorheology::bath_members(const Trajectory& t, int tracer_species) const {
  if (!s_.bath_species.empty()) return t.members(t.species_index(s_.bath_species, config_file_, "bath_species"));
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < t.particles; ++i)
    if (t.species[i] != tracer_species) out.push_back(i);
  return out;
}

void ActiveMicrorheology::accumulate(const Trajectory& t) {
  const int ts = t.species_index(s_.species, config_file_, "species");
  const std::vector<std::size_t> tracers = t.members(ts);
  if (tracers.size() != 1)
    throw InputError(config_file_, "species", "expected exactly one particle of the tracer species '" + s_.species + "' in " + t.path +
                                                  ", found " + std::to_string(tracers.size()));
  const PathSeries path = tracer_path(t, tracers.front());
  const SteadyVelocity v = steady_velocity(path.time, path.displacement, s_.steady_distance, s_.steady_from);
  if (v.points < 3)
    throw InputError(config_file_, s_.steady_from ? "steady_from" : "steady_distance",
                     "the tracer path of " + t.path + " has " + std::to_string(v.points) + " points in its steady part (" +
                         (s_.steady_from ? "t >= steady_from" : "after moving steady_distance along the force") +
                         "); at least 3 are needed — run longer, or lower steady_distance / steady_from");
  per_replica_.push_back(v);
  paths_.push_back(t.path);
  add_velocity_samples(path, v);
  if (s_.density_map) add_map(t, tracers.front(), v.t_start);
}

void ActiveMicrorheology::setup_map(const Trajectory& t, const std::vector<std::size_t>& bath) {
  // Decision bins; |dz| ≤ L_∥/2 and ρ_c ≤ L_⊥/2 keep every bin inside the minimum-image cell.
  const Vec3 L = t.box_edges(0);
  const int a1 = (axis_ + 1) % 3, a2 = (axis_ + 2) % 3;
  grid_.dz = s_.dz_bin;
  grid_.drho = s_.rho_bin;
  grid_.nz = 2 * static_cast<std::size_t>(std::floor(0.5 * L[axis_] / grid_.dz + 1e-9));
  grid_.nrho = static_cast<std::size_t>(std::floor(0.5 * std::min(L[a1], L[a2]) / grid_.drho + 1e-9));
  grid_.z_min = -static_cast<double>(grid_.nz / 2) * grid_.dz;
  if (grid_.nz == 0 || grid_.nrho == 0) throw InputError(config_file_, "bin_width", "expected bins smaller than half the box");
  const std::size_t bins = grid_.nz * grid_.nrho;
  sum_.assign(bins, 0.0);
  sum_sq_.assign(bins, 0.0);
  pooled_count_.assign(bins, 0.0);
  bool anisotropic = false;  // U of spheres (identity orientations) would read 1: skip it
  for (std::size_t i : bath) anisotropic = anisotropic || t.species_table[static_cast<std::size_t>(t.species[i])].shape.is_anisotropic();
  has_order_ = s_.order_axis >= 0 && !t.orientation.empty() && anisotropic;
  if (has_order_) order_sum_.assign(6 * bins, 0.0);
  on_axis_bins_ = std::min(grid_.nrho, std::max<std::size_t>(1, static_cast<std::size_t>(std::floor(s_.on_axis_radius / grid_.drho + 1e-9))));
  on_axis_radius_used_ = static_cast<double>(on_axis_bins_) * grid_.drho;
  bath_ = bath.size();
}

void ActiveMicrorheology::add_frame(const Trajectory& t, std::size_t f, std::size_t tracer, const std::vector<std::size_t>& bath,
                                    std::vector<double>& map) {
  const Box box(t.box_edges(f));
  const double bath_density = static_cast<double>(bath.size()) / box.volume();
  const int a1 = (axis_ + 1) % 3, a2 = (axis_ + 2) % 3;
  const Vec3 rt = t.pos(f, tracer);
  for (std::size_t j : bath) {
    const Vec3 d = box.min_image(t.pos(f, j) - rt);
    const double z = sign_ * d[axis_], rho = std::hypot(d[a1], d[a2]);
    const double kz = std::floor((z - grid_.z_min) / grid_.dz), km = std::floor(rho / grid_.drho);
    if (kz < 0 || kz >= static_cast<double>(grid_.nz) || km >= static_cast<double>(grid_.nrho)) continue;
    const std::size_t m = static_cast<std::size_t>(km), bin = static_cast<std::size_t>(kz) * grid_.nrho + m;
    map[bin] += 1.0 / (grid_.ring_volume(m) * bath_density);
    pooled_count_[bin] += 1.0;
    if (has_order_) {
      const Vec3 u = t.axis(f, j, s_.order_axis);
      double* o = &order_sum_[6 * bin];
      o[0] += u.x() * u.x(); o[1] += u.y() * u.y(); o[2] += u.z() * u.z();
      o[3] += u.x() * u.y(); o[4] += u.x() * u.z(); o[5] += u.y() * u.z();
    }
  }
}

void ActiveMicrorheology::add_map_sample(std::vector<double> map, double frames) {
  const std::size_t nrho = grid_.nrho;
  std::vector<double> on_axis(grid_.nz, 0.0);
  for (std::size_t k = 0; k < grid_.nz; ++k) {
    double volume = 0;  // the on-axis cylinder: bin densities weighted by ring volume
    for (std::size_t m = 0; m < nrho; ++m) {
      double& x = map[k * nrho + m];
      x /= frames;
      sum_[k * nrho + m] += x;
      sum_sq_[k * nrho + m] += x * x;
      if (m < on_axis_bins_) { on_axis[k] += x * grid_.ring_volume(m); volume += grid_.ring_volume(m); }
    }
    on_axis[k] /= volume;
  }
  on_axis_samples_.add(std::move(on_axis));
  ++map_samples_;
}

void ActiveMicrorheology::add_map(const Trajectory& t, std::size_t tracer, double t_start) {
  const std::vector<std::size_t> bath = bath_members(t, t.species[tracer]);
  if (bath.empty()) return;  // a tracer alone in the box: friction only
  if (grid_.nz == 0) setup_map(t, bath);
  std::vector<std::size_t> frames;
  for (std::size_t f = 0; f < t.frames; ++f)
    if (t.time[f] >= t_start) frames.push_back(f);
  if (frames.empty())
    throw InputError(config_file_, s_.steady_from ? "steady_from" : "steady_distance", t.path + " has no frame in the steady part");
  // one sample per replica, or blocks of the steady frames of a single replica
  const std::size_t blocks = replicas_ == 1 ? std::max<std::size_t>(1, std::min(s_.single_replica_blocks, frames.size())) : 1;
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t q0 = b * frames.size() / blocks, q1 = (b + 1) * frames.size() / blocks;
    std::vector<double> map(grid_.nz * grid_.nrho, 0.0);
    for (std::size_t q = q0; q < q1; ++q) add_frame(t, frames[q], tracer, bath, map);
    add_map_sample(std::move(map), static_cast<double>(q1 - q0));
  }
  steady_frames_ += frames.size();
}

ActiveResult ActiveMicrorheology::compute() const {
  ActiveResult r;
  r.replicas = per_replica_;
  r.replica_paths = paths_;
  r.path_source = source_used_;
  r.beta_force = s_.beta_force;
  r.D_s = s_.D_s;
  r.velocity_samples = velocity_samples_.count();
  std::vector<double> v;
  for (const auto& smp : velocity_samples_.samples()) v.push_back(smp[0] / smp[1]);
  r.replica_velocity = mean_and_error(v);
  r.velocity_scatter = r.replica_velocity.error * std::sqrt(static_cast<double>(v.size()));
  r.velocity = jackknife(velocity_samples_, [](const std::vector<double>& m) { return m[0] / m[1]; });
  const double drive = s_.D_s * s_.beta_force;  // the free velocity D_s βF
  if (drive > 0.0) r.gamma_ratio = jackknife(velocity_samples_, [drive](const std::vector<double>& m) { return drive * m[1] / m[0]; });

  r.has_map = map_samples_ > 0;
  if (!r.has_map) return r;
  r.has_order = has_order_;
  r.grid = grid_;
  r.map_samples = map_samples_;
  r.steady_frames = steady_frames_;
  r.bath_particles = bath_;
  r.on_axis_radius_used = on_axis_radius_used_;
  const double S = static_cast<double>(map_samples_);
  const std::size_t bins = grid_.nz * grid_.nrho;
  r.density.assign(bins, kNaN);
  r.density_error.assign(bins, kNaN);
  r.order.assign(bins, kNaN);
  r.particle_frames = pooled_count_;
  for (std::size_t b = 0; b < bins; ++b) {
    const double mean = sum_[b] / S;
    r.density[b] = mean;
    if (S > 1) r.density_error[b] = std::sqrt(std::max(0.0, (sum_sq_[b] - S * mean * mean) / (S - 1.0)) / S);
    if (has_order_ && pooled_count_[b] > 0) {
      const double* o = &order_sum_[6 * b];
      Mat3 m;
      m << o[0], o[3], o[4], o[3], o[1], o[5], o[4], o[5], o[2];
      const Mat3 q = 1.5 * m / pooled_count_[b] - 0.5 * Mat3::Identity();
      r.order[b] = uniaxial_order(q).order;
    }
  }
  r.on_axis = on_axis_samples_.mean();
  r.on_axis_error = on_axis_samples_.standard_error();
  const double threshold = s_.wake_threshold;
  const DensityMapGrid g = grid_;
  const auto wake = jackknife_curve(on_axis_samples_, [&](const std::vector<double>& profile) {
    return std::vector<double>{wake_length_of(profile, g, threshold)};
  });
  r.wake_length = {wake.value[0], wake.error[0]};
  return r;
}

}  // namespace anisodyn::analysis
