// anisodyn-order: orientational order over time and its run average (spec 50 §3.1–3.4): per-axis
// uniaxial order U_T, U_W, U_L, biaxial order B_2,K, rod order tensor, cube order S^(tot) (and
// S^(c), S^(free) with a dipolar chain rule), the finite-N isotropic baseline and the phase verdict.
#include <algorithm>
#include <cstdio>

#include "anisodyn/analysis/order_parameters.hpp"
#include "anisodyn/analysis/per_species_stage.hpp"
#include "anisodyn/system/order.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

bool requested(const OrderStageSettings& s, const std::string& series) {
  const std::string group = series.rfind("U", 0) == 0 ? "U" : series.rfind("S_cube", 0) == 0 || series == "chain_fraction" ? "S_cube" : series;
  return std::find(s.observables.begin(), s.observables.end(), group) != s.observables.end();
}

void write_results(StageRun& run, const OrderStageSettings& settings, const SelectedSpecies& sp, const OrderResult& r) {
  Table& t = run.out.table("order_" + sp.name, "orientational order of species " + sp.name +
                                                   " against time, mean over replicas on the common grid (spec 50 section 0, 3)");
  t.add("time", "tau", "common time grid: mean time stamp of each frame over the replicas (spec 50 section 0)", r.time);
  const std::string axis_note = std::string(" (main axis K = ") + axis_letter(r.main_axis) + ")";
  for (const auto& s : r.series) {
    if (!requested(settings, s.name)) continue;
    const std::string def = s.definition + (s.name == "B2" ? axis_note : "");
    t.add(s.name, s.units, def + "; replicas linearly interpolated onto the common grid", s.mean);
    t.add(s.name + "_se", s.units, "standard error of " + s.name + " over replicas (n - 1; NaN for one replica)", s.error);
    Scalar sc;
    sc.name = s.name + "_" + sp.name;
    sc.value = s.run_average.value;
    sc.error = s.run_average.error;
    sc.units = s.units;
    sc.definition = "run average of " + def;
    sc.details = {{"error", r.replicas >= 2 ? "standard error of the replicas' run averages (n - 1)"
                                             : "block average of the single run (core/statistics block_average)"},
                  {"average_from", settings.average_from}, {"frames_averaged", r.averaged_frames},
                  {"replica_average", s.replica_average}, {"replica_block_error", s.replica_block_error}};
    run.out.scalar(sc);
  }
  run.out.scalar({"U_isotropic_baseline_" + sp.name, r.isotropic_baseline, std::nan(""), "1",
                  "spec 50 C1: mean largest eigenvalue of Q for N uniformly random orientations at the same N "
                  "(finite-N isotropic baseline, Monte Carlo over 200 sets; error not estimated)",
                  {{"particles", r.particles}}});
  const std::string phase = r.nematic ? "nematic" : "isotropic";
  run.out.scalar({"nematic_" + sp.name, r.nematic ? 1.0 : 0.0, 0.0, "1",
                  "spec 50 C1 phase criterion: 1 if the largest run-averaged eigenvalue of any Q^{kk} exceeds 0.40, else 0",
                  {{"phase", phase}, {"largest_eigenvalue", r.largest_eigenvalue}, {"threshold", kNematicThreshold},
                   {"isotropic_baseline", r.isotropic_baseline}}});
  const double b2 = r.get("B2").run_average.value;
  run.out.scalar({"main_axis_" + sp.name, static_cast<double>(r.main_axis), 0.0, "1",
                  "main axis K of B_2,K (0 T, 1 W, 2 L; spec 50 C2 Decision: given, or the axis of the largest "
                  "run-averaged U of the first replica)",
                  {{"axis", axis_letter(r.main_axis)},
                   {"choice", settings.order.main_axis < 0 ? "auto: largest run-averaged U_k of the first replica" : "given"},
                   {"first_replica_U", {r.main_axis_order.x(), r.main_axis_order.y(), r.main_axis_order.z()}},
                   {"biaxiality", b2 >= kBiaxialThreshold ? "biaxial" : b2 >= kWeaklyBiaxialThreshold ? "weakly biaxial" : "not biaxial"}}});
  if (!run.opt.quiet)
    std::fprintf(stderr, "anisodyn-order: %s: largest U = %.4f (isotropic baseline %.4f) -> %s; B2_%s = %.4f\n", sp.name.c_str(),
                 r.largest_eigenvalue, r.isotropic_baseline, phase.c_str(), axis_letter(r.main_axis), b2);
}

tool::Description description() {
  using tool::optional;
  return analysis_description(
      {optional("species", "string", nullptr, "the species to analyse (none: every anisotropic species)"),
       optional("observables", "array", nlohmann::json::array({"U", "B2", "S_rod", "S_cube"}), "order parameters to compute"),
       optional("main_axis", "string", "auto", "T | W | L | auto (largest run-averaged U of the first replica)"),
       optional("rod_axis", "string", "L", "body axis of S_rod"),
       optional("field_direction", "array", nlohmann::json::array({0, 0, 1}), "reference direction of S_cube"),
       optional("chain_threshold", "object", nullptr, "{gamma, sigma, bu_max}: splits S_cube into chains and free cubes"),
       optional("average_from", "number", nullptr, "start time of the run averages (none: the first frame)")},
      "table order_<species> (time series) and scalars: run averages, isotropic baseline, phase verdict");
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-order", "orientational order parameters over time, run averages and the phase verdict",
                            "See docs/analysis.md.", description()};
  return run_analysis_stage(argc, argv, info, [](StageRun& run) {
    const OrderStageSettings settings = parse_order_settings(run.cfg);
    run.cfg.finish();
    TrajectoryNeeds needs;
    needs.orientations = true;
    needs.positions = settings.order.chains.has_value();
    run_per_species(
        run, {settings.species, SpeciesScope::Oriented}, needs, [&] { return OrderAnalysis(settings, run.opt.config_name()); },
        [&](const SelectedSpecies& sp, OrderAnalysis& a, const std::vector<double>& grid) { write_results(run, settings, sp, a.compute(grid)); });
  });
}
