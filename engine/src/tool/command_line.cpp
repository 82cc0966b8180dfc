#include "anisodyn/tool/command_line.hpp"

#include <omp.h>

#include <boost/program_options.hpp>
#include <cstdio>
#include <iostream>

#include "anisodyn/core/error.hpp"
#include "anisodyn/tool/atomic_file.hpp"
#include "anisodyn/tool/json_config.hpp"
#include "anisodyn/version.hpp"

namespace anisodyn::tool {

namespace po = boost::program_options;

nlohmann::ordered_json describe(const ToolInfo& info) {
  using nlohmann::ordered_json;
  const Description& d = info.description;
  ordered_json parameters = ordered_json::array();
  for (const auto& p : d.parameters) {
    ordered_json j{{"name", p.name}, {"type", p.type}, {"required", p.required}};
    if (!p.required) j["default"] = ordered_json::parse(p.default_value.dump());
    j["meaning"] = p.meaning;
    parameters.push_back(j);
  }
  ordered_json output{{"kind", d.output.kind}, {"format", d.output.format}, {"meaning", d.output.meaning}};
  if (!d.output.adds_particles.is_null()) output["adds_particles"] = ordered_json::parse(d.output.adds_particles.dump());
  return {{"name", info.name},
          {"summary", info.summary},
          {"version", kVersion},
          {"role", role_name(d.role)},
          {"replica", d.replica},
          {"inputs", {{"kind", d.inputs.kind}, {"min", d.inputs.min}, {"max", d.inputs.max < 0 ? ordered_json(nullptr) : ordered_json(d.inputs.max)},
                      {"meaning", d.inputs.meaning}}},
          {"output", output},
          {"parameters", parameters},
          {"cost", ordered_json::parse(d.cost.dump())}};
}

std::string parameters_help(const ToolInfo& info) {
  if (info.description.parameters.empty()) return "";
  std::string out = "Configuration keys (--config FILE.json; --describe gives them as JSON):\n";
  for (const auto& p : info.description.parameters) {
    out += "  " + p.name + " (" + p.type + ", ";
    if (p.required) out += "required";
    else if (p.default_value.is_null()) out += "optional";
    else out += "default " + p.default_value.dump();
    out += "): " + p.meaning + "\n";
  }
  return out;
}

std::optional<CommonOptions> parse_command_line(int argc, char** argv, const ToolInfo& info) {
  CommonOptions opt;
  opt.tool = info.name;
  for (int i = 0; i < argc; ++i) opt.argv.emplace_back(argv[i]);

  po::options_description desc("Options");
  std::uint64_t seed = 0, replica = 0;
  std::int64_t checkpoint_every = 0;
  desc.add_options()
      ("help,h", "show this help and exit")
      ("version", "show the version and exit")
      ("describe", "print what this tool is, reads, writes and takes (JSON) and exit")
      ("config,c", po::value<std::string>(&opt.config_path), "JSON configuration file")
      ("set", po::value<std::vector<std::string>>(&opt.overrides)->composing(), "override a configuration value: key.path=value (repeatable)")
      ("input,i", po::value<std::vector<std::string>>(&opt.inputs)->multitoken()->composing(),
       "input file(s): --input a.h5 b.h5, or --input repeated")
      ("output,o", po::value<std::string>(&opt.output), "output file")
      ("seed", po::value<std::uint64_t>(&seed), "random seed (overrides the configuration's seed)")
      ("replica", po::value<std::uint64_t>(&replica), "replica index K: an independent random stream derived from (seed, K)")
      ("threads", po::value<int>(&opt.threads)->default_value(1), "OpenMP threads")
      ("checkpoint-every", po::value<std::int64_t>(&checkpoint_every), "cycles between checkpoints")
      ("quiet,q", po::bool_switch(&opt.quiet), "no progress output");
  po::variables_map vm;
  try {
    const po::parsed_options parsed = po::command_line_parser(argc, argv).options(desc).run();
    // A word that belongs to no option used to be dropped without a word: `--input a.h5 b.h5`
    // before --input took several files read a.h5 alone.
    const std::vector<std::string> stray = po::collect_unrecognized(parsed.options, po::include_positional);
    if (!stray.empty()) throw InputError("command line", "", "unexpected argument '" + stray.front() + "': every argument belongs to an option (see --help)");
    po::store(parsed, vm);
    po::notify(vm);
  } catch (const po::error& e) {
    throw InputError("command line", "", std::string(e.what()) + " (see --help)");
  }
  if (vm.count("help")) {
    std::cout << info.name << " — " << info.summary << "\n\nUsage: " << info.name << " [options]\n\n" << desc;
    const std::string keys = parameters_help(info);
    if (!keys.empty()) std::cout << "\n" << keys;
    if (!info.usage_notes.empty()) std::cout << "\n" << info.usage_notes << "\n";
    return std::nullopt;
  }
  if (vm.count("describe")) {
    std::cout << describe(info).dump(2) << std::endl;
    return std::nullopt;
  }
  if (vm.count("version")) {
    std::cout << info.name << " " << kVersion << " (" << kGitRevision << ")\n";
    return std::nullopt;
  }
  if (vm.count("seed")) opt.seed = seed;
  if (vm.count("replica")) opt.replica = replica;
  if (vm.count("checkpoint-every")) {
    if (checkpoint_every <= 0) throw InputError("command line", "--checkpoint-every", "expected a positive number of cycles");
    opt.checkpoint_every = checkpoint_every;
  }
  if (opt.threads < 1) throw InputError("command line", "--threads", "expected at least 1 thread");
  omp_set_num_threads(opt.threads);
  if (!opt.config_path.empty()) opt.config = load_json_file(opt.config_path);
  for (const auto& assignment : opt.overrides) apply_override(opt.config, assignment);
  return opt;
}

const std::string& require_one_input_and_output(const CommonOptions& opt) {
  if (opt.inputs.size() != 1) throw InputError("command line", "--input", "exactly one input state (H5MD)");
  if (opt.output.empty()) throw InputError("command line", "--output", "an output file");
  check_output_writable(opt.output);
  return opt.inputs[0];
}

int run_tool(int argc, char** argv, const ToolInfo& info, const std::function<void(CommonOptions&)>& body) {
  try {
    auto opt = parse_command_line(argc, argv, info);
    if (!opt) return kExitOk;
    body(*opt);
    return kExitOk;
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s: error: %s\n", info.name.c_str(), e.what());
    return kExitBadInput;
  } catch (const Interrupted& e) {
    std::fprintf(stderr, "%s: interrupted: %s\n", info.name.c_str(), e.what());
    return kExitInterrupted;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: runtime failure: %s\n", info.name.c_str(), e.what());
    return kExitRuntime;
  }
}

}  // namespace anisodyn::tool
