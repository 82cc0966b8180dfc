#pragma once
// Provenance records stored in every output (/parameters/provenance in H5MD files).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace anisodyn::tool {

/// {tool, version, git_revision, command_line, argv, created_utc, hostname, inputs: [{path, sha256}]}.
/// `command_line` is argv joined with POSIX shell quoting (copy-paste runnable); `created_utc` is
/// ISO 8601 ("2024-05-01T12:34:56Z"). A missing input file → InputError(path, "", "cannot open file: …").
nlohmann::json make_provenance(const std::string& tool, const std::vector<std::string>& argv,
                               const std::vector<std::string>& input_paths);

/// Convenience for main(): argv as strings.
std::vector<std::string> argv_vector(int argc, const char* const* argv);

/// The current UTC time as ISO 8601 with seconds and a trailing Z.
std::string utc_timestamp();

/// `arg` quoted for a POSIX shell when needed ('…' with embedded quotes escaped).
std::string shell_quote(const std::string& arg);

}  // namespace anisodyn::tool
