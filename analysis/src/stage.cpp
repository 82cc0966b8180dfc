#include "anisodyn/analysis/stage.hpp"

#include <cstdio>
#include <utility>

#include "anisodyn/core/error.hpp"
#include "anisodyn/tool/atomic_file.hpp"
#include "anisodyn/tool/provenance.hpp"

namespace anisodyn::analysis {

void StageRun::report_replica(std::size_t k, const std::string& path) const {
  if (opt.quiet) return;
  std::fprintf(stderr, "%s: replica %zu/%zu: %s\n", opt.tool.c_str(), k + 1, inputs.size(), path.c_str());
  std::fflush(stderr);
}

std::vector<double> StageRun::each_replica(const TrajectoryNeeds& needs,
                                           const std::function<void(const Trajectory&, std::size_t)>& fn,
                                           double time_tolerance) const {
  TrajectoryNeeds windowed = needs;
  windowed.window = window;
  FrameSelection selected;
  auto grid = for_each_replica(
      inputs, windowed,
      [&](const Trajectory& t, std::size_t k) {
        report_replica(k, t.path);
        if (k == 0) out.set_unit_system(t.units);
        fn(t, k);
      },
      time_tolerance, &selected);
  if (window.given) out.set_window(window.record(selected.frames, selected.grid));
  return grid;
}

void StageRun::fail(const std::string& key, const std::string& problem) const {
  throw InputError(opt.config_name(), key, problem);
}

std::vector<tool::Parameter> lag_grid_parameters(const std::string& mode) {
  const std::string when = mode.empty() ? "" : mode + ": ";
  return {tool::optional("lags_per_decade", "number", 10, when + "lag grid density (0: every lag)"),
          tool::optional("max_origins", "integer", 0, when + "thinning of time origins (0: every origin)")};
}

tool::Description analysis_description(std::vector<tool::Parameter> parameters, const std::string& output_meaning,
                                       const std::vector<tool::Parameter>& more) {
  tool::Description d;
  d.role = tool::Role::Analysis;
  d.replica = false;
  d.inputs = {"trajectory", 1, -1, "trajectories (H5MD), one per replica; shell globs allowed; or the key inputs"};
  d.output = {"analysis", "HDF5 + CSV", output_meaning + "; CSV files beside it unless csv is false", nullptr};
  d.parameters = std::move(parameters);
  d.parameters.insert(d.parameters.end(), more.begin(), more.end());
  d.parameters.push_back(tool::optional("inputs", "array", nullptr, "trajectory paths or globs, in addition to --input"));
  d.parameters.push_back(tool::optional("csv", "boolean", true, "write CSV files beside the HDF5 output"));
  d.parameters.push_back(tool::optional("window", "object", nullptr,
                                        "time window {from, to, stride} of the analysed frames (none: every frame)"));
  d.cost = tool::negligible_cost("analysis jobs are short next to the engine jobs they read");
  return d;
}

int run_analysis_stage(int argc, char** argv, const tool::ToolInfo& info, const std::function<void(StageRun&)>& body) {
  return tool::run_tool(argc, argv, info, [&](tool::CommonOptions& opt) {
    if (opt.output.empty()) throw InputError("--output", "", "expected an output file (.h5); CSV files are written beside it");
    tool::ConfigNode cfg(opt.config, opt.config_name());
    std::vector<std::string> patterns = opt.inputs;
    if (cfg.has("inputs"))
      for (auto& p : cfg.strings("inputs")) patterns.push_back(p);
    else
      cfg.mark_used("inputs");
    const bool csv = cfg.boolean("csv", true);
    const FrameWindow window = parse_frame_window(cfg);
    const std::vector<std::string> inputs = expand_inputs(patterns, opt.inputs.empty() ? opt.config_name() : "--input");
    tool::check_output_writable(opt.output);
    AnalysisOutput out(opt.output, opt.config, nlohmann::json::object());
    StageRun run{opt, cfg, inputs, out, window};
    body(run);
    out.set_provenance(tool::make_provenance(info.name, opt.argv, inputs));
    out.write(csv);
    if (!opt.quiet) std::fprintf(stderr, "%s: wrote %s\n", info.name.c_str(), opt.output.c_str());
  });
}

}  // namespace anisodyn::analysis
