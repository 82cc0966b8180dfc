// anisodyn-viscosity: the Green–Kubo shear viscosity of spec 30 §7 (study C1) from the stress
// autocorrelation that anisodyn-dpd records with its `green_kubo` key: the running integral η(t)
// of the total stress and of each part, the plateau η over [t_min, t_max] with the standard error
// over the blocks of every input run.
#include <cstdio>

#include "anisodyn/analysis/green_kubo.hpp"
#include "anisodyn/analysis/stage.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

GreenKuboSettings parse_settings(StageRun& run) {
  GreenKuboSettings s;
  if (auto plateau = run.cfg.optional_object("plateau")) {
    s.plateau_t_min = plateau->non_negative("t_min", s.plateau_t_min);
    s.plateau_t_max = plateau->positive("t_max", s.plateau_t_max);
    plateau->finish();
    if (!(s.plateau_t_max > s.plateau_t_min)) run.fail("plateau.t_max", "expected t_max > t_min");
  }
  return s;
}

void write_curves(StageRun& run, const GreenKuboResult& r) {
  Table& t = run.out.table("green_kubo", "spec 30 §7: stress autocorrelation and its running integral, mean over the blocks of every run");
  t.add("time", "tau", "lag time t (the multiple-tau grid of the record)", r.lag_time);
  for (const GreenKuboPart& p : r.parts) {
    const std::string what = p.name == "total" ? "the total stress" : "the " + p.name + " part of the stress alone";
    t.add("C_" + p.name, "(kT/r_c^3)^2", "<P_ab(0) P_ab(t)> of " + what + ", mean over xy, xz, yz", p.acf);
    t.add("C_" + p.name + "_se", "(kT/r_c^3)^2", "standard error of C_" + p.name + " over the blocks", p.acf_error);
    t.add("eta_" + p.name, "kT tau/r_c^3", "(V/kT) int_0^t C_" + p.name + " dt' (trapezoid on the lag grid)", p.eta);
    t.add("eta_" + p.name + "_se", "kT tau/r_c^3", "standard error of eta_" + p.name + " over the blocks", p.eta_error);
  }
}

void write_scalars(StageRun& run, const GreenKuboResult& r, const GreenKuboSettings& s) {
  const nlohmann::json details = {{"plateau_t_min", s.plateau_t_min},
                                  {"plateau_t_max", s.plateau_t_max},
                                  {"plateau_lags", r.plateau_lags},
                                  {"blocks", r.blocks},
                                  {"runs", r.runs},
                                  {"method", "per block: mean of eta(t) over the plateau lags; mean and standard error over all blocks"}};
  for (const GreenKuboPart& p : r.parts) {
    const bool total = p.name == "total";
    run.out.scalar({total ? "eta" : "eta_" + p.name, p.plateau.mean, p.plateau.error, "kT tau/r_c^3",
                    total ? "spec 30 §7: Green-Kubo shear viscosity, plateau of eta(t) (kinetic + conservative + dissipative + random)"
                          : "plateau of the " + p.name + " part's own autocorrelation integral (no cross terms)",
                    details});
  }
  if (!run.opt.quiet && !r.parts.empty())
    std::fprintf(stderr, "anisodyn-viscosity: eta = %.5g ± %.2g over t = %.3g … %.3g (%zu blocks of %zu runs)\n", r.parts.front().plateau.mean,
                 r.parts.front().plateau.error, s.plateau_t_min, s.plateau_t_max, r.blocks, r.runs);
}

tool::Description description() {
  return analysis_description(
      {tool::optional("plateau", "object", nlohmann::json({{"t_min", 2.0}, {"t_max", 5.0}}),
                      "{t_min, t_max}: the lags whose running integral is averaged into the plateau (spec 30 §7: 2 … 5 tau)")},
      "table green_kubo (C(t) and eta(t) of the total stress and of each part, with standard errors) and scalars eta, eta_<part>");
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-viscosity", "Green-Kubo shear viscosity from a recorded stress autocorrelation",
                            "See docs/analysis.md.", description()};
  return run_analysis_stage(argc, argv, info, [](StageRun& run) {
    const GreenKuboSettings settings = parse_settings(run);
    run.cfg.finish();
    GreenKuboViscosity viscosity(settings);
    for (std::size_t k = 0; k < run.inputs.size(); ++k) {
      run.report_replica(k, run.inputs[k]);
      viscosity.add(read_stress_acf(run.inputs[k]));
    }
    const GreenKuboResult r = viscosity.compute();
    if (r.plateau_lags == 0 || r.lag_time.back() < settings.plateau_t_max)
      run.fail("plateau", "expected a plateau window inside the recorded lags (0 … " + std::to_string(r.lag_time.back()) +
                              "): raise the engine's green_kubo.max_lag or lower t_max");
    write_curves(run, r);
    write_scalars(run, r, settings);
  });
}
