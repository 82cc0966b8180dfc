// anisodyn-dmc: Dynamic Monte Carlo production runs of hard particles (spec 10 §4–7) from an H5MD
// state to an H5MD trajectory. Frames and per-cycle observables stream into <output>.partial;
// checkpoints go to <output>.checkpoint.h5, and running the same command again resumes from it.
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/signals.hpp"
#include "anisodyn/dmc/dmc_runner.hpp"
#include "anisodyn/tool/atomic_file.hpp"
#include "anisodyn/tool/command_line.hpp"
#include "anisodyn/io/h5md.hpp"
#include "anisodyn/tool/provenance.hpp"

using namespace anisodyn;

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-dmc", "Dynamic Monte Carlo of hard particles: Brownian dynamics by Metropolis moves",
                          "Configuration keys: seed, time_step {species: dt}, balance {mode, reference, clock, preliminary_cycles, "
                          "max_iterations, tolerance, smoothing_cycles}, cycles | time, moves {rotation, sequential_order, "
                          "translation_frame}, field {direction, initially, orientational {strength, axis}, dipoles {gamma, species, "
                          "accuracy, minimum_image_only}}, schedule {segments[], repeat | switches[]}, tracer {species, pe, axis, a0, "
                          "record_every}, frames {every_cycles, every_time, log_first_time, log_per_decade, after_switch}, "
                          "observe_every, species {name: {D_trans, D_rot}}. See docs/dmc.md."};
  return tool::run_tool(argc, argv, info, [&](tool::CommonOptions& opt) {
    const std::string& input = tool::require_one_input_and_output(opt);

    tool::ConfigNode cfg(opt.config, opt.config_name());
    DmcProtocol protocol = parse_dmc_protocol(cfg);
    cfg.finish();
    if (opt.seed) protocol.seed = *opt.seed;
    if (opt.replica) protocol.replica = *opt.replica;
    nlohmann::json parameters = opt.config;
    parameters["seed"] = protocol.seed;
    parameters["replica"] = protocol.replica;

    const std::string checkpoint_path = opt.output + ".checkpoint.h5";
    const bool resuming = std::filesystem::exists(checkpoint_path);
    State state;
    nlohmann::json engine_state;
    if (resuming) {
      const io::H5mdReader checkpoint(checkpoint_path);
      if (checkpoint.parameters() != parameters)
        throw InputError(checkpoint_path, "/parameters", "a checkpoint of the same configuration; this one was written with "
                                                         "different parameters: delete it to start afresh");
      const auto j = checkpoint.checkpoint();
      if (!j) throw InputError(checkpoint_path, "/anisodyn/checkpoint", "an engine state");
      state = checkpoint.read_frame(-1);
      engine_state = *j;
    } else {
      state = io::H5mdReader(input).read_frame(-1);
    }
    state.step = 0;
    state.time = 0.0;
    require_minimum_image(state, input);
    std::unique_ptr<DmcRunner> runner;
    try {
      runner = std::make_unique<DmcRunner>(state, protocol, opt.config_name(), opt.quiet);
    } catch (const InputError& e) {
      // Errors without a file of their own concern the input configuration.
      if (std::string(e.what()).rfind(opt.config_name(), 0) == 0) throw;
      throw InputError(input, "/particles/all", e.what());
    }
    nlohmann::json provenance = tool::make_provenance(info.name, opt.argv, opt.inputs);
    if (!protocol.diffusion_origins.empty()) provenance["diffusion_sources"] = protocol.diffusion_origins;
    const io::H5mdHeader header{"anisodyn", "", "anisodyn user", parameters, provenance, state.species};
    std::optional<io::H5mdWriter> out;
    if (resuming) {
      runner->restore(engine_state.at("runner"));
      out.emplace(io::H5mdWriter::resume(opt.output, runner->last_output_step()));
      if (!opt.quiet) std::fprintf(stderr, "anisodyn-dmc: resuming from %s\n", checkpoint_path.c_str());
    } else {
      out.emplace(opt.output, header);
    }

    auto checkpoint = [&] {
      const nlohmann::json j{{"runner", runner->checkpoint_state()}};
      out->write_checkpoint(j);  // flushes the streamed output first
      io::write_checkpoint_file(checkpoint_path, header, state, j);
    };
    install_interrupt_handlers();
    try {
      runner->run(*out, opt.checkpoint_every.value_or(0), checkpoint);
    } catch (const Interrupted&) {
      out->suspend();
      throw;
    }
    out->write_checkpoint({{"runner", runner->checkpoint_state()}});
    out->commit();
    std::filesystem::remove(checkpoint_path);
    std::cout << runner->summary().dump(2) << std::endl;
  });
}
