// anisodyn-order-relaxation: collective rotational diffusion D_r^coll of rods from the order tensor
// the BD engine records (spec 20 §7, spec 50 §9.3): Method A (`decay`, from the aligned start) or
// Method B (`regression`, equilibrium fluctuations), and D_r^coll/D_r with the free-rod D_r of the
// species table.
#include <cstdio>

#include "anisodyn/analysis/order_relaxation.hpp"
#include "anisodyn/analysis/per_species_stage.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

nlohmann::json fit_details(const RelaxationFit& f, const OrderRelaxationSettings& s) {
  return {{"method", s.method == RelaxationMethod::Decay ? "decay (Method A)" : "regression (Method B)"},
          {"fit", "ordinary least squares of ln y over the window"},
          {"fit_t_min", f.t_min}, {"fit_t_max", f.t_max}, {"fit_points", f.window.size()},
          {"fit_band", {s.band_low, s.band_high}}, {"error", f.error_method}};
}

/// D_r^coll, and D_r^coll/D_r with D_r = D_rot about a perpendicular body axis (T) of the species table.
void write_rate(StageRun& run, const SelectedSpecies& sp, const RelaxationFit& fit, nlohmann::json details) {
  if (fit.window.size() < 2) details["warning"] = "fewer than 2 points in the fit window: no rate";
  run.out.scalar({"Dr_coll_" + sp.name, fit.rate.value, fit.rate.error, "1/tau",
                  "spec 50 I3: D_r^coll = -slope/6 of ln y over the fit window (y = delta S_zz for decay, C(t) for regression)", details});
  const double dr0 = sp.properties.D_rot.x();
  if (dr0 > 0)
    run.out.scalar({"Dr_coll_over_Dr0_" + sp.name, fit.rate.value / dr0, fit.rate.error / dr0, "1",
                    "D_r^coll / D_r, D_r the free-rod rotational diffusion of the species table (D_rot about T); error from D_r^coll alone",
                    {{"Dr0", dr0}}});
  if (!run.opt.quiet)
    std::fprintf(stderr, "anisodyn-order-relaxation: %s: D_r^coll = %.5g ± %.2g over t in [%.4g, %.4g] (%zu points)\n", sp.name.c_str(),
                 fit.rate.value, fit.rate.error, fit.t_min, fit.t_max, fit.window.size());
}

std::vector<double> in_window(std::size_t n, const IndexWindow& w) {
  std::vector<double> out(n, 0.0);
  for (std::size_t k = w.first; k < w.last; ++k) out[k] = 1.0;
  return out;
}

void write_decay(StageRun& run, const OrderRelaxationSettings& s, const SelectedSpecies& sp, const OrderDecayResult& r) {
  Table& t = run.out.table("order_decay_" + sp.name, "order tensor of species " + sp.name + " after the aligned start, mean over decays on the common grid (spec 50 I3, Method A)");
  t.add("time", "tau", "common time grid: mean time of each order-tensor row over the replicas (spec 50 section 0)", r.time);
  const std::vector<std::pair<std::string, std::pair<const std::vector<double>*, const std::vector<double>*>>> diagonal{
      {"xx", {&r.s_xx, &r.s_xx_error}}, {"yy", {&r.s_yy, &r.s_yy_error}}, {"zz", {&r.s_zz, &r.s_zz_error}}};
  for (const auto& [c, v] : diagonal) {
    t.add("S_" + c, "1", "S_" + c + " of S = (1/N) sum u u, mean over replicas", *v.first);
    t.add("S_" + c + "_se", "1", "standard error of S_" + c + " over replicas", *v.second);
  }
  t.add("dS_zz", "1", "spec 50 I3: delta S_zz = S_zz - 1/3", r.ds_zz);
  t.add("dS_zz_se", "1", "standard error of delta S_zz (that of S_zz)", r.s_zz_error);
  t.add("in_fit", "1", "1 for the rows of the fit window", in_window(r.time.size(), r.fit.window));
  nlohmann::json details = fit_details(r.fit, s);
  details.update({{"noise_level", r.noise}, {"noise_from", r.noise_from}, {"noise_rows", r.noise_rows}, {"noise_factor", s.noise_factor},
                  {"lower_bound_in_force", r.threshold}, {"replicas", r.replicas}});
  run.out.scalar({"dS_zz_noise_" + sp.name, r.noise, std::nan(""), "1",
                  "equilibrium noise level of delta S_zz: rms of the replica-mean delta S_zz over the rows t >= noise_from",
                  {{"noise_from", r.noise_from}, {"rows", r.noise_rows}}});
  write_rate(run, sp, r.fit, details);
}

void write_regression(StageRun& run, const OrderRelaxationSettings& s, const SelectedSpecies& sp, const OrderRegressionResult& r) {
  Table& t = run.out.table("order_correlation_" + sp.name, "equilibrium order-tensor correlation of species " + sp.name + " (spec 50 I3, Method B)");
  t.add("time", "tau", "lag t (mean over the lag class and replicas)", r.lag);
  t.add("origins", "1", "time origins summed over replicas", r.origins);
  t.add("C", "1", "spec 50 I3: C(t) = <dS(t0 + t) : dS(t0)>, dS = S - <S> (run mean), off-diagonal components counted twice", r.correlation);
  t.add("C_se", "1", "standard error of C over replicas (10 blocks of origins for one replica)", r.correlation_error);
  t.add("C_over_C0", "1", "C(t)/C(0)", r.normalised);
  t.add("C_over_C0_se", "1", "jackknife error of C(t)/C(0)", r.normalised_error);
  t.add("in_fit", "1", "1 for the lags of the fit window", in_window(r.lag.size(), r.fit.window));
  nlohmann::json details = fit_details(r.fit, s);
  details.update({{"replicas", r.replicas}, {"error_samples", r.samples}, {"rows_per_replica", r.rows}});
  write_rate(run, sp, r.fit, details);
}

tool::Description description() {
  using tool::optional;
  using tool::required;
  return analysis_description(
      {required("method", "string", "decay (Method A: aligned start) | regression (Method B: equilibrium)"),
       optional("species", "string", nullptr, "the rod species (none: every anisotropic species)"),
       optional("fit_band", "array", nullptr, "[low, high] of delta S_zz (decay; default [0.02, 0.1]) or C/C(0) (regression; default [0.05, 0.5])"),
       optional("noise_from", "number", nullptr, "decay: start of the rows the noise level is measured on (none: the last quarter of the run)"),
       optional("noise_factor", "number", 3, "decay: the fit needs delta S_zz above this multiple of the noise level")},
      "table order_decay_<species> or order_correlation_<species>, scalars Dr_coll_<species>, Dr_coll_over_Dr0_<species>",
      lag_grid_parameters("regression"));
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-order-relaxation", "collective rotational diffusion from the order tensor (decay or regression)",
                            "See docs/analysis.md.", description()};
  return run_analysis_stage(argc, argv, info, [](StageRun& run) {
    const OrderRelaxationSettings settings = parse_order_relaxation_settings(run.cfg);
    run.cfg.finish();
    const SpeciesRequest request{settings.species, SpeciesScope::Oriented};
    TrajectoryNeeds needs;
    for (const auto& sp : select_species(run.inputs.front(), request, run.opt.config_name(), "species"))
      needs.observables.push_back(order_tensor_observable(sp.name));
    run_per_species(
        run, request, needs,
        [&] { return OrderRelaxationAnalysis(settings, run.inputs.size(), run.opt.config_name()); },
        [&](const SelectedSpecies& sp, OrderRelaxationAnalysis& a, const std::vector<double>&) {
          if (settings.method == RelaxationMethod::Decay) write_decay(run, settings, sp, a.decay());
          else write_regression(run, settings, sp, a.regression());
        });
  });
}
