// anisodyn-pair-distances: the effective diameter of soft rods from P_d(x), the distribution of the
// scaled axis distances x = d/D of interacting pairs that anisodyn-bd records (spec 20 §5, spec 50
// §9.5): P_d(x), ⟨x⟩, σ_x, D_eff = D⟨x⟩ and the study-B box edge (250 π L² D_eff)^(1/3).
#include <cstdio>

#include "anisodyn/analysis/pair_distances.hpp"
#include "anisodyn/analysis/species_selection.hpp"
#include "anisodyn/analysis/stage.hpp"
#include "anisodyn/core/error.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

/// The rod species whose pairs the histogram counts: the named one or the file's only anisotropic
/// species; it must be the potential's species when the run names one.
SelectedSpecies rod_species(const StageRun& run, const std::string& requested) {
  const auto species = select_species(run.inputs.front(), {requested, SpeciesScope::Oriented}, run.opt.config_name(), "species");
  if (species.size() > 1)
    run.fail("species", run.inputs.front() + " has several anisotropic species: name the rods of the potential");
  const SelectedSpecies& sp = species.front();
  if (sp.properties.shape.kind != ShapeKind::Spherocylinder || !(sp.properties.shape.length > 0))
    run.fail("species", "expected rods (spherocylinders): species '" + sp.name + "' has no rod length and diameter");
  return sp;
}

void check_potential_species(const Trajectory& t, const SelectedSpecies& sp, const std::string& config_file) {
  const auto& p = t.parameters;
  if (!p.is_object() || !p.contains("potential") || !p["potential"].is_object() || !p["potential"].contains("species") ||
      !p["potential"]["species"].is_string())
    return;
  const std::string potential = p["potential"]["species"].get<std::string>();
  if (potential != sp.name)
    throw InputError(config_file, "species", "the histogram of " + t.path + " counts the pairs of species '" + potential + "' (its potential.species), not '" + sp.name + "'");
}

void write_results(StageRun& run, const SelectedSpecies& sp, const PairDistanceResult& r) {
  Table& t = run.out.table("pair_distances_" + sp.name, "distribution P_d(x) of the scaled axis distances x = d/D of interacting rod pairs (spec 20 section 5, spec 50 I5)");
  t.add("x", "1", "bin centre of x = d/D (D the bare diameter)", r.x);
  t.add("P_d", "1", "spec 50 I5: P_d(x) = c_b/(n dx), normalised so that the integral over [0, 1] is 1; mean over replicas", r.density);
  t.add("P_d_se", "1", "standard error of P_d over replicas (n - 1; NaN for one replica)", r.density_error);
  t.add("counts", "1", "interacting pairs counted in the bin, summed over replicas", r.counts);
  const std::size_t n = r.replica_pairs.size();
  const nlohmann::json details = {{"replicas", n}, {"replica_pairs", r.replica_pairs}, {"bins", r.x.size()},
                                  {"error", n >= 2 ? "standard error over replicas (n - 1)" : "none: one replica holds one histogram of the whole run"},
                                  {"x", "bin centres"}, {"bare_diameter", r.diameter}};
  run.out.scalar({"D_eff_over_D_" + sp.name, r.mean_x.value, r.mean_x.error, "1", "spec 20 section 5: <x> = sum_b c_b x_b / sum_b c_b (D_eff/D)", details});
  run.out.scalar({"sigma_x_" + sp.name, r.sigma_x.value, r.sigma_x.error, "1", "spec 20 section 5: sigma_x = sqrt(<x^2> - <x>^2)", details});
  run.out.scalar({"D_eff_" + sp.name, r.effective_diameter.value, r.effective_diameter.error, "length",
                  "spec 20 section 5: D_eff = D <x>, D the bare diameter of the species", details});
  Estimate pairs = mean_and_error(r.replica_pairs);
  run.out.scalar({"pairs_" + sp.name, pairs.value, pairs.error, "1", "interacting pairs counted per replica (summed over the run's observation rows)", details});
  nlohmann::json box = details;
  box["rod_length"] = r.length;
  box["error"] = "jackknife over replicas";
  run.out.scalar({"box_edge_" + sp.name, r.box_edge.value, r.box_edge.error, "length",
                  "spec 20 section 1: edge of the cubic box V = 250 pi L^2 D_eff (L the rod's cylinder length)", box});
  if (!run.opt.quiet)
    std::fprintf(stderr, "anisodyn-pair-distances: %s: D_eff/D = %.5g ± %.2g, sigma_x = %.4g, box edge %.5g\n", sp.name.c_str(), r.mean_x.value,
                 r.mean_x.error, r.sigma_x.value, r.box_edge.value);
}

tool::Description description() {
  using tool::optional;
  return analysis_description({optional("species", "string", nullptr, "the rods of the potential (none: the file's only anisotropic species)")},
                              "table pair_distances_<species> (x, P_d) and scalars D_eff_over_D, sigma_x, D_eff, pairs, box_edge");
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-pair-distances", "effective rod diameter from the distribution of interacting pair distances",
                            "See docs/analysis.md.", description()};
  return run_analysis_stage(argc, argv, info, [](StageRun& run) {
    const std::string requested = run.cfg.string("species", "");
    run.cfg.finish();
    // The engine sums the histogram over the whole run: a window cannot select part of it.
    if (run.window.given) run.fail("window", "has no effect: " + kPairDistanceObservable + " is one histogram summed over the whole run");
    const SelectedSpecies sp = rod_species(run, requested);
    PairDistanceAnalysis a(sp.properties.shape.diameter, sp.properties.shape.length);
    TrajectoryNeeds needs;
    needs.observables = {kPairDistanceObservable};
    run.each_replica(needs, [&](const Trajectory& t, std::size_t) {
      check_potential_species(t, sp, run.opt.config_name());
      a.accumulate(t);
    });
    write_results(run, sp, a.compute());
  });
}
