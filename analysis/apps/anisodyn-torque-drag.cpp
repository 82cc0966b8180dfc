// anisodyn-torque-drag: Method II of spec 20 §6.2 (study B3): D_r(φ) = ⟨ω⟩/(βT_ex) of rods turned by
// anisodyn-bd's external torque, from the unwrapped in-plane angles of the tagged rods.
#include <cstdio>

#include "anisodyn/analysis/bd_caps.hpp"
#include "anisodyn/analysis/free_rotation.hpp"
#include "anisodyn/analysis/stage.hpp"
#include "anisodyn/analysis/torque_drag.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

void write_rods(StageRun& run, const TorqueDragResult& r) {
  Table& t = run.out.table("torque_drag_rods", "Method II (spec 20 §6.2): each tagged rod of each replica");
  t.add("replica", "1", "index of the input trajectory", column_of(r.rods, &TaggedRodDrag::replica));
  t.add("id", "1", "particle id of the tagged rod", column_of(r.rods, &TaggedRodDrag::id));
  t.add("omega", "rad/tau", "least-squares slope of the unwrapped in-plane angle about the torque axis against time", column_of(r.rods, &TaggedRodDrag::omega));
  t.add("t_start", "tau", "first tagged_axes row fitted", column_of(r.rods, &TaggedRodDrag::t_start));
  t.add("t_end", "tau", "last tagged_axes row fitted", column_of(r.rods, &TaggedRodDrag::t_end));
  t.add("rows", "1", "tagged_axes rows fitted", column_of(r.rods, &TaggedRodDrag::rows));
  t.add("mean_axial_square", "1", "<(u.e)^2> over the rows, e the torque axis (confinement check: about kT/kappa_c)",
        column_of(r.rods, &TaggedRodDrag::mean_axial_square));
  t.add("large_turns", "1", "rows turning by more than pi/2 since the previous one (unwrapping unsafe if any)",
        column_of(r.rods, &TaggedRodDrag::large_turns));
}

void write_scalars(StageRun& run, const TorqueDragResult& r, double free_dr) {
  std::size_t large_turns = 0;
  for (const auto& rod : r.rods) large_turns += rod.large_turns;
  nlohmann::json details = {{"torque_kT", r.torque.beta_torque},
                                  {"axis", {r.torque.axis.x(), r.torque.axis.y(), r.torque.axis.z()}},
                                  {"tagged_rods", r.torque.particles},
                                  {"species", r.species},
                                  {"samples", r.samples},
                                  {"error", r.time_blocks ? "standard error over 10 time blocks of the one tagged rod"
                                                          : "standard error over the tagged rods of every replica"},
                                  {"method", "least-squares slope of the unwrapped angle per rod (per block), averaged"},
                                  {"large_turns", large_turns},
                                  {"D_r_free", free_dr},
                                  {"D_r_free_source", "D_rot of species " + r.species + " about a perpendicular axis, species table of the first input"}};
  // the caps slow a tagged rod whose deterministic turn per step exceeds the bound: then ⟨ω⟩ is not the drag's
  details["capped_torques"] = r.capped_torques ? nlohmann::json(*r.capped_torques) : nlohmann::json("not recorded");
  run.out.scalar({"mean_angular_velocity", r.omega.value, r.omega.error, "rad/tau", "spec 20 §6.2: <omega> about the torque axis", details});
  run.out.scalar({"Dr_phi", r.dr.value, r.dr.error, "rad^2/tau", "spec 20 §6.2: D_r(phi) = <omega> / (beta T_ex)", details});
  run.out.scalar({"Dr_phi_over_Dr", r.dr.value / free_dr, r.dr.error / free_dr, "1",
                  "spec 20 §6.2: D_r(phi)/D_r (D_r the free-rod input, error from D_r(phi) alone)", details});
  run.out.scalar({"Dr_free", free_dr, 0.0, "rad^2/tau", "free-rod D_r of the species table (the normalisation)", details});
  if (!run.opt.quiet)
    std::fprintf(stderr, "anisodyn-torque-drag: <omega> = %.5g ± %.2g, D_r(phi)/D_r = %.5g ± %.2g (%zu samples)%s\n", r.omega.value,
                 r.omega.error, r.dr.value / free_dr, r.dr.error / free_dr, r.samples,
                 large_turns ? "  (warning: rows turning by more than pi/2: record tagged_axes more often)" : "");
  if (!run.opt.quiet && r.capped_torques && *r.capped_torques > 0)
    std::fprintf(stderr, "anisodyn-torque-drag: warning: %.0f capped torques: the caps slowed the rods (use a smaller time step)\n", *r.capped_torques);
}

tool::Description description() {
  return analysis_description({}, "table torque_drag_rods (omega per tagged rod and replica) and scalars mean_angular_velocity, Dr_phi, "
                                  "Dr_phi_over_Dr, Dr_free");
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-torque-drag", "self-rotational diffusion D_r(phi) of rods from the drag under an external torque (Method II)",
                            "See docs/analysis.md.", description()};
  return run_analysis_stage(argc, argv, info, [](StageRun& run) {
    run.cfg.finish();
    TrajectoryNeeds needs;
    needs.observables = {kTaggedAxes, kCappedObservable};
    TorqueDragAnalysis a(run.inputs.size());
    Species tagged;
    // each replica on its own clock: only the tagged rods' rows are compared, not frame times
    run.each_replica(
        needs,
        [&](const Trajectory& t, std::size_t k) {
          a.accumulate(t, k);
          if (k == 0) tagged = t.species_table[static_cast<std::size_t>(a.species_index())];
        },
        kIndependentTimes);
    const TorqueDragResult r = a.compute();
    write_rods(run, r);
    write_scalars(run, r, free_rod_rotational_diffusion(tagged, run.inputs.front()));
  });
}
