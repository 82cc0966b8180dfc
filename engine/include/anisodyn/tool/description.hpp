#pragma once
// What an executable says about itself with --describe (JSON on stdout): its role, whether it takes
// --replica, what it reads and writes, its top-level configuration keys, and how much work a job
// of it is. The study runner (workflows/anisodyn_run/describe.py) reads these descriptions instead
// of keeping its own lists of tools; docs/manifests.md, "Tool descriptions", gives the schema.
//
// Each tool states its description once, beside its main() (engine/apps/, analysis/apps/); the
// --help text lists the configuration keys from it.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace anisodyn::tool {

enum class Role {
  Builder,     // makes a state from a recipe (anisodyn-config)
  Engine,      // runs a simulation from a state; must state a cost model
  Analysis,    // reads trajectories, writes tables and scalars
  Tensors,     // computes species data (anisodyn-hydro)
  Example,     // a helper that writes example files for tests
  Dispatcher,  // `anisodyn TOOL`: runs another executable
};

/// One top-level configuration key.
struct Parameter {
  std::string name;
  std::string type;               // JSON type(s): "integer", "number", "string", "boolean", "object", "array", "string | number"
  bool required = false;
  nlohmann::json default_value;   // used when the key is absent; null: no value (the meaning says what absence does)
  std::string meaning;            // one line
};

/// A key that must be given.
Parameter required(std::string name, std::string type, std::string meaning);
/// A key that may be left out; `default_value` null means there is no default value (`meaning` says
/// what leaving it out does).
Parameter optional(std::string name, std::string type, nlohmann::json default_value, std::string meaning);

/// `seed` (default 1), the key of every tool with random streams; --seed overrides it, --replica K
/// draws stream K.
Parameter seed_parameter();

/// What the tool reads with --input (repeatable): how many files, of what kind.
struct Inputs {
  std::string kind = "none";  // "none", "state" (H5MD, last frame used), "trajectory" (H5MD frames)
  int min = 0;
  int max = 0;                // -1: any number (shell globs allowed)
  std::string meaning;
};

/// What --output receives.
struct Output {
  std::string kind = "none";   // "none", "state", "trajectory", "species" (species file), "analysis" (tables and scalars)
  std::string format;          // "H5MD", "HDF5 + CSV", "JSON or HDF5", ...
  std::string meaning;
  /// For a builder: how many particles its output adds to its input's (the runner's cost estimate
  /// counts an engine job's particles from it), e.g. {"sum_over": "composition", "key": "count"}.
  nlohmann::json adds_particles;
};

struct Description {
  Role role = Role::Example;
  bool replica = false;  // takes --replica K (independent random stream K); campaigns replicate it by default
  Inputs inputs;
  Output output;
  std::vector<Parameter> parameters;
  /// {"kind": "model", ...} (docs/manifests.md, "Cost models") for engines: the runner refuses an
  /// engine without one; {"kind": "negligible" | "not_estimated", "why": ...} for other tools.
  nlohmann::json cost;
};

/// {"kind": "negligible", "why": why}.
nlohmann::json negligible_cost(const std::string& why);

/// What every engine shares: role engine, --replica, one starting state as input, an H5MD
/// trajectory as output (its contents in `output_meaning`); the caller adds parameters and cost.
Description engine_description(const std::string& output_meaning);

const char* role_name(Role role);

}  // namespace anisodyn::tool
