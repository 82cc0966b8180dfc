// anisodyn-dpd: dissipative particle dynamics of a Groot–Warren liquid (spec 30 §2) from an H5MD
// state to an H5MD trajectory. Frames and observables stream into <output>.partial; checkpoints go
// to <output>.checkpoint.h5, and running the same command again resumes from it (run/run_files.hpp).
#include "anisodyn/dpd/dpd_runner.hpp"
#include "anisodyn/run/engine_main.hpp"
#include "anisodyn/tool/command_line.hpp"

using namespace anisodyn;

namespace {

tool::Description description() {
  tool::Description d = tool::engine_description("frames by the frames rules (with velocities), observables every observe_every steps, the summary");
  d.parameters = {
      tool::seed_parameter(),
      tool::required("time_step", "number", "the time step Δt in τ (spec 30: 0.005)"),
      tool::optional("steps", "integer", nullptr, "run length in steps (or time)"),
      tool::optional("time", "number", nullptr, "run length in time (or steps)"),
      tool::optional("kT", "number", 1, "temperature of the thermostat (energy unit)"),
      tool::required("liquid", "object",
                     "{species (default: every species), a (25), gamma (4.5), cutoff (1), skin (0.3)}: the Groot–Warren liquid"),
      tool::optional("velocities", "string", nullptr,
                     "input | maxwell_boltzmann: where the starting velocities come from (default: the input's if it has them)"),
      tool::optional("frames", "object", nullptr, "frame rules: every_steps, every_time, log_first_time + log_per_decade, log_steps"),
      tool::optional("observe_every", "integer", 100, "steps between observation rows (each the mean over its steps)"),
      tool::optional("green_kubo", "object", nullptr,
                     "{blocks (10), max_lag (20)}: the off-diagonal pressure tensor (total and each part) sampled every step into a "
                     "multiple-tau autocorrelator, one row of stress_acf per block, for anisodyn-viscosity (absent: not recorded)"),
      tool::optional("colloids", "object", nullptr,
                     "{species (required), gamma_surface (0), shell (0.5), shell_noise (vector3d | along_v), mass_density (3), "
                     "site_spacing (0.5), fixed (false)}: rigid colloids in the liquid, spheres as point masses and rods as linear rotors of "
                     "sites, with the Mie(50,49) core and the friction shell (spec 30 §3-§4; absent: a pure liquid)"),
      tool::optional("frame_species", "array", nullptr, "the species whose particles the frames hold (absent: every particle)"),
      tool::optional("walls", "object", nullptr,
                     "{type: flat_mie, height, gamma_surface: [bottom, top], shell (0.5), shell_noise}: flat Mie(50,49) walls at z = 0 and "
                     "z = height with friction shells (spec 30 §6; the box must be taller by the cut-off; absent: periodic in z)"),
      tool::optional("drive", "object or array", nullptr, "{force: [fx, fy, fz], z_min, z_max}: a constant force on the liquid particles in the slab z_min <= z < z_max (z wrapped into the box); a list of such slabs adds up (two opposite ones: the periodic Poiseuille flow)"),
      tool::optional("profiles", "object", nullptr,
                     "{z_bin, radial_bin, radial_max, midplane_half_width (0.25)}: liquid number and v_x per slab along z and per shell "
                     "around the first colloid, per observation row (for anisodyn-flow)"),
  };
  // Work of a job = particles x steps; rate: 24000 liquid particles, one core, bench/dpd_throughput.cpp.
  d.cost = {{"kind", "model"},
            {"work", "particle-steps"},
            {"amount", {"particles", {{"rule", "time_steps"}}}},
            {"rate", 5.13e6},
            {"measured", "bench/peers/dpd_side_by_side.sh, 2026-11-25 12:15: 24000 particles at rho = 3, gamma = 4.5, one core, median of 5 (docs/performance.md)"},
            {"note", "pure liquid"}};
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-dpd", "Dissipative particle dynamics of a Groot–Warren liquid", "See docs/dpd.md.", description()};
  return tool::run_tool(argc, argv, info, [&](tool::CommonOptions& opt) {
    run::run_production_engine<DpdRunner, DpdProtocol>(opt, info, &parse_dpd_protocol);
  });
}
