// anisodyn-microrheology: probe microrheology over replicas (spec 50 §6).
//   mode "passive": G′(ω), G″(ω) from the 3-D tracer MSD by the Mason GSER (F1), the GSER to second
//                   order in the log curvature, and the Evans compliance method (F2) on the same
//                   ω = 1/t grid, with jackknife errors.
//   mode "active":  effective friction γ_eff/γ_0 of a pulled tracer (F3), the axisymmetric bath density
//                   map around it with the local order, the on-axis profile and the wake length (F4).
#include <algorithm>
#include <type_traits>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "anisodyn/analysis/active_microrheology.hpp"
#include "anisodyn/analysis/passive_microrheology.hpp"
#include "anisodyn/analysis/species_selection.hpp"
#include "anisodyn/analysis/stage.hpp"
#include "anisodyn/io/h5md.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

/// The rows of a curve on ascending t, reversed so that ω ascends.
std::vector<double> by_omega(std::vector<double> v) {
  std::reverse(v.begin(), v.end());
  return v;
}

void write_passive(StageRun& run, const PassiveResult& r) {
  Table& t = run.out.table("moduli", "storage and loss moduli of the tracer's surroundings by the Mason GSER (spec 50 F1) and the "
                                     "Evans compliance method (F2), on omega = 1/t of the MSD lag grid (rows by ascending omega)");
  t.add("omega", "1/tau", "angular frequency omega = 1/t_k, t_k a lag of the MSD grid", by_omega(r.mason.omega));
  t.add("time", "tau", "lag time t_k = 1/omega", by_omega(r.time));
  t.add("msd", "length^2", "spec 50 A1: 3-D tracer MSD <dr^2(t)> averaged over tracers, time origins and replicas", by_omega(r.msd));
  t.add("msd_se", "length^2", "standard error of msd over replicas (origin blocks for one replica)", by_omega(r.msd_error));
  t.add("alpha", "1", "spec 50 F1: alpha = d ln msd / d ln t at t = 1/omega, local quadratic fit of ln msd vs ln t over +-0.25 decade (Decision)",
        by_omega(r.mason.alpha));
  t.add("alpha_se", "1", "jackknife standard error of alpha over replicas", by_omega(r.mason_error.alpha));
  t.add("Gp_mason", "k_BT/length^3", "spec 50 F1: G' = |G*| cos(pi alpha/2), |G*| = k_BT/(pi a msd(1/omega) Gamma(1 + alpha)); NaN where the fit has < 4 lags",
        by_omega(r.mason.storage));
  t.add("Gp_mason_se", "k_BT/length^3", "jackknife standard error of Gp_mason over replicas", by_omega(r.mason_error.storage));
  t.add("Gpp_mason", "k_BT/length^3", "spec 50 F1: G'' = |G*| sin(pi alpha/2)", by_omega(r.mason.loss));
  t.add("Gpp_mason_se", "k_BT/length^3", "jackknife standard error of Gpp_mason over replicas", by_omega(r.mason_error.loss));
  t.add("curvature", "1", "beta = d^2 ln msd / d(ln t)^2 at t = 1/omega, from the same local quadratic fit", by_omega(r.mason2.curvature));
  t.add("curvature_se", "1", "jackknife standard error of curvature over replicas", by_omega(r.mason2_error.curvature));
  t.add("Gp_mason2", "k_BT/length^3",
        "Re G* of the GSER to second order (docs/analysis.md): G* = k_BT/(pi a msd(1/omega) Gamma(1 + alpha) e^{-i pi alpha/2} "
        "[1 + (beta/2)((psi(1 + alpha) - i pi/2)^2 + psi_1(1 + alpha))]), beta = curvature",
        by_omega(r.mason2.storage));
  t.add("Gp_mason2_se", "k_BT/length^3", "jackknife standard error of Gp_mason2 over replicas", by_omega(r.mason2_error.storage));
  t.add("Gpp_mason2", "k_BT/length^3", "Im G* of the GSER to second order", by_omega(r.mason2.loss));
  t.add("Gpp_mason2_se", "k_BT/length^3", "jackknife standard error of Gpp_mason2 over replicas", by_omega(r.mason2_error.loss));
  t.add("Gp_evans", "k_BT/length^3",
        "spec 50 F2: Re G*, i omega/G* = (1 - e^{-i omega t_1}) J_1/t_1 + eta_inf^-1 e^{-i omega t_N} + sum_k (dJ_k/dt_k)(e^{-i omega t_{k-1}} - e^{-i omega t_k}), "
        "J = (pi a/k_BT) msd, J(0) = 0, eta_inf^-1 = (pi a/k_BT) 6 D_long; t_N = the end of the D_long fit window (or evans_t_max), J linear with slope eta_inf^-1 beyond",
        by_omega(r.evans.storage));
  t.add("Gp_evans_se", "k_BT/length^3", "jackknife standard error of Gp_evans over replicas (D_long refitted per leave-one-out sample)",
        by_omega(r.evans_error.storage));
  t.add("Gpp_evans", "k_BT/length^3", "spec 50 F2: Im G* of the compliance method", by_omega(r.evans.loss));
  t.add("Gpp_evans_se", "k_BT/length^3", "jackknife standard error of Gpp_evans over replicas", by_omega(r.evans_error.loss));

  const nlohmann::json window = {{"fit_t_min", r.fit_t_min}, {"fit_t_max", r.fit_t_max},
                                 {"window", r.fit_window_automatic ? "automatic: last decade of lags with >= 20 independent origins (spec 50 A3)" : "given"},
                                 {"mean_beta_in_window", r.fit_mean_beta}, {"beta_within_0.05_of_1", std::abs(r.fit_mean_beta - 1.0) <= 0.05},
                                 {"samples", r.samples}, {"tracers_per_replica", r.tracers}, {"radius", r.radius}, {"kT", r.kT},
                                 {"evans_t_N", r.evans_t_max}};
  Scalar d{"D_long", r.d_long.value, r.d_long.error, "length^2/tau",
           "spec 50 A3: slope of the 3-D tracer msd against t over the fit window / 6; the Evans eta_inf^-1 = (pi a/k_BT) 6 D_long", window};
  d.details["method"] = "ordinary least squares on the replica-mean MSD; error by jackknife over replicas";
  run.out.scalar(d);
  const double eta = r.kT / (6.0 * std::numbers::pi * r.radius * r.d_long.value);
  run.out.scalar({"eta_long", eta, eta * r.d_long.error / r.d_long.value, "k_BT tau/length^3",
                  "long-time (zero-shear) viscosity from Stokes-Einstein, k_BT/(6 pi a D_long)", window});
  run.out.scalar({"fit_t_min", r.fit_t_min, 0.0, "tau", "start of the D_long fit window", window});
  run.out.scalar({"fit_t_max", r.fit_t_max, 0.0, "tau", "end of the D_long fit window", window});
  if (!run.opt.quiet)
    std::fprintf(stderr, "anisodyn-microrheology: D_long = %.5g ± %.2g over t in [%.4g, %.4g] (mean beta %.3f), %zu samples\n", r.d_long.value,
                 r.d_long.error, r.fit_t_min, r.fit_t_max, r.fit_mean_beta, r.samples);
}

void run_passive(StageRun& run) {
  PassiveMicrorheologySettings s = parse_passive_microrheology_settings(run.cfg);
  run.cfg.finish();
  select_species(run.inputs.front(), s.species, run.opt.config_name(), "species");
  s.radius = resolve_tracer_radius(s, io::H5mdReader(run.inputs.front()).species(), run.opt.config_name());
  PassiveMicrorheology p(s, run.inputs.size(), run.opt.config_name());
  TrajectoryNeeds needs;
  needs.positions = true;
  needs.min_frames = 2;  // one lag
  run.each_replica(needs, [&](const Trajectory& t, std::size_t) { p.accumulate(t); });
  write_passive(run, p.compute());
}

void write_friction(StageRun& run, const ActiveResult& r, const nlohmann::json& details) {
  Table& t = run.out.table("friction_replicas", "steady tracer velocity per replica (spec 50 F3), in input order");
  using Replica = std::decay_t<decltype(r.replicas.front())>;
  const double drive = r.D_s * r.beta_force;
  t.add("replica", "1", "index of the input trajectory", index_column(r.replicas.size()));
  t.add("velocity", "length/tau",
        "spec 50 F3: end-to-end drift over the steady part, [(r(t_end) - r(t_start)).e] / (t_end - t_start), the maximum-likelihood "
        "drift of a random walk", column_of(r.replicas, &Replica::velocity));
  t.add("velocity_path_se", "length/tau",
        "error of that drift from the path's own increments, sqrt(sigma^2/(t_end - t_start)) with sigma^2 their variance per unit time "
        "(assumes uncorrelated increments: indicative only)", column_of(r.replicas, &Replica::velocity_error));
  t.add("displacement", "length", "(r(t_end) - r(t_start)).e", column_of(r.replicas, &Replica::displacement));
  t.add("t_start", "tau", "start of the steady part: first time the tracer has moved steady_distance (Decision: 2 sigma) along e, or steady_from",
        column_of(r.replicas, &Replica::t_start));
  t.add("t_end", "tau", "last time of the path", column_of(r.replicas, &Replica::t_end));
  t.add("points", "1", "path points in the steady part", column_of(r.replicas, &Replica::points));
  t.add("gamma_eff_over_gamma0", "1", "D_s beta F / velocity of this replica alone (NaN at zero force)",
        column_of(r.replicas, [&](const Replica& p) { return drive > 0.0 ? drive / p.velocity : std::nan(""); }));

  nlohmann::json d = details;
  d["method"] = "D_s beta F / <v>, <v> = sum of steady displacements / sum of steady durations over replicas (each replica's end-to-end "
                "drift, pooled); errors by jackknife over replicas (consecutive time blocks of the steady part for one replica)";
  d["samples"] = r.velocity_samples;
  d["beta_force"] = r.beta_force;
  d["D_s"] = r.D_s;
  d["path_source"] = r.path_source;
  d["velocity_replica_mean"] = r.replica_velocity.value;
  d["velocity_replica_se"] = r.replica_velocity.error;
  run.out.scalar({"gamma_eff_over_gamma0", r.gamma_ratio.value, r.gamma_ratio.error, "1",
                  "spec 50 F3: gamma_eff/gamma_0 = D_s beta F / <v_z> (NaN: undefined at zero force, Pe = 0)", d});
  run.out.scalar({"mean_velocity", r.velocity.value, r.velocity.error, "length/tau",
                  "steady tracer velocity <v_z> along the force, sum of displacements / sum of durations over replicas; jackknife error", d});
  run.out.scalar({"velocity_replica_sd", r.velocity_scatter, 0.0, "length/tau",
                  "standard deviation of the per-replica (or per-block) steady velocities: the scatter behind the jackknife error of "
                  "mean_velocity (about sd/sqrt(samples) when the steady parts are of similar length)", d});
  if (!run.opt.quiet)
    std::fprintf(stderr,
                 "anisodyn-microrheology: gamma_eff/gamma_0 = %.5g ± %.2g (<v> = %.5g ± %.2g jackknife; per-sample sd %.3g, sd/sqrt(n) %.2g; "
                 "D_s beta F = %.5g, %zu samples)\n",
                 r.gamma_ratio.value, r.gamma_ratio.error, r.velocity.value, r.velocity.error, r.velocity_scatter, r.replica_velocity.error,
                 drive, r.velocity_samples);
}

void write_density_map(StageRun& run, const ActiveResult& r, const nlohmann::json& details) {
  const DensityMapGrid& g = r.grid;
  std::vector<double> dz, rho, dens, dens_se, order, count;
  for (std::size_t k = 0; k < g.nz; ++k)
    for (std::size_t m = 0; m < g.nrho; ++m) {
      const std::size_t b = k * g.nrho + m;
      dz.push_back(g.dz_centre(k));
      rho.push_back(g.rho_centre(m));
      dens.push_back(r.density[b]);
      dens_se.push_back(r.density_error[b]);
      order.push_back(r.order[b]);
      count.push_back(r.particle_frames[b]);
    }
  Table& t = run.out.table("density_map", "spec 50 F4: axisymmetric bath density around the tracer, long format (one row per (dz, rho_c) bin), "
                                          "averaged over steady frames and replicas");
  t.add("dz", "length", "bin centre of dz = (r_j - r_tracer).e, minimum image, +dz = force direction (upstream); bin width " + std::to_string(g.dz) + " (Decision 0.25)", dz);
  t.add("rho_c", "length", "bin centre of the distance of the bath centre from the line through the tracer along e; bin width " + std::to_string(g.drho), rho);
  t.add("density", "1", "spec 50 F4: rho(dz, rho_c)/rho_bath, counts / (pi[(rho_c+d rho)^2 - rho_c^2] d z) / (N_c/V)", dens);
  t.add("density_se", "1", "standard error of density over replicas (time blocks for one replica)", dens_se);
  t.add("U", "1", "largest eigenvalue of the Q tensor of the chosen body axis of the bath particles in the bin, pooled over frames and replicas "
                  "(NaN for spherical baths or empty bins; finite-count bias ~ count^-1/2)", order);
  t.add("particle_frames", "1", "bath particle-frames counted in the bin (pooled)", count);

  std::vector<double> axis_dz;
  for (std::size_t k = 0; k < g.nz; ++k) axis_dz.push_back(g.dz_centre(k));
  Table& a = run.out.table("on_axis", "spec 50 F4: on-axis density profile rho(dz, rho_c < " + std::to_string(r.on_axis_radius_used) + ")/rho_bath");
  a.add("dz", "length", "bin centre of dz (+dz = force direction)", axis_dz);
  a.add("density", "1", "density in the cylinder rho_c < on_axis_radius (whole rho bins) / rho_bath", r.on_axis);
  a.add("density_se", "1", "standard error over replicas (time blocks for one replica)", r.on_axis_error);

  nlohmann::json d = details;
  d["threshold"] = "first recovery of the on-axis density to 0.9 rho_bath behind the tracer (Decision), linear interpolation between bin centres";
  d["on_axis_radius"] = r.on_axis_radius_used;
  d["samples"] = r.map_samples;
  d["steady_frames"] = r.steady_frames;
  d["bath_particles"] = r.bath_particles;
  run.out.scalar({"wake_length", r.wake_length.value, r.wake_length.error, "length",
                  "spec 50 F4: distance behind the tracer where the on-axis density first recovers to the threshold (NaN: never); error by jackknife", d});
}

/// Whether any bath species has an orientation worth a local order parameter.
bool bath_is_anisotropic(const SpeciesTable& table, const ActiveMicrorheologySettings& s) {
  for (const auto& sp : table)
    if (sp.name != s.species && (s.bath_species.empty() || sp.name == s.bath_species) && sp.shape.is_anisotropic()) return true;
  return false;
}

void run_active(StageRun& run) {
  ActiveMicrorheologySettings s = parse_active_microrheology_settings(run.cfg);
  run.cfg.finish();
  nlohmann::json details = nlohmann::json::object();
  SpeciesTable table;
  {
    io::H5mdReader reader(run.inputs.front());
    table = reader.species();
    resolve_active_defaults(s, table, reader.parameters(), run.opt.config_name(), details);
  }
  TrajectoryNeeds needs;
  needs.positions = true;
  needs.orientations = s.density_map && s.order_axis >= 0 && bath_is_anisotropic(table, s);
  if (s.source != TracerPathSource::Frames) needs.observables.push_back("tracer_position");
  ActiveMicrorheology a(s, run.inputs.size(), run.opt.config_name());
  // Each replica's drift is measured on its own time axis: runs of the same cycles map to different
  // Brownian times (their preliminary balances differ), and runs given in time hold different frames.
  run.each_replica(needs, [&](const Trajectory& t, std::size_t) { a.accumulate(t); }, kIndependentTimes);
  const ActiveResult r = a.compute();
  write_friction(run, r, details);
  if (r.has_map) write_density_map(run, r, details);
  else if (!run.opt.quiet && s.density_map)
    std::fprintf(stderr, "anisodyn-microrheology: no bath particles: no density map\n");
}

tool::Description description() {
  using tool::optional;
  return analysis_description(
      {tool::required("mode", "string", "passive | active"),
       tool::required("species", "string", "the tracer species"),
       optional("radius", "number", nullptr, "tracer radius (or tracer_diameter; none: half the sphere's diameter)"),
       optional("tracer_diameter", "number", nullptr, "tracer diameter (or radius)"),
       optional("kT", "number", 1.0, "passive: thermal energy; active: converts force into beta_force"),
       optional("alpha_fit_decades", "number", 0.25, "passive: half width of the local fit of alpha"),
       optional("fit", "object", nullptr, "passive: {t_min, t_max} of the D_long fit (none: as anisodyn-msd)"),
       optional("evans_t_max", "number", nullptr, "passive: end of the Evans sum (none: the end of the D_long window)"),
       optional("beta_force", "number", nullptr, "active: the force beta F (or force, or pe; none: the run's tracer.pe)"),
       optional("force", "number", nullptr, "active: the force F, with kT"),
       optional("pe", "number", nullptr, "active: the Peclet number"),
       optional("D_s", "number", nullptr, "active: tracer diffusion coefficient (none: from the species table)"),
       optional("direction", "array", nullptr, "active: the pulling direction, a box axis (none: the run's tracer axis)"),
       optional("steady_distance", "number", nullptr, "active: distance after which the motion is steady (none: 2 sigma)"),
       optional("steady_from", "number", nullptr, "active: time from which the motion is steady (instead of steady_distance)"),
       optional("position_source", "string", "auto", "active: auto | frames | observable"),
       optional("density_map", "boolean", true, "active: the density map around the tracer"),
       optional("bath_species", "string", nullptr, "active: species of the density map (none: every other species)"),
       optional("bin_width", "number", 0.25, "active: bin width of the density map"),
       optional("dz_bin", "number", nullptr, "active: bin width along the force (none: bin_width)"),
       optional("rho_bin", "number", nullptr, "active: radial bin width (none: bin_width)"),
       optional("on_axis_radius", "number", 0.5, "active: radius of the on-axis profile"),
       optional("wake_threshold", "number", 0.9, "active: density ratio that ends the wake"),
       optional("order_axis", "string", "L", "active: body axis of the local order (T | W | L | none)")},
      "passive: table moduli (Mason, second-order GSER, Evans); active: friction, density map, on-axis profile, wake length",
      lag_grid_parameters("passive"));
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-microrheology", "passive (GSER and compliance) and active (pulled tracer) microrheology over replicas",
                            "Each mode reads only its own keys (docs/analysis.md).", description()};
  return run_analysis_stage(argc, argv, info, [](StageRun& run) {
    const std::string mode = run.cfg.choice("mode", {"passive", "active"});
    if (mode == "passive") run_passive(run);
    else run_active(run);
  });
}
