// anisodyn-bd: overdamped Brownian dynamics of rods and spheres (spec 20) from an H5MD state to an
// H5MD trajectory. Frames and observables stream into <output>.partial; checkpoints go to
// <output>.checkpoint.h5, and running the same command again resumes from it (run/run_files.hpp).
#include "anisodyn/bd/bd_runner.hpp"
#include "anisodyn/run/engine_main.hpp"
#include "anisodyn/tool/command_line.hpp"

using namespace anisodyn;

namespace {

tool::Description description() {
  tool::Description d = tool::engine_description("frames by the frames rules, observables every observe_every steps, the summary");
  d.parameters = {
      tool::seed_parameter(),
      tool::required("time_step", "number", "the time step Δt (τ in reduced units, s in SI)"),
      tool::optional("steps", "integer", nullptr, "run length in steps (or time)"),
      tool::optional("time", "number", nullptr, "run length in time (or steps)"),
      tool::optional("units", "object", nullptr, "{system: reduced | SI, length (m per length unit), temperature (K)}; reduced by default"),
      tool::optional("species", "object", nullptr,
                     "{name: {D_trans, D_rot} | {diffusion_from: {file, species}}}: diffusion tensors replacing the input's"),
      tool::optional("slender_body", "object", nullptr,
                     "{rod species: {viscosity, diameter}}: free-rod D from the slender-body formulas of spec 20 §2 (diameter "
                     "optional, default the species')"),
      tool::optional("frames", "object", nullptr, "frame rules: every_steps, every_time, log_first_time + log_per_decade, log_steps"),
      tool::optional("observe_every", "integer", 100, "steps between observation rows"),
      tool::optional("potential", "object", nullptr,
                     "{type: overlap_volume, species, hardness (kT/D^3; default k f(0.8D) = kT), finite_length: segment_distance | "
                     "interior_only, skin}: the rod-rod potential of spec 20 §4; none: free particles"),
      tool::optional("tracer", "object", nullptr,
                     "{species, pe, axis, record_every}: the pulled tracer of active microrheology (a constant force on the one "
                     "sphere of species); none: no tracer"),
      tool::optional("external_torque", "object", nullptr,
                     "{particles, torque_kT, axis, confinement_kT, record_every}: Method II's constant torque on the tagged rods, "
                     "their axes held near the plane normal to axis (spec 20 §6.2); none: no external torque"),
      tool::optional("caps", "object", nullptr, "{force, torque}: step_bound (default), a value, or null (no cap)"),
  };
  // Work of a job = particles x steps; rate: 1760 free rods, one core, bench/bd_throughput.cpp.
  d.cost = {{"kind", "model"},
            {"work", "particle-steps"},
            {"amount", {"particles", {{"rule", "time_steps"}}}},  // steps, or time / time_step
            {"rate", 4.5e6},
            // With a potential: rods at B3's densest (L/D)φ = 1.76 (440 rods at 0.44 run at 3.1e6).
            {"rates_when", {{{"present", "potential"}, {"rate", 1.47e6}}}},
            {"measured", "bench/bd_throughput.cpp, 2026-11-24, one core, medians of 3 (docs/performance.md): 1760 free rods; "
                         "1760 rods with the overlap-volume potential at (L/D)phi = 1.76"},
            {"note", "free particles, or the rate of dense interacting rods when a potential is given"}};
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-bd", "Overdamped Brownian dynamics of rods and spheres", "See docs/bd.md.", description()};
  return tool::run_tool(argc, argv, info, [&](tool::CommonOptions& opt) {
    run::run_production_engine<BdRunner, BdProtocol>(opt, info, &parse_bd_protocol, [](const BdProtocol& p, nlohmann::json& provenance) {
      provenance["units"] = p.units.to_json();  // the unit system of every number in the output
      if (p.potential)  // the finite-length rule of the main branch (spec 20 §4.1), whether given or by default
        provenance["potential"] = {{"type", "overlap_volume"}, {"finite_length", p.potential->interior_only ? "interior_only" : "segment_distance"}};
    });
  });
}
