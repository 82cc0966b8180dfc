#pragma once
// The frame every analysis executable shares: common options (architecture §5), input
// trajectories from --input (repeatable, shell globs allowed) and/or the config key `inputs`,
// the output HDF5 path (--output, required) with CSV files beside it unless `"csv": false`,
// progress lines, and the exit codes (2 for bad input, with nothing written).
//
// A stage's body reads its parameters from `cfg`, calls `cfg.finish()` (unknown keys → exit 2)
// before the heavy work, fills `out` and returns; the driver then writes all files atomically.
//
// The driver also reads the time window every stage takes (`window`, frame_window.hpp): each_replica
// loads only the window's frames and records the window in the output. A stage states how many
// frames it needs in TrajectoryNeeds::min_frames. A stage that analyses each species on its own runs
// through run_per_species (per_species_stage.hpp).
#include <functional>
#include <string>
#include <vector>

#include "anisodyn/analysis/analysis_output.hpp"
#include "anisodyn/analysis/trajectory.hpp"
#include "anisodyn/tool/command_line.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::analysis {

struct StageRun {
  tool::CommonOptions& opt;
  tool::ConfigNode& cfg;
  std::vector<std::string> inputs;  // expanded, in order
  AnalysisOutput& out;
  FrameWindow window;               // the configuration's `window` (not given = every frame)

  /// "replica k/n: path" on stderr (unless --quiet).
  void report_replica(std::size_t k, const std::string& path) const;
  /// Loads and checks every replica in turn (see for_each_replica), the frames of the window only,
  /// with progress; records the window in the output.
  std::vector<double> each_replica(const TrajectoryNeeds& needs,
                                   const std::function<void(const Trajectory&, std::size_t)>& fn,
                                   double time_tolerance = 0.05) const;
  /// A parameter error: InputError naming the config file and `key` (a path like "reference").
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;
};

int run_analysis_stage(int argc, char** argv, const tool::ToolInfo& info, const std::function<void(StageRun&)>& body);

/// The description (--describe) of an analysis stage: its own parameters, then `more` (e.g.
/// lag_grid_parameters()), then the keys the driver reads for every stage (inputs, csv, window);
/// trajectories in (any number), tables and scalars out, no cost estimate.
tool::Description analysis_description(std::vector<tool::Parameter> parameters, const std::string& output_meaning,
                                       const std::vector<tool::Parameter>& more = {});

/// lags_per_decade and max_origins, the lag-grid keys of the stages that correlate frames (`mode`:
/// the mode that reads them, e.g. "passive"; empty: every mode).
std::vector<tool::Parameter> lag_grid_parameters(const std::string& mode = "");

}  // namespace anisodyn::analysis
