// anisodyn-msd: translational MSD family over replicas (spec 50 §1.1–1.5): total, per box axis,
// parallel/perpendicular to a director, field or the particle's own axis, body-frame components;
// non-Gaussian parameter, apparent exponent, long-time D with its fit window. See docs/analysis.md.
#include <cstdio>
#include <optional>

#include "anisodyn/analysis/msd.hpp"
#include "anisodyn/analysis/per_species_stage.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

const char* kMsdDefinition = "spec 50 A1: <dr_l^2(t)> = (1/N) < sum_i |r_l,i(t0+t) - r_l,i(t0)|^2 >";

void add_component_columns(Table& t, const MsdComponent& c) {
  const std::string n = c.name;
  t.add("msd_" + n, "length^2", std::string(kMsdDefinition) + ", component " + n + " (d = " + std::to_string(c.dimension) + ")", c.msd);
  t.add("msd_" + n + "_se", "length^2", "standard error of msd_" + n + " over replicas (or origin blocks)", c.msd_error);
  t.add("msd4_" + n, "length^4", "fourth moment <dr_l^4(t)>, component " + n, c.msd4);
  t.add("ngp_" + n, "1", "spec 50 A5: alpha_2,d = <dr^4>/(c_2,d <dr^2>^2) - 1, component " + n, c.ngp);
  t.add("ngp_" + n + "_se", "1", "jackknife standard error of ngp_" + n, c.ngp_error);
  t.add("beta_" + n, "1", "spec 50 A4: d ln msd_" + n + " / d ln t (local fit over +-smoothing decades)", c.beta);
  t.add("beta_" + n + "_se", "1", "standard error of beta_" + n + " from per-replica exponents", c.beta_error);
}

/// The free-particle diffusion coefficient of a component, from the trajectory's species table
/// (infinite dilution, body axes T, W, L): the orientational average tr(D)/3 for the total and
/// the lab axes, D_k for a body axis; none for par/perp, which depend on the orientations.
std::optional<double> free_diffusion(const std::string& component, const Species& species) {
  const Vec3& D = species.D_trans;
  if (!(D.minCoeff() > 0.0)) return std::nullopt;  // not set in the trajectory
  if (component == "tot" || component == "x" || component == "y" || component == "z") return D.sum() / 3.0;
  if (component.rfind("body_", 0) == 0) return D[component.back() - 'x'];  // body_x, body_y, body_z
  return std::nullopt;
}

void write_free_diffusion(StageRun& run, const SelectedSpecies& sp, const MsdComponent& c) {
  const auto d0 = free_diffusion(c.name, sp.properties);
  if (!d0) return;
  const nlohmann::json details = {{"source", "D_trans of species " + sp.name + " in the species table of the first input trajectory"},
                                  {"D_trans", {sp.properties.D_trans.x(), sp.properties.D_trans.y(), sp.properties.D_trans.z()}}};
  run.out.scalar({"D0_" + c.name + "_" + sp.name, *d0, 0.0, "length^2/tau",
                  c.name.rfind("body_", 0) == 0 ? "free-particle D along the body axis (infinite dilution)"
                                                : "free-particle D = tr(D_trans)/3 (infinite dilution, orientational average)",
                  details});
  run.out.scalar({"D_over_D0_" + c.name + "_" + sp.name, c.diffusion.value / *d0, c.diffusion.error / *d0, "1",
                  "D_" + c.name + " / D0_" + c.name + " (error from D's alone: D0 is an input)", details});
}

void write_results(StageRun& run, const SelectedSpecies& sp, const MsdResult& r) {
  Table& t = run.out.table("msd_" + sp.name, "MSD family of species " + sp.name + " (spec 50 section 1)");
  t.add("time", "tau", "lag time t (mean over the pairs of the lag class and the replicas)", r.lag);
  t.add("origins", "1", "particle-origin pairs per replica in the lag class", r.origins);
  for (const auto& c : r.components) add_component_columns(t, c);
  for (const auto& c : r.components) {
    Scalar s;
    s.name = "D_" + c.name + "_" + sp.name;
    s.value = c.diffusion.value;
    s.error = c.diffusion.error;
    s.units = c.name.rfind("body", 0) == 0 || c.name == "tot" || c.name == "x" || c.name == "y" || c.name == "z" || c.name == "par" || c.name == "perp"
                  ? "length^2/tau" : "";
    s.definition = "spec 50 A3: slope of msd_" + c.name + " against t over the fit window / (2 d), d = " + std::to_string(c.dimension);
    s.details = {{"fit_t_min", r.fit_t_min}, {"fit_t_max", r.fit_t_max}, {"window", r.fit_window_automatic ? "automatic: last decade of lags with >= 20 independent origins" : "given"},
                 {"method", "ordinary least squares on the replica-mean MSD; error by jackknife over replicas (origin blocks for one replica)"},
                 {"mean_beta_in_window", r.fit_mean_beta}, {"beta_within_0.05_of_1", std::abs(r.fit_mean_beta - 1.0) <= 0.05},
                 {"samples", r.samples}};
    run.out.scalar(s);
    write_free_diffusion(run, sp, c);
  }
  const nlohmann::json ratio_details = {{"fit_t_min", r.fit_t_min}, {"fit_t_max", r.fit_t_max}, {"samples", r.samples},
                                        {"method", "ratio of the fitted slopes; jackknife over replicas (origin blocks for one replica)"}};
  if (r.par_over_perp)
    run.out.scalar({"D_par_over_D_perp_" + sp.name, r.par_over_perp->value, r.par_over_perp->error, "1",
                    "D_par / D_perp (lab frame, to the reference at the time origin)", ratio_details});
  if (r.body_par_over_perp)
    run.out.scalar({"D_body_par_over_perp_" + sp.name, r.body_par_over_perp->value, r.body_par_over_perp->error, "1",
                    "D_body_z / ((D_body_x + D_body_y)/2): a rod's D_par/D_perp in its body frame", ratio_details});
  for (std::size_t k = 0; k < r.directors.size(); ++k) {
    nlohmann::json details = {{"director", {r.directors[k].x(), r.directors[k].y(), r.directors[k].z()}}};
    if (!r.director_species.empty()) details["director_species"] = r.director_species;  // spheres take the bath's
    run.out.scalar({"director_order_replica" + std::to_string(k) + "_" + sp.name, r.director_order[k], 0.0, "1",
                    "largest eigenvalue U of the run-averaged Q tensor used as the reference (spec 50 section 3.1)", details});
  }
  if (!run.opt.quiet)
    std::fprintf(stderr, "anisodyn-msd: %s: D_tot = %.5g ± %.2g over t in [%.4g, %.4g] (mean beta %.3f), NGP constant: %s\n",
                 sp.name.c_str(), r.components[0].diffusion.value, r.components[0].diffusion.error, r.fit_t_min, r.fit_t_max,
                 r.fit_mean_beta, r.ngp_constant.c_str());
}

tool::Description description() {
  using tool::optional;
  return analysis_description(
      {optional("species", "string", nullptr, "the species to analyse (none: every species)"),
       optional("reference", "string", "axes", "axes | director | field | vector | particle_axis: the frame of the components"),
       optional("direction", "array", nullptr, "the direction of reference field or vector"),
       optional("axis", "string", "auto", "body axis T | W | L of reference director (auto: largest U) or particle_axis (L)"),
       optional("director_species", "string", nullptr, "for spheres with reference director: the species whose director they use"),
       optional("body_frame", "boolean", false, "also the body-frame cumulative displacement components"),
       optional("fit", "object", nullptr, "{t_min, t_max} of the D fit (none: the last decade of lags with >= 20 origins)"),
       optional("ngp_constant", "string", "auto", "auto | isotropic | anisotropic constant of the non-Gaussian parameter"),
       optional("beta_smoothing_decades", "number", 0.1, "half width of the local log-log fit of beta(t)")},
      "tables msd_<species> (MSD, NGP, beta per component) and scalars D_<component>_<species>",
      lag_grid_parameters());
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-msd", "mean-squared displacements, non-Gaussian parameter and diffusion coefficients over replicas",
                            "See docs/analysis.md.", description()};
  return run_analysis_stage(argc, argv, info, [](StageRun& run) {
    const MsdSettings settings = parse_msd_settings(run.cfg);
    run.cfg.finish();
    TrajectoryNeeds needs;
    needs.positions = true;
    needs.min_frames = 2;  // one lag
    needs.orientations = settings.reference == MsdReference::Director || settings.reference == MsdReference::ParticleAxis || settings.body_frame;
    if (settings.body_frame) needs.optional_elements = {"body_displacement"};
    run_per_species(
        run, {settings.species}, needs, [&] { return MsdAnalysis(settings, run.inputs.size(), run.opt.config_name()); },
        [&](const SelectedSpecies& sp, MsdAnalysis& a, const std::vector<double>&) { write_results(run, sp, a.compute()); });
  });
}
