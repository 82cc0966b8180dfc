#pragma once
// What the main() of every production engine does, written once (anisodyn-dmc, anisodyn-bd, …):
// read the configuration with the engine's parser and refuse unknown keys; apply --seed and
// --replica; find the run's files (resume from a checkpoint of the same parameters, run/run_files.hpp);
// start from the checkpoint's or the input's last state with step and time 0; install the
// interrupt handlers; build the runner
// (an input error without a file of its own concerns the input state); write the header with the
// provenance; run to completion with checkpoints; print the summary as JSON on stdout.
//
// The protocol has `seed`, `replica` and, if the engine takes D tensors, `diffusion` (io::DiffusionOverrides); the runner is
// constructed as Runner(state, protocol, config name, quiet) and has run, restore,
// checkpoint_state, last_output_step and summary; a runner whose state includes large arrays also
// has checkpoint_arrays() and restore_arrays(reader), reader(name) giving the checkpoint's array.
#include <cstdio>
#include <functional>
#include <iostream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/signals.hpp"
#include "anisodyn/interactions/hard_overlap.hpp"
#include "anisodyn/io/h5md.hpp"
#include "anisodyn/run/run_files.hpp"
#include "anisodyn/tool/command_line.hpp"
#include "anisodyn/tool/provenance.hpp"

namespace anisodyn::run {

template <class Runner, class Protocol>
void run_production_engine(tool::CommonOptions& opt, const tool::ToolInfo& info, Protocol (*parse)(tool::ConfigNode&),
                           const std::function<void(const Protocol&, nlohmann::json&)>& add_provenance = {}) {
  const std::string& input = tool::require_one_input_and_output(opt);
  tool::ConfigNode cfg(opt.config, opt.config_name());
  Protocol protocol = parse(cfg);
  cfg.finish();
  if (opt.seed) protocol.seed = *opt.seed;
  if (opt.replica) protocol.replica = *opt.replica;
  nlohmann::json parameters = opt.config;
  parameters["seed"] = protocol.seed;
  parameters["replica"] = protocol.replica;

  RunFiles files(opt.output, parameters);
  State state = files.starting_state(input);
  state.step = 0;
  state.time = 0.0;
  // The hard-body minimum-image rule; an engine whose interactions are not the shapes' own (DPD:
  // a liquid of soft points, colloids seen through their sites) checks its ranges itself.
  if constexpr (!requires { Protocol::kChecksOwnRanges; }) require_minimum_image(state, input);
  // From here an interrupt is honoured at the first step (a checkpoint, exit 130), not by dying in
  // the set-up, which can take a while (an LB run builds its raspberries' bead layers).
  install_interrupt_handlers();
  std::unique_ptr<Runner> runner;
  try {
    runner = std::make_unique<Runner>(state, protocol, opt.config_name(), opt.quiet);
  } catch (const InputError& e) {
    if (std::string(e.what()).rfind(opt.config_name(), 0) == 0) throw;
    throw InputError(input, "/particles/all", e.what());
  }
  nlohmann::json provenance = tool::make_provenance(info.name, opt.argv, opt.inputs);
  if constexpr (requires { protocol.diffusion; })  // engines that take D tensors (DPD does not)
    if (!protocol.diffusion.origins.empty()) provenance["diffusion_sources"] = protocol.diffusion.origins;
  if (add_provenance) add_provenance(protocol, provenance);
  const io::H5mdHeader header{"anisodyn", "", "anisodyn user", parameters, provenance, state.species};
  if (files.resuming()) {
    runner->restore(files.engine_state().at("runner"));
    if constexpr (requires { runner->checkpoint_arrays(); })
      runner->restore_arrays([&files](const std::string& name) { return files.checkpoint_array(name); });
    if (!opt.quiet) std::fprintf(stderr, "%s: resuming from %s\n", info.name.c_str(), files.checkpoint_path().c_str());
  }
  files.run_to_completion(header, state, *runner, opt.checkpoint_every.value_or(0));
  std::cout << runner->summary().dump(2) << std::endl;
}

}  // namespace anisodyn::run
