// anisodyn-config: initial configurations (lattice or random insertion, any mixture), or random
// insertion of extra particles (tracers) into an existing state given with --input.
#include <cstdio>

#include "anisodyn/config/config_tool.hpp"
#include "anisodyn/core/error.hpp"
#include "anisodyn/tool/atomic_file.hpp"
#include "anisodyn/tool/command_line.hpp"
#include "anisodyn/io/h5md.hpp"
#include "anisodyn/tool/provenance.hpp"

using namespace anisodyn;

namespace {

tool::Description description() {
  tool::Description d;
  d.role = tool::Role::Builder;
  d.replica = true;
  d.inputs = {"state", 0, 1, "an existing state to insert the new particles into (its box and particles are kept)"};
  // The particles it adds, for cost estimates: the composition's counts, plus a liquid fill's density × box volume.
  d.output = {"state", "H5MD", "one frame: the configuration",
              {{"sum_over", "composition"},
               {"key", "count"},
               {"fill", {{"when", "liquid"}, {"density", "liquid.density"}, {"default_density", 3.0}, {"edges", "box.edges"}}}}};
  d.parameters = {
      tool::seed_parameter(),
      tool::optional("species", "array", nullptr,
                     "the species table: {name, shape, mass, D_trans, D_rot} or {name, diffusion_from: {file, species}}; "
                     "required unless inserting into --input"),
      tool::required("composition", "array", "particles to place: {species, count, orientation {mode, axis, director, random_azimuth}}"),
      tool::optional("box", "object", nullptr,
                     "{edges} or {packing_fraction, aspect}; required unless inserting into --input (whose box is kept)"),
      tool::optional("placement", "string", "lattice",
                     "lattice | random | uniform | colloids_in_liquid (random when inserting into --input)"),
      tool::optional("liquid", "object", nullptr,
                     "colloids_in_liquid: {species, density (3), subtract_colloid_volume (true)}, the DPD liquid placed "
                     "uniformly around the composition's colloids"),
      tool::optional("max_attempts_per_particle", "integer", 10000, "bound on the attempts per particle of random placement"),
  };
  d.cost = tool::negligible_cost("a configuration takes well under a second to seconds");
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-config", "build an initial configuration and write it as H5MD", "See docs/config.md.",
                            description()};
  return tool::run_tool(argc, argv, info, [&](tool::CommonOptions& opt) {
    if (opt.output.empty()) throw InputError("command line", "--output", "an output file (state.h5)");
    if (opt.inputs.size() > 1) throw InputError("command line", "--input", "at most one input state to insert into");
    tool::check_output_writable(opt.output);
    tool::ConfigNode cfg(opt.config, opt.config_name());
    const std::uint64_t seed = opt.seed.value_or(static_cast<std::uint64_t>(cfg.non_negative_integer("seed", 1)));
    std::optional<State> existing;
    if (!opt.inputs.empty()) existing = io::H5mdReader(opt.inputs[0]).read_frame(-1);

    const std::uint64_t replica = opt.replica.value_or(0);
    nlohmann::json diffusion_origins;
    nlohmann::json liquid_record;
    State state = build_configuration(cfg, existing, seed, replica, &diffusion_origins, &liquid_record);

    nlohmann::json parameters = opt.config;
    parameters["seed"] = seed;
    if (replica) parameters["replica"] = replica;
    nlohmann::json provenance = tool::make_provenance(info.name, opt.argv, opt.inputs);
    provenance["diffusion_sources"] = diffusion_origins;  // which species file (and entry) each D came from
    if (!liquid_record.is_null()) provenance["liquid_fill"] = liquid_record;
    io::H5mdWriter writer(opt.output, {"anisodyn", "", "anisodyn user", parameters, provenance, state.species});
    writer.append_frame(state);
    writer.commit();
    if (!opt.quiet)
      std::fprintf(stderr, "anisodyn-config: %zu particles, box %.6g x %.6g x %.6g, packing fraction %.6f -> %s\n",
                   state.particles.size(), state.box.edges().x(), state.box.edges().y(), state.box.edges().z(),
                   state.packing_fraction(), opt.output.c_str());
  });
}
