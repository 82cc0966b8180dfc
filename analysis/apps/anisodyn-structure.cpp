// anisodyn-structure: pair structure over frames and replicas (spec 50 §4.1–4.2): g(r) for like and
// unlike species pairs, g_∥(r) and g_⊥(r) about the field or the nematic director, and slab density
// profiles along x, y, z (§1.7).
#include <cstdio>

#include "anisodyn/analysis/order_parameters.hpp"
#include "anisodyn/analysis/pair_structure.hpp"
#include "anisodyn/analysis/stage.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

void write_pair(StageRun& run, const PairStructureSettings& s, const PairStructureResult& r, const PairCurves& c) {
  const std::string pair = c.a + "_" + c.b;
  const std::string err = r.blocks ? "standard error over " + std::to_string(r.samples) + " blocks of frames of the single replica"
                                   : "standard error over replicas (n - 1)";
  Table& t = run.out.table("structure_" + pair, "pair structure of " + c.a + "-" + c.b + " (spec 50 section 4), averaged over frames and replicas");
  t.add("r", "length", "bin centre; bin [r - dr/2, r + dr/2), dr = " + std::to_string(s.dr), r.r);
  t.add("g", "1", "spec 50 D1: g_AB(r) = <sum_{i in A} sum_{j in B, j != i} 1[r <= r_ij < r + dr]> / (N_A rho_B v(r)), "
                  "v = 4 pi [(r + dr)^3 - r^3]/3, minimum image", c.g);
  t.add("g_se", "1", err + " of g", c.g_se);
  t.add("coordination", "1", "running coordination number n_AB(r) = rho_B sum_{bins <= r} v g (neighbours of type B within the bin's upper edge)",
        c.coordination);
  t.add("g_par", "1", "spec 50 D2: g_par(r) = <count of r <= |r_ij.e| < r + dr, r_perp < R_par> / (N_A rho_B 2 pi R_par^2 dr) "
                      "(Decision: factor 2 for both sides); NaN where the cylinder leaves the minimum-image cell", c.g_par);
  t.add("g_par_se", "1", err + " of g_par", c.g_par_se);
  t.add("g_perp", "1", "spec 50 D2: g_perp(r) = <count of r <= r_perp < r + dr, |r_ij.e| < h_perp> / (N_A rho_B pi [(r + dr)^2 - r^2] 2 h_perp) "
                       "(Decision: factor 2); NaN where the slab leaves the minimum-image cell", c.g_perp);
  t.add("g_perp_se", "1", err + " of g_perp", c.g_perp_se);
  run.out.scalar({"particles_" + pair, static_cast<double>(c.count_a), 0.0, "1", "N_A and N_B of the pair (details)",
                  {{"N_A", c.count_a}, {"N_B", c.count_b}, {"reference", r.reference}, {"R_par", s.cylinder_radius},
                   {"h_perp", s.slab_half_height}, {"samples", r.samples}, {"frames_per_replica", r.frames_per_replica}}});
}

void write_profile(StageRun& run, const PairStructureResult& r, const SlabProfile& p, std::size_t bins) {
  const std::string err = r.blocks ? "standard error over blocks of frames of the single replica" : "standard error over replicas (n - 1)";
  Table& t = run.out.table("slab_" + p.species, "slab density profiles of species " + p.species + " (spec 50 A7), " +
                                                    std::to_string(bins) + " slabs per axis (Decision: ds = L/50 by default)");
  const char* names[3] = {"x", "y", "z"};
  for (std::size_t a = 0; a < 3; ++a) {
    const std::string n = names[a];
    t.add("s_" + n, "length", "slab centre along " + n + " (mean box edge over the frames times the fractional position)", p.s[a]);
    t.add("rho_" + n, "1", "spec 50 A7: rho_r(s) = <N_s in [s, s + ds)> / (A ds) / (N/V) along " + n +
                               ", A = V / L_" + n + " (V^(2/3) for a cubic box)", p.rho[a]);
    t.add("rho_" + n + "_se", "1", err + " of rho_" + n, p.rho_se[a]);
  }
}

tool::Description description() {
  using tool::optional;
  return analysis_description(
      {optional("pairs", "array", nullptr, "species pairs [[A, B], ...] (none: each species with itself)"),
       optional("dr", "number", 0.05, "bin width"),
       optional("r_max", "number", nullptr, "largest distance (none: half the smallest box edge)"),
       optional("reference", "string", "field", "field | director | none: the axis of g_par and g_perp"),
       optional("direction", "array", nlohmann::json::array({0, 0, 1}), "the field direction (reference field)"),
       optional("axis", "string", "auto", "body axis of the director (reference director)"),
       optional("director_species", "string", nullptr, "the species whose director is the reference (reference director)"),
       optional("cylinder_radius", "number", 0.5, "R_par of g_par"),
       optional("slab_half_height", "number", 0.5, "h_perp of g_perp"),
       optional("slab_bins", "integer", 50, "slabs per axis of the density profiles")},
      "tables structure_<A>_<B> (g, coordination, g_par, g_perp) and slab_<species>");
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-structure", "radial and directional pair correlations and slab density profiles",
                            "See docs/analysis.md.", description()};
  return run_analysis_stage(argc, argv, info, [](StageRun& run) {
    const PairStructureSettings settings = parse_structure_settings(run.cfg);
    run.cfg.finish();
    PairStructureAnalysis analysis(settings, run.inputs.size(), run.opt.config_name());
    TrajectoryNeeds needs;
    needs.positions = true;
    needs.orientations = settings.reference == PairReference::Director;
    run.each_replica(needs, [&](const Trajectory& t, std::size_t) { analysis.accumulate(t); });
    const PairStructureResult r = analysis.compute();
    for (const auto& c : r.pairs) write_pair(run, settings, r, c);
    for (const auto& p : r.profiles) write_profile(run, r, p, settings.slab_bins);
    for (std::size_t k = 0; k < r.director_axis.size(); ++k)
      run.out.scalar({"director_order_replica" + std::to_string(k), r.director_order[k], 0.0, "1",
                      "mean over the frames of the largest eigenvalue U of Q of the director axis (spec 50 section 3.1)",
                      {{"axis", axis_letter(r.director_axis[k])}}});
    if (!run.opt.quiet)
      std::fprintf(stderr, "anisodyn-structure: %zu pair(s), %zu bins up to r = %.4g, reference: %s\n", r.pairs.size(), r.r.size(),
                   r.r.empty() ? 0.0 : r.r.back() + 0.5 * settings.dr, r.reference.c_str());
  });
}
