#pragma once
// The frame every analysis executable shares: common options (architecture §5), input
// trajectories from --input (repeatable, shell globs allowed) and/or the config key `inputs`,
// the output HDF5 path (--output, required) with CSV files beside it unless `"csv": false`,
// progress lines, and the exit codes (2 for bad input, with nothing written).
//
// A stage's body reads its parameters from `cfg`, calls `cfg.finish()` (unknown keys → exit 2)
// before the heavy work, fills `out` and returns; the driver then writes all files atomically.
#include <functional>
#include <string>
#include <vector>

#include "anisodyn/analysis/analysis_output.hpp"
#include "anisodyn/analysis/trajectory.hpp"
#include "anisodyn/io/command_line.hpp"
#include "anisodyn/io/json_config.hpp"

namespace anisodyn::analysis {

struct StageRun {
  io::CommonOptions& opt;
  io::ConfigNode& cfg;
  std::vector<std::string> inputs;  // expanded, in order
  AnalysisOutput& out;

  /// "replica k/n: path" on stderr (unless --quiet).
  void report_replica(std::size_t k, const std::string& path) const;
  /// Loads and checks every replica in turn (see for_each_replica), with progress.
  std::vector<double> each_replica(const TrajectoryNeeds& needs,
                                   const std::function<void(const Trajectory&, std::size_t)>& fn,
                                   double time_tolerance = 0.05) const;
  /// A parameter error: InputError naming the config file and `key` (a path like "reference").
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;
};

int run_analysis_stage(int argc, char** argv, const io::ToolInfo& info, const std::function<void(StageRun&)>& body);

}  // namespace anisodyn::analysis
