#pragma once
// Options shared by every anisodyn executable (architecture §5) and the wrapper that maps errors to
// exit codes: 2 bad input, 3 runtime failure, 130 interrupted.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/tool/description.hpp"

namespace anisodyn::tool {

struct ToolInfo {
  std::string name;         // e.g. "anisodyn-mc"
  std::string summary;      // one line
  std::string usage_notes;  // printed in --help after the option list and the configuration keys
  Description description;  // --describe (description.hpp); --help lists its parameters
};

/// The JSON that --describe prints: name, summary, version, role, replica, inputs, output,
/// parameters and cost (docs/manifests.md, "Tool descriptions").
nlohmann::ordered_json describe(const ToolInfo& info);

/// The "Configuration keys" section of --help, one line per parameter of the description.
std::string parameters_help(const ToolInfo& info);

struct CommonOptions {
  std::string tool;
  std::vector<std::string> argv;
  std::string config_path;            // --config FILE.json ("" if none)
  std::vector<std::string> overrides;  // --set key.path=value
  std::vector<std::string> inputs;     // --input (repeatable)
  std::string output;                  // --output
  std::optional<std::uint64_t> seed;   // --seed
  std::optional<std::uint64_t> replica;  // --replica K (tools with random streams: stream K of the seed)
  int threads = 1;                     // --threads
  std::optional<std::int64_t> checkpoint_every;  // --checkpoint-every (cycles)
  bool quiet = false;
  nlohmann::json config = nlohmann::json::object();  // the config file with overrides applied

  /// Name to quote in error messages about the configuration.
  std::string config_name() const { return config_path.empty() ? "(command line)" : config_path; }
};

/// Parses the command line, loads --config and applies --set. Returns nullopt after --help,
/// --version or --describe (already printed; they need no other option). Throws InputError on bad options.
std::optional<CommonOptions> parse_command_line(int argc, char** argv, const ToolInfo& info);

/// For tools that turn one input state into one output file: checks that there is exactly one
/// --input and a writable --output (InputError otherwise) and returns the input path.
const std::string& require_one_input_and_output(const CommonOptions& opt);

/// Runs body with parsed options; returns the exit code (prints errors as "<tool>: error: ...").
int run_tool(int argc, char** argv, const ToolInfo& info, const std::function<void(CommonOptions&)>& body);

}  // namespace anisodyn::tool
