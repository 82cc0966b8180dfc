// anisodyn-msd: translational MSD family over replicas (spec 50 §1.1–1.5): total, per box axis,
// parallel/perpendicular to a director, field or the particle's own axis, body-frame components;
// non-Gaussian parameter, apparent exponent, long-time D with its fit window. See docs/analysis.md.
#include <cstdio>

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
  }
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

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-msd", "mean-squared displacements, non-Gaussian parameter and diffusion coefficients over replicas",
                          "Configuration keys: inputs, species, reference (axes | director | field | particle_axis), "
                          "direction, axis (T W L | auto), director_species (spheres: whose director), body_frame, lags_per_decade, max_origins, fit {t_min, t_max}, "
                          "ngp_constant, beta_smoothing_decades, window {from, to, stride}, csv. See docs/analysis.md."};
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
