// anisodyn-vanhove: self van Hove functions at requested lag times, translational per component
// and angular per body axis, each with its Gaussian reference at the same time (spec 50 A6, B2).
#include <cstdio>

#include "anisodyn/analysis/per_species_stage.hpp"
#include "anisodyn/analysis/van_hove.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

tool::Description description() {
  using tool::optional;
  return analysis_description(
      {optional("species", "string", nullptr, "the species to analyse (none: every species)"),
       tool::required("times", "array", "lag times (the nearest lag class is used)"),
       optional("components", "array", nlohmann::json::array({"tot", "x", "y", "z"}), "any of tot, x, y, z, par, perp"),
       optional("direction", "array", nlohmann::json::array({0, 0, 1}), "the reference direction of par and perp"),
       optional("bin_width", "number", nullptr, "translational bin width (none: 0.02 <dr^2>^1/2 of the first replica)"),
       optional("bins", "integer", 500, "translational bins"),
       optional("angular_axes", "array", nullptr, "body axes (T, W, L) of angular van Hove functions (none: no angular ones)"),
       optional("angular_bin_width", "number", 0.02, "angular bin width (rad)"),
       optional("angular_dimension", "integer", 2, "dimension of the angular Gaussian reference (1, 2 or 3)")},
      "table vanhove_<species> (long format, with the Gaussian reference) and the scalar vanhove_curves_<species>",
      lag_grid_parameters());
}

void write_curves(StageRun& run, const SelectedSpecies& sp, const std::vector<VanHoveCurve>& curves) {
  Table& t = run.out.table("vanhove_" + sp.name,
                           "self van Hove functions of species " + sp.name + " (spec 50 A6, B2), long format");
  std::vector<double> time, comp_index, dim, r, g, ge, gauss;
  nlohmann::json legend = nlohmann::json::array();
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const auto& cv = curves[c];
    legend.push_back({{"index", c}, {"component", cv.component}, {"time", cv.time}, {"mean_square", cv.mean_square},
                      {"overflow_fraction", cv.overflow}, {"dimension", cv.dimension}});
    for (std::size_t j = 0; j < cv.r.size(); ++j) {
      time.push_back(cv.time); comp_index.push_back(static_cast<double>(c)); dim.push_back(cv.dimension);
      r.push_back(cv.r[j]); g.push_back(cv.g[j]); ge.push_back(cv.g_error[j]); gauss.push_back(cv.gaussian[j]);
    }
    if (!run.opt.quiet && cv.overflow > 1e-3)
      std::fprintf(stderr, "anisodyn-vanhove: warning: %s at t = %.4g: %.2g%% of displacements beyond the last bin (raise bins)\n",
                   cv.component.c_str(), cv.time, 100 * cv.overflow);
  }
  t.add("time", "tau", "lag time used (the lag class nearest the requested time)", time);
  t.add("curve", "1", "index of the curve (component and time) in the scalar 'vanhove_curves_<species>' details", comp_index);
  t.add("dimension", "1", "dimension d of the component (angular: of the Gaussian reference)", dim);
  t.add("r", "length or rad", "bin centre of |dr_l| (translational) or |dphi| (angular)", r);
  t.add("G", "length^-d or rad^-3", "spec 50 A6: G_s with int v_d G dr = 1 (v_1 = 2, v_2 = 2 pi r, v_3 = 4 pi r^2); angular B2: int 4 pi phi^2 G dphi = 1", g);
  t.add("G_se", "length^-d or rad^-3", "standard error of G over replicas (or origin blocks)", ge);
  t.add("G_gaussian", "length^-d or rad^-3", "Gaussian reference with the same <dr_l^2> at the same t, bin-averaged in the same normalisation", gauss);
  run.out.scalar({"vanhove_curves_" + sp.name, static_cast<double>(curves.size()), 0.0, "1",
                  "number of van Hove curves; details list each curve's component, time, mean square and overflow", {{"curves", legend}}});
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-vanhove", "self van Hove functions (translational and angular) with Gaussian references",
                            "See docs/analysis.md.", description()};
  return run_analysis_stage(argc, argv, info, [](StageRun& run) {
    const VanHoveSettings settings = parse_van_hove_settings(run.cfg);
    run.cfg.finish();
    TrajectoryNeeds needs;
    needs.positions = true;
    needs.min_frames = 2;  // one lag
    needs.orientations = !settings.angular_axes.empty();
    if (needs.orientations) needs.optional_elements = {"rotation_vector"};
    run_per_species(
        run, {settings.species}, needs, [&] { return VanHoveAnalysis(settings, run.inputs.size()); },
        [&](const SelectedSpecies& sp, VanHoveAnalysis& a, const std::vector<double>&) { write_curves(run, sp, a.compute()); });
  });
}
