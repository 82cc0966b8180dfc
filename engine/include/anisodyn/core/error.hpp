#pragma once
// Error types and the exit codes the executables map them to (architecture §5).
#include <stdexcept>
#include <string>

namespace anisodyn {

enum ExitCode : int { kExitOk = 0, kExitBadInput = 2, kExitRuntime = 3, kExitInterrupted = 130 };

/// Bad input: the message names the file, the JSON path (if any) and what was expected.
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string json_path, std::string problem)
      : std::runtime_error(compose(file, json_path, problem)),
        file_(std::move(file)), json_path_(std::move(json_path)) {}
  explicit InputError(std::string problem) : InputError("", "", std::move(problem)) {}
  const std::string& file() const { return file_; }
  const std::string& json_path() const { return json_path_; }

 private:
  static std::string compose(const std::string& file, const std::string& path, const std::string& problem) {
    std::string msg;
    if (!file.empty()) msg += file;
    if (!path.empty()) msg += (msg.empty() ? "" : ": ") + std::string("at ") + path;
    if (!msg.empty()) msg += ": ";
    return msg + problem;
  }
  std::string file_, json_path_;
};

/// A failure while running (I/O error, numerical breakdown): exit code 3.
class RuntimeFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Raised when SIGINT/SIGTERM was received and a checkpoint has been written: exit code 130.
class Interrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace anisodyn
