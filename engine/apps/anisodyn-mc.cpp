// anisodyn-mc: Metropolis MC preparation runs (compression, NPT, NVT, optional orientational
// field) from an H5MD state to an H5MD trajectory. Frames and observables stream into
// <output>.partial; checkpoints go to <output>.checkpoint.h5, and running the same command again
// resumes from it (run/run_files.hpp).
#include <cstdio>
#include <iostream>

#include "anisodyn/core/error.hpp"
#include "anisodyn/io/h5md.hpp"
#include "anisodyn/mc/protocol_config.hpp"
#include "anisodyn/run/run_files.hpp"
#include "anisodyn/tool/command_line.hpp"
#include "anisodyn/tool/provenance.hpp"

using namespace anisodyn;

namespace {

tool::Description description() {
  tool::Description d = tool::engine_description("frames by the frames rules (always the final state), observables every observe_every cycles, the summary");
  d.parameters = {
      tool::seed_parameter(),
      tool::optional("target_acceptance", "number", 0.35, "target acceptance of move-size tuning (only when a phase tunes)"),
      tool::optional("tune_every", "integer", 100, "cycles between tuning updates (only when a phase tunes)"),
      tool::optional("observe_every", "integer", 10, "cycles between observable samples"),
      tool::optional("sweeps", "string", "sequential",
                     "sequential | domains: domain sweeps on all --threads (two slabs, or from 4000 particles a grid of domains; same distribution, other trajectory; docs/mc.md)"),
      tool::optional("frames", "object", nullptr, "frame rules: every_cycles, log_cycles {per_decade, restart_every}; none: the final frame only "
                                                  "(docs/run.md)"),
      tool::optional("field", "object", nullptr,
                     "orientational field on for the whole run: {direction, orientational {strength, axis}} (docs/run.md)"),
      tool::required("phases", "array", "the protocol: phases {type: compress | npt | nvt, ...} run in order (docs/mc.md)"),
  };
  // Work of a job = particles of its system x the cycles of its phases; the rate is the single-core
  // throughput of bench/mc_throughput.cpp measured 2026-11-22 (docs/performance.md, "MC throughput").
  d.cost = {{"kind", "model"},
            {"work", "trial moves"},
            {"amount", {"particles", {{"rule", "mc_phases"}, {"default_max_cycles", 1000000}}}},  // parse_phase's default
            {"rate", 9.57e5},
            {"measured", "bench/mc_throughput.cpp, 2026-11-22: 2000 boards 12x3.46x1 at eta = 0.20, one core, "
                         "median of 7 repetitions (docs/performance.md)"},
            {"note", "a compression phase counts at its max_cycles (10^6 when not given): an upper bound"}};
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-mc", "Metropolis MC equilibration and compression of hard particles", "See docs/mc.md.",
                            description()};
  return tool::run_tool(argc, argv, info, [&](tool::CommonOptions& opt) {
    const std::string& input = tool::require_one_input_and_output(opt);

    tool::ConfigNode cfg(opt.config, opt.config_name());
    McProtocol protocol = parse_mc_protocol(cfg);
    if (opt.seed) protocol.seed = *opt.seed;
    if (opt.replica) protocol.replica = *opt.replica;
    cfg.finish();
    nlohmann::json parameters = opt.config;
    parameters["seed"] = protocol.seed;
    if (protocol.replica) parameters["replica"] = protocol.replica;

    // Resuming starts from the checkpoint's state; otherwise from the input's last frame.
    run::RunFiles files(opt.output, parameters);
    State state = files.starting_state(input);
    const std::string& state_file = files.resuming() ? files.checkpoint_path() : input;
    require_minimum_image(state, state_file);

    std::unique_ptr<McRunner> runner;
    try {
      runner = std::make_unique<McRunner>(state, protocol, opt.quiet);
    } catch (const InputError& e) {
      throw InputError(state_file, "/particles/all", e.what());
    }
    if (files.resuming()) {
      runner->restore(files.engine_state().at("runner"));
      runner->restore_phase_samples(files.partial_output());
      if (!opt.quiet) std::fprintf(stderr, "anisodyn-mc: resuming from %s at cycle %lld\n", files.checkpoint_path().c_str(),
                                   static_cast<long long>(state.step));
    }
    const io::H5mdHeader header{"anisodyn", "", "anisodyn user", parameters, tool::make_provenance(info.name, opt.argv, opt.inputs), state.species};
    files.run_to_completion(header, state, *runner, opt.checkpoint_every.value_or(0));
    std::cout << runner->summary().dump(2) << std::endl;
  });
}
