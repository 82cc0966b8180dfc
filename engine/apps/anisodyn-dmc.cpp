// anisodyn-dmc: Dynamic Monte Carlo production runs of hard particles (spec 10 §4–7) from an H5MD
// state to an H5MD trajectory. Frames and per-cycle observables stream into <output>.partial;
// checkpoints go to <output>.checkpoint.h5, and running the same command again resumes from it
// (run/run_files.hpp).
#include "anisodyn/dmc/dmc_runner.hpp"
#include "anisodyn/run/engine_main.hpp"
#include "anisodyn/tool/command_line.hpp"

using namespace anisodyn;

namespace {

tool::Description description() {
  tool::Description d = tool::engine_description("frames by the frames rules (with per-particle accumulators), observables every observe_every cycles, the summary");
  d.parameters = {
      tool::seed_parameter(),
      tool::required("time_step", "object", "{species: dt_MC}: the MC time step of each species (others follow by balance)"),
      tool::optional("cycles", "integer", nullptr, "run length in cycles (or time; not with schedule.segments)"),
      tool::optional("time", "number", nullptr, "run length in Brownian time (or cycles; not with schedule.segments)"),
      tool::optional("balance", "object", nullptr,
                     "{mode: equilibrium | per_cycle | none, reference, clock, preliminary_cycles, max_iterations, tolerance, "
                     "smoothing_cycles}; equilibrium by default"),
      tool::optional("moves", "object", nullptr, "{rotation: exponential | sequential, sequential_order, translation_frame}"),
      tool::optional("field", "object", nullptr,
                     "{direction, initially, check_direction, orientational {strength, axis}, dipoles {gamma, species, accuracy, "
                     "minimum_image_only}} (docs/run.md)"),
      tool::optional("schedule", "object", nullptr, "field on/off: {segments[], repeat} or {switches[]} (docs/run.md)"),
      tool::optional("tracer", "object", nullptr, "pulled tracer: {species, pe, axis, a0, record_every}"),
      tool::optional("frames", "object", nullptr,
                     "frame rules: every_cycles, every_time, log_first_time + log_per_decade, after_switch, log_cycles; none: "
                     "first and last frame"),
      tool::optional("observe_every", "integer", 1, "cycles between observation rows"),
      tool::optional("species", "object", nullptr,
                     "{name: {D_trans, D_rot} | {diffusion_from: {file, species}}}: diffusion tensors replacing the input's"),
  };
  // Work of a job = particles of its system x its cycles (production + preliminary balancing); the
  // rates are single-core throughputs of bench/dmc_throughput.cpp measured 2026-11-24 with skin
  // lists, medians of three rounds (docs/performance.md, "DMC throughput").
  d.cost = {{"kind", "model"},
            {"work", "trial moves"},
            // a cycle advances Brownian time by at most dt/3; balance.preliminary_cycles defaults to 10^4 (dmc_protocol.cpp)
            {"amount", {"particles", {{"rule", "dmc_cycles"}, {"cycles_per_time_step", 3}, {"default_preliminary_cycles", 10000}}}},
            {"rate", 9.6e5},
            {"measured", "bench/dmc_throughput.cpp, 2026-11-24, skin lists, median of three rounds: 2000 boards 12x1x1 + "
                         "200 spheres at eta = 0.34, nematic (the slowest hard-core case) (docs/performance.md)"},
            {"rates_when",
             {{{"present", "field.dipoles"},
               {"rate", 8.9e4},
               {"measured", "bench/dmc_throughput.cpp, 2026-11-24: 1500 dipolar cubes with Ewald, field on"}}}},
            {"note", "a run given in time counts 3 time / max(time_step) cycles (acceptance 1: a lower bound); an equilibrium "
                     "balance adds its preliminary_cycles once"}};
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-dmc", "Dynamic Monte Carlo of hard particles: Brownian dynamics by Metropolis moves",
                            "See docs/dmc.md.", description()};
  return tool::run_tool(argc, argv, info, [&](tool::CommonOptions& opt) {
    run::run_production_engine<DmcRunner, DmcProtocol>(opt, info, &parse_dmc_protocol);
  });
}
