// anisodyn-restoring-torque: Method III of spec 20 §6.3 (study B3): the self-rotational diffusion
// D_r(φ) of rods from the restoring torque T̄ (the `systematic_torque` element of anisodyn-bd's
// frames): βT_r(t), D_r(φ, t) from n = 1 and 2, their plateau D_r(φ) and D_r(φ)/D_r, and the direct
// against the reconstructed ⟨û(t)·û(0)⟩.
#include <cstdio>

#include "anisodyn/analysis/bd_caps.hpp"
#include "anisodyn/analysis/free_rotation.hpp"
#include "anisodyn/analysis/per_species_stage.hpp"
#include "anisodyn/analysis/restoring_torque.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

void write_curves(StageRun& run, const SelectedSpecies& sp, const RestoringTorqueResult& r) {
  Table& t = run.out.table("restoring_torque_" + sp.name, "Method III (spec 20 §6.3) for the rods of species " + sp.name);
  t.add("time", "tau", "lag time t", r.lag);
  t.add("C1", "1", "spec 50 B3: <u(t0+t).u(t0)>, direct", r.c1);
  t.add("C1_se", "1", "standard error of C1", r.c1_error);
  t.add("C2", "1", "spec 50 B3: <P_2(u(t0+t).u(t0))>, direct", r.c2);
  t.add("C2_se", "1", "standard error of C2", r.c2_error);
  t.add("betaT_r", "1", "spec 20 §6.3: beta <(u(t) x u(0)).T(t)> / <u(t).u(0)>, T the systematic torque at the later time", r.beta_torque);
  t.add("betaT_r_se", "1", "jackknife error of betaT_r", r.beta_torque_error);
  t.add("Dr_t", "rad^2/tau", "spec 20 §6.3: D_r(phi, t) = D_r [1 - betaT_r / 2] (= -d ln C1/dt / 2)", r.dr1);
  t.add("Dr_t_se", "rad^2/tau", "jackknife error of Dr_t", r.dr1_error);
  t.add("Dr2_t", "rad^2/tau", "spec 20 §6.3, n = 2: D_r [1 - beta <P_2'(x) (u(t) x u(0)).T(t)> / (6 C2)] (= -d ln C2/dt / 6)", r.dr2);
  t.add("Dr2_t_se", "rad^2/tau", "jackknife error of Dr2_t", r.dr2_error);
  t.add("C1_reconstructed", "1", "spec 20 §6.3: exp[-2 int_0^t Dr_t dt'], trapezoid on the lags from Dr_t(0) = D_r", r.c1_reconstructed);
  t.add("C1_reconstructed_se", "1", "jackknife error of C1_reconstructed", r.c1_reconstructed_error);
}

void write_scalars(StageRun& run, const SelectedSpecies& sp, const RestoringTorqueResult& r, const RestoringTorqueSettings& s) {
  nlohmann::json details = {{"plateau_t_min", r.plateau_t_min},
                            {"plateau_t_max", r.plateau_t_max},
                            {"plateau_lags", r.plateau_lags},
                            {"plateau_rule", s.plateau_window ? "configured plateau {t_min, t_max}" : "lags with floor <= C1 <= ceiling"},
                            {"method", "unweighted mean of the curve over the plateau lags, jackknife error"},
                            {"D_r_free", r.free_dr},
                            {"D_r_free_source", "D_rot of species " + sp.name + " about a perpendicular axis, species table of the first input"},
                            {"samples", r.samples}};
  if (!s.plateau_window) details["plateau_correlation"] = {{"floor", s.plateau_floor}, {"ceiling", s.plateau_ceiling}};
  // T̄ is recorded before the caps; the caps changed the dynamics this many particle-steps.
  details["capped_torques"] = r.capped_known ? nlohmann::json(r.capped_torques) : nlohmann::json("not recorded");
  const std::string n = "_" + sp.name;
  const double d0 = r.free_dr;
  run.out.scalar({"Dr_phi" + n, r.dr1_plateau.value, r.dr1_plateau.error, "rad^2/tau", "spec 20 §6.3: plateau of Dr_t (n = 1)", details});
  run.out.scalar({"Dr_phi_over_Dr" + n, r.dr1_plateau.value / d0, r.dr1_plateau.error / d0, "1",
                  "spec 20 §6.3: D_r(phi)/D_r (n = 1; D_r the free-rod input, error from D_r(phi) alone)", details});
  run.out.scalar({"Dr2_phi" + n, r.dr2_plateau.value, r.dr2_plateau.error, "rad^2/tau", "spec 20 §6.3: plateau of Dr2_t (n = 2)", details});
  run.out.scalar({"Dr2_phi_over_Dr" + n, r.dr2_plateau.value / d0, r.dr2_plateau.error / d0, "1",
                  "spec 20 §6.3: D_r(phi)/D_r from n = 2 (error from D_r(phi) alone)", details});
  run.out.scalar({"betaT_r_plateau" + n, r.beta_torque_plateau.value, r.beta_torque_plateau.error, "1",
                  "spec 20 §6.3: plateau of betaT_r = 2 (1 - D_r(phi)/D_r)", details});
  run.out.scalar({"Dr_free" + n, d0, 0.0, "rad^2/tau", "free-rod D_r of the species table (the normalisation)", details});
  if (!run.opt.quiet)
    std::fprintf(stderr, "anisodyn-restoring-torque: %s: D_r(phi)/D_r = %.5g ± %.2g (n = 1), %.5g ± %.2g (n = 2) over t = %.4g … %.4g\n",
                 sp.name.c_str(), r.dr1_plateau.value / d0, r.dr1_plateau.error / d0, r.dr2_plateau.value / d0,
                 r.dr2_plateau.error / d0, r.plateau_t_min, r.plateau_t_max);
}

tool::Description description() {
  using tool::optional;
  return analysis_description(
      {optional("species", "string", nullptr, "the rod species to analyse (none: every anisotropic species)"),
       optional("plateau", "object", nullptr, "{t_min, t_max}: the lags of the plateau D_r(phi) (none: plateau_correlation)"),
       optional("plateau_correlation", "object", nlohmann::json({{"floor", 0.05}, {"ceiling", 0.5}}),
                "without plateau: the plateau is the lags with floor <= C1 <= ceiling")},
      "table restoring_torque_<species> (C1, C2, betaT_r, D_r(phi, t) for n = 1, 2, reconstructed C1) and scalars "
      "Dr_phi_<species>, Dr_phi_over_Dr_<species>, Dr2_phi..., betaT_r_plateau_<species>, Dr_free_<species>",
      lag_grid_parameters());
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-restoring-torque", "self-rotational diffusion D_r(phi) of rods from the restoring torque (Method III)",
                            "See docs/analysis.md.", description()};
  return run_analysis_stage(argc, argv, info, [](StageRun& run) {
    const RestoringTorqueSettings settings = parse_restoring_torque_settings(run.cfg);
    run.cfg.finish();
    TrajectoryNeeds needs;
    needs.orientations = true;
    needs.elements = {kSystematicTorque};
    needs.observables = {kCappedObservable};
    needs.min_frames = 2;  // one lag
    run_per_species(
        run, {settings.species, SpeciesScope::Oriented}, needs,
        [&] { return RestoringTorqueAnalysis(settings, run.inputs.size()); },
        [&](const SelectedSpecies& sp, RestoringTorqueAnalysis& a, const std::vector<double>&) {
          const RestoringTorqueResult r = a.compute(free_rod_rotational_diffusion(sp.properties, run.inputs.front()));
          write_curves(run, sp, r);
          write_scalars(run, sp, r, settings);
        });
  });
}
