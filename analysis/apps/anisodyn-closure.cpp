// anisodyn-closure: the closure check of spec 20 §9 (spec 50 §9.4) along aligned → isotropic decays:
// per frame, S⁽⁴⁾:S from the rod axes against the closure (1/5)[2 S·S + 3 S (S:S)], mean over
// replicas on the common time grid.
#include <cstdio>

#include "anisodyn/analysis/closure.hpp"
#include "anisodyn/analysis/order_parameters.hpp"
#include "anisodyn/analysis/per_species_stage.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

std::string definition_of(const std::string& name) {
  const std::string c = name.substr(name.size() - 2);
  if (name.rfind("S4S", 0) == 0) return "spec 50 I4: (S4:S)_" + c + " = (1/N) sum_n u_" + c.substr(0, 1) + " u_" + c.substr(1) + " (u.S.u), S4 = <uuuu>";
  if (name.rfind("closure", 0) == 0) return "spec 50 I4: [(1/5)(2 S.S + 3 S (S:S))]_" + c;
  return "spec 50 C3: S_" + c + " of S = (1/N) sum_n u_n u_n";
}

void write_results(StageRun& run, const SelectedSpecies& sp, const ClosureResult& r) {
  Table& t = run.out.table("closure_" + sp.name, "closure check along the decays of species " + sp.name +
                                                     ": both sides per frame, mean over replicas on the common grid (spec 20 section 9, spec 50 I4)");
  t.add("time", "tau", "common time grid: mean time stamp of each frame over the replicas (spec 50 section 0)", r.time);
  for (const auto& s : r.series) {
    t.add(s.name, "1", definition_of(s.name) + "; replicas linearly interpolated onto the common grid", s.mean);
    t.add(s.name + "_se", "1", "standard error of " + s.name + " over replicas (n - 1; NaN for one replica)", s.error);
  }
  run.out.scalar({"rods_" + sp.name, static_cast<double>(r.rods), 0.0, "1", "rods per frame", {{"replicas", r.replicas}}});
  if (!run.opt.quiet) std::fprintf(stderr, "anisodyn-closure: %s: %zu frames, %zu replicas\n", sp.name.c_str(), r.time.size(), r.replicas);
}

tool::Description description() {
  using tool::optional;
  return analysis_description({optional("species", "string", nullptr, "the rod species (none: every anisotropic species)"),
                               optional("rod_axis", "string", "L", "body axis of the rods")},
                              "table closure_<species>: time, S, S4:S and the closure (xx, yy, zz) per frame");
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-closure", "closure check of the Doi-Edwards-Kuzuu equation along order-tensor decays",
                            "See docs/analysis.md.", description()};
  return run_analysis_stage(argc, argv, info, [](StageRun& run) {
    const std::string species = run.cfg.string("species", "");
    const int rod_axis = parse_body_axis(run.cfg, "rod_axis", "L", false);
    run.cfg.finish();
    TrajectoryNeeds needs;
    needs.orientations = true;
    run_per_species(
        run, {species, SpeciesScope::Oriented}, needs, [&] { return ClosureAnalysis(rod_axis); },
        [&](const SelectedSpecies& sp, ClosureAnalysis& a, const std::vector<double>& grid) { write_results(run, sp, a.compute(grid)); });
  });
}
