// anisodyn-lb: raspberry colloids in a fluctuating D3Q19 lattice-Boltzmann fluid (spec 40) from an
// H5MD state to an H5MD trajectory. Frames and observables stream into <output>.partial;
// checkpoints (with the fluid's populations) go to <output>.checkpoint.h5, and running the same
// command again resumes from it (run/run_files.hpp).
#include "anisodyn/lb/lb_runner.hpp"
#include "anisodyn/run/engine_main.hpp"
#include "anisodyn/tool/command_line.hpp"

using namespace anisodyn;

namespace {

tool::Description description() {
  tool::Description d = tool::engine_description("frames of the raspberries (positions, orientations, velocities, angular momenta) by the frames rules, observables every observe_every steps, the summary");
  d.parameters = {
      tool::seed_parameter(),
      tool::required("time_step", "number", "the MD time step in t0 (spec 40: 0.01)"),
      tool::optional("steps", "integer", nullptr, "run length in MD steps (or time)"),
      tool::optional("time", "number", nullptr, "run length in time (or steps)"),
      tool::optional("kT", "number", 1, "temperature of the fluid and bead noise (energy unit); refused with fluid.thermal false"),
      tool::optional("fluid", "object", nullptr,
                     "{agrid (1), lb_steps (2), density (6.004), viscosity (0.8), bulk_relaxation (0), ghost_relaxation (0), thermal (true), "
                     "initial_velocity ([0, 0, 0]), warmup_steps (1000), body_force ([0, 0, 0])}: the D3Q19 fluid, in sigma, M0 and t0"),
      tool::required("raspberries", "object",
                     "{species (default: every species), xi_bead (required), xi_bead_is_nominal (true), centre_couples (true), fixed (false), "
                     "coupling_velocity (with_half_force | momentum_only), allow_unstable (false), layers (two | single: without the outer "
                     "hydrodynamic-only layer, spec 40 §6's ablation)}: sphere and spheroid raspberries (spec 40 §4-§5)"),
      tool::optional("walls", "object", nullptr,
                     "{normal: x | y | z, velocity ([0, 0, 0])}: a bounce-back wall layer at node 0 along normal, moving tangentially (spec 40 §7.2)"),
      tool::optional("pore", "object", nullptr,
                     "{radius (required), wall_bead_radius (6.25), wall_bead_spacing (5), epsilon (1)}: a cylindrical pore along z through the "
                     "box's centre, solid nodes beyond the radius and WCA wall beads repelling the inner layers (spec 40 §6; refused with walls)"),
      tool::optional("frames", "object", nullptr, "frame rules: every_steps, every_time, log_first_time + log_per_decade, log_steps"),
      tool::optional("observe_every", "integer", 100, "MD steps between observation rows (each the mean over its steps)"),
  };
  // Work of a job = lattice nodes x LB steps; rate: 64^3 fluctuating, one core, bench/lb_throughput.cpp.
  d.cost = {{"kind", "model"},
            {"work", "node-MD-steps"},
            {"amount", {"box_volume", {{"rule", "time_steps"}}}},
            {"rate", 2 * 13.3e6},
            {"measured", "bench/lb_throughput.cpp, 2026-11-26: 64^3 fluctuating D3Q19, one core, 13.3-13.5 MLUPS per LB step (rate per MD step at lb_steps = 2)"},
            {"note", "the cost per MD step is half an LB step; coupled beads add about 1.3 ms per 1000 beads per LB step"}};
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-lb", "Raspberry colloids in a fluctuating lattice-Boltzmann fluid", "See docs/lb.md.", description()};
  return tool::run_tool(argc, argv, info, [&](tool::CommonOptions& opt) {
    run::run_production_engine<lb::LbRunner, lb::LbProtocol>(
        opt, info, &lb::parse_lb_protocol,
        [](const lb::LbProtocol& p, nlohmann::json& provenance) { provenance["units"] = lb::units_record(p.raspberries.scaling, p.fluid.density); });
  });
}
