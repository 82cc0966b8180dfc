// anisodyn-mc: Metropolis MC preparation runs (compression, NPT, NVT, optional orientational
// field) from an H5MD state to an H5MD trajectory. Checkpoints to <output>.checkpoint.h5 and
// resumes from it when run again with the same configuration.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "anisodyn/core/signals.hpp"
#include "anisodyn/core/error.hpp"
#include "anisodyn/tool/atomic_file.hpp"
#include "anisodyn/tool/command_line.hpp"
#include "anisodyn/io/h5md.hpp"
#include "anisodyn/tool/provenance.hpp"
#include "anisodyn/mc/protocol_config.hpp"

using namespace anisodyn;

namespace {

void write_trajectory(io::H5mdWriter& w, const McRunner& runner) {
  for (const State& f : runner.frames()) w.append_frame(f);
  for (const auto& [name, s] : runner.observables()) {
    for (std::size_t r = 0; r < s.step.size(); ++r) {
      const auto first = s.value.begin() + static_cast<std::ptrdiff_t>(r * s.width);
      w.append_observable(name, s.step[r], s.time[r], std::vector<double>(first, first + static_cast<std::ptrdiff_t>(s.width)));
    }
    w.set_observable_attribute(name, "definition", s.definition);
    w.set_observable_attribute(name, "units", name.rfind("box_edges", 0) == 0 ? "length unit of the study" : "1");
  }
}

std::map<std::string, Series> read_observables(const io::H5mdReader& r) {
  std::map<std::string, Series> out;
  for (const auto& name : r.observable_names()) {
    const auto s = r.read_observable(name);
    Series& d = out[name];
    d.step = s.step;
    d.time = s.time;
    d.value = s.value;
    d.width = s.width;
    d.definition = r.observable_attribute(name, "definition").value_or("");
  }
  return out;
}

tool::Description description() {
  tool::Description d;
  d.role = tool::Role::Engine;
  d.replica = true;
  d.inputs = {"state", 1, 1, "the starting state (its last frame)"};
  d.output = {"trajectory", "H5MD", "stored frames (always the final state), observables every sample_every cycles, the summary", nullptr};
  d.parameters = {
      tool::seed_parameter(),
      tool::optional("target_acceptance", "number", 0.35, "target acceptance of move-size tuning (only when a phase tunes)"),
      tool::optional("tune_every", "integer", 100, "cycles between tuning updates (only when a phase tunes)"),
      tool::optional("sample_every", "integer", 10, "cycles between observable samples"),
      tool::optional("frame_every", "integer", 0, "cycles between stored frames (0: the final frame only)"),
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

    // Resuming starts from the checkpoint's last frame; otherwise from the input's. Either way the
    // starting state is read once.
    const std::string checkpoint_path = opt.output + ".checkpoint.h5";
    std::unique_ptr<io::H5mdReader> checkpoint_reader;
    nlohmann::json engine_state;
    std::size_t frames_kept = 0;
    State state;
    if (std::filesystem::exists(checkpoint_path)) {
      checkpoint_reader = std::make_unique<io::H5mdReader>(checkpoint_path);
      if (checkpoint_reader->parameters() != parameters)
        throw InputError(checkpoint_path, "/parameters", "a checkpoint of the same configuration; this one was written with "
                                                         "different parameters: delete it to start afresh");
      const auto j = checkpoint_reader->checkpoint();
      if (!j) throw InputError(checkpoint_path, "/anisodyn/checkpoint", "an engine state");
      engine_state = *j;
      frames_kept = engine_state.at("frames_kept").get<std::size_t>();
      state = checkpoint_reader->read_frame(static_cast<std::ptrdiff_t>(frames_kept));
    } else {
      state = io::H5mdReader(input).read_frame(-1);
    }
    const std::string& state_file = checkpoint_reader ? checkpoint_path : input;
    require_minimum_image(state, state_file);

    std::unique_ptr<McRunner> runner;
    try {
      runner = std::make_unique<McRunner>(state, protocol, opt.quiet);
    } catch (const InputError& e) {
      throw InputError(state_file, "/particles/all", e.what());
    }
    if (checkpoint_reader) {
      std::vector<State> frames;
      for (std::size_t f = 0; f < frames_kept; ++f) frames.push_back(checkpoint_reader->read_frame(static_cast<std::ptrdiff_t>(f)));
      runner->restore(engine_state.at("runner"), read_observables(*checkpoint_reader), std::move(frames));
      if (!opt.quiet) std::fprintf(stderr, "anisodyn-mc: resuming from %s at cycle %lld\n", checkpoint_path.c_str(),
                                   static_cast<long long>(state.step));
    }
    const io::H5mdHeader header{"anisodyn", "", "anisodyn user", parameters, tool::make_provenance(info.name, opt.argv, opt.inputs), state.species};
    auto checkpoint = [&] {
      io::H5mdWriter w(checkpoint_path, header);
      write_trajectory(w, *runner);
      w.append_frame(state);
      nlohmann::json engine_state{{"frames_kept", runner->frames().size()}, {"runner", runner->checkpoint_state()}};
      w.write_checkpoint(engine_state);
      w.commit();
    };

    install_interrupt_handlers();
    runner->run(opt.checkpoint_every.value_or(0), checkpoint);

    io::H5mdWriter writer(opt.output, header);
    write_trajectory(writer, *runner);
    writer.write_checkpoint({{"frames_kept", runner->frames().size()}, {"runner", runner->checkpoint_state()}});
    writer.commit();
    std::filesystem::remove(checkpoint_path);
    std::cout << runner->summary().dump(2) << std::endl;
  });
}
