// anisodyn-rotation: rotational statistics per body axis over replicas (spec 50 §2.1, §2.3): MSAD of
// the unbounded rotation vector, Legendre correlations C_1 and C_2, and D_r from both.
#include <cstdio>

#include "anisodyn/analysis/free_rotation.hpp"
#include "anisodyn/analysis/rotation.hpp"
#include "anisodyn/geometry/body_axes.hpp"
#include "anisodyn/analysis/per_species_stage.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {


/// The details of a D_r from C_n: the rule and the lags it picked (spec 50 §0: every fit records its window).
nlohmann::json correlation_fit_details(nlohmann::json details, const CorrelationFitWindow& w, const RotationSettings& s) {
  details["window"] = "lags with correlation_floor <= C_n < correlation_ceiling";
  details["correlation_floor"] = s.correlation_floor;
  details["correlation_ceiling"] = s.correlation_ceiling;
  details["fit_t_min"] = w.t_min;
  details["fit_t_max"] = w.t_max;
  details["fit_lags"] = w.lags;
  details["method"] = "ordinary least squares of ln C_n";
  return details;
}

/// D_r(φ)/D_r of spec 20 §6.1 for C1 and C2, when the species table gives a free D_r for the axis
/// (a top symmetric about it): the free value is an input, so the error is D_r(φ)'s alone.
void write_free_rotation_ratios(StageRun& run, const SelectedSpecies& sp, const AxisRotation& a) {
  const auto d0 = free_axis_rotational_diffusion(sp.properties, a.axis);
  if (!d0) return;
  const std::string n = body_axis_name(a.axis);
  const nlohmann::json details = {{"source", "D_rot of species " + sp.name + " about the two other body axes, species table of the first input"},
                                  {"D_r_free", *d0}};
  run.out.scalar({"Dr_C1_over_Dr_" + n + "_" + sp.name, a.D_c1.value / *d0, a.D_c1.error / *d0, "1",
                  "spec 20 §6.1: Dr_C1_" + n + " / free D_r (error from Dr_C1 alone)", details});
  run.out.scalar({"Dr_C2_over_Dr_" + n + "_" + sp.name, a.D_c2.value / *d0, a.D_c2.error / *d0, "1",
                  "spec 20 §6.1: Dr_C2_" + n + " / free D_r (error from Dr_C2 alone)", details});
}

void write_results(StageRun& run, const SelectedSpecies& sp, const RotationResult& r, const RotationSettings& settings) {
  Table& t = run.out.table("rotation_" + sp.name, "rotational statistics of species " + sp.name + " per body axis (spec 50 B1, B3)");
  t.add("time", "tau", "lag time t", r.lag);
  for (const auto& a : r.axes) {
    const std::string n = body_axis_name(a.axis);
    t.add("msad_" + n, "rad^2", "spec 50 B1: <|phi_" + n + "(t0+t) - phi_" + n + "(t0)|^2>, unbounded rotation vector of body axis " + n, a.msad);
    t.add("msad_" + n + "_se", "rad^2", "standard error of msad_" + n, a.msad_error);
    t.add("C1_" + n, "1", "spec 50 B3: <P_1(u_" + n + "(t0+t).u_" + n + "(t0))>", a.c1);
    t.add("C1_" + n + "_se", "1", "standard error of C1_" + n, a.c1_error);
    t.add("C2_" + n, "1", "spec 50 B3: <P_2(u_" + n + "(t0+t).u_" + n + "(t0))>", a.c2);
    t.add("C2_" + n + "_se", "1", "standard error of C2_" + n, a.c2_error);
  }
  for (const auto& a : r.axes) {
    const std::string n = body_axis_name(a.axis);
    const nlohmann::json source = {{"rotation_vectors", a.exact_rotation_vectors ? "exact (accumulated per move by the engine)" : "accumulated between frames"},
                                   {"frame_rotations_above_0.2_rad", a.violations}, {"frame_intervals", a.intervals}, {"samples", r.samples}};
    nlohmann::json msad_details = source;
    msad_details["fit_t_min"] = r.fit_t_min;
    msad_details["fit_t_max"] = r.fit_t_max;
    run.out.scalar({"Dr_msad_" + n + "_" + sp.name, a.D_msad.value, a.D_msad.error, "rad^2/tau",
                    "spec 50 B1: slope of msad_" + n + " / 4 over the fit window (a linear rod's D_r; for a body axis the mean D_r of the two other axes)", msad_details});
    run.out.scalar({"Dr_C1_" + n + "_" + sp.name, a.D_c1.value, a.D_c1.error, "rad^2/tau", "spec 50 B3: -slope of ln C1_" + n + " / 2",
                    correlation_fit_details(source, a.window_c1, settings)});
    run.out.scalar({"Dr_C2_" + n + "_" + sp.name, a.D_c2.value, a.D_c2.error, "rad^2/tau", "spec 50 B3: -slope of ln C2_" + n + " / 6",
                    correlation_fit_details(source, a.window_c2, settings)});
    write_free_rotation_ratios(run, sp, a);
    if (!run.opt.quiet)
      std::fprintf(stderr, "anisodyn-rotation: %s axis %s: D_r from MSAD %.5g ± %.2g, from C1 %.5g, from C2 %.5g%s\n", sp.name.c_str(),
                   n.c_str(), a.D_msad.value, a.D_msad.error, a.D_c1.value, a.D_c2.value,
                   a.violations ? "  (warning: some frame intervals rotate by more than 0.2 rad)" : "");
  }
}

tool::Description description() {
  using tool::optional;
  return analysis_description(
      {optional("species", "string", nullptr, "the species to analyse (none: every species)"),
       optional("axes", "array", nlohmann::json::array({"T", "W", "L"}), "body axes"),
       optional("fit", "object", nullptr, "{t_min, t_max} of the MSAD fit (none: first lag to run/20)"),
       optional("correlation_floor", "number", 0.05, "C_n fits use the lags with C_n >= this"),
       optional("correlation_ceiling", "number", 1.0, "C_n fits use the lags with C_n < this (spec 20 §6.1: 0.5)")},
      "table rotation_<species> (MSAD, C1, C2 per axis) and scalars Dr_msad_<axis>_<species>, Dr_C1_..., Dr_C2_...",
      lag_grid_parameters());
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-rotation", "rotational MSAD and Legendre correlations per body axis, with D_r",
                            "See docs/analysis.md.", description()};
  return run_analysis_stage(argc, argv, info, [](StageRun& run) {
    const RotationSettings settings = parse_rotation_settings(run.cfg);
    run.cfg.finish();
    TrajectoryNeeds needs;
    needs.orientations = true;
    needs.optional_elements = {"rotation_vector"};
    needs.min_frames = 2;  // one lag
    run_per_species(
        run, {settings.species}, needs, [&] { return RotationAnalysis(settings, run.inputs.size()); },
        [&](const SelectedSpecies& sp, RotationAnalysis& a, const std::vector<double>&) { write_results(run, sp, a.compute(), settings); });
  });
}
