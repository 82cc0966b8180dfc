// anisodyn-observables: means and drifts of an engine's observation rows over the window, with errors
// over replicas (or blocks of one replica): e.g. anisodyn-dpd's kinetic temperature and pressure, and
// the energy drift of a run without thermostat (spec 60 C0).
#include <cstdio>

#include "anisodyn/analysis/observable_summary.hpp"
#include "anisodyn/analysis/stage.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

/// name, or name_k for component k of a vector observable.
std::string component_name(const std::string& name, std::size_t k, std::size_t width) {
  return width == 1 ? name : name + "_" + std::to_string(k);
}

tool::Description description() {
  return analysis_description(
      {tool::optional("means", "array", nlohmann::json::array(), "observables whose mean over the window's rows is reported (scalars <name>, or <name>_<k> per component)"),
       tool::optional("drifts", "array", nlohmann::json::array(),
                      "observables whose slope against time over the window is reported (scalars <name>_drift per time unit and "
                      "<name>_change over the window)"),
       tool::optional("blocks", "integer", 10, "a single replica's rows in this many blocks for the errors (several replicas: one sample each)")},
      "scalars <name> (means) and <name>_drift, <name>_change (drifts), each with its error");
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-observables", "means and drifts of observation rows (temperature, pressure, energy)",
                            "See docs/analysis.md.", description()};
  return run_analysis_stage(argc, argv, info, [](StageRun& run) {
    const auto means = run.cfg.has("means") ? run.cfg.strings("means") : std::vector<std::string>{};
    const auto drifts = run.cfg.has("drifts") ? run.cfg.strings("drifts") : std::vector<std::string>{};
    if (means.empty() && drifts.empty()) run.fail("means", "expected at least one observable in means or drifts");
    const auto blocks = static_cast<std::size_t>(run.cfg.positive_integer("blocks", 10));
    run.cfg.reject_unless(run.inputs.size() == 1, "blocks", "with several replicas (each replica is one sample)");
    if (run.inputs.size() == 1 && blocks < 2) run.fail("blocks", "expected at least 2 blocks for an error bar");
    run.cfg.finish();
    const auto keep = [&](double t) { return run.window.contains(t); };
    auto rows_of = [&](const std::string& name) {
      std::vector<ObservableRows> runs;
      for (const std::string& path : run.inputs) runs.push_back(read_rows(path, name, keep));
      if (run.inputs.size() == 1 && runs.front().time.size() < blocks)
        run.fail("blocks", "expected at least as many rows of " + name + " in the window (" + std::to_string(runs.front().time.size()) +
                               ") as blocks");
      return runs;
    };
    const nlohmann::json details = {{"samples", run.inputs.size() == 1 ? blocks : run.inputs.size()},
                                    {"error", run.inputs.size() == 1 ? "jackknife over blocks of the rows" : "over replicas"}};
    for (std::size_t k = 0; k < run.inputs.size(); ++k) run.report_replica(k, run.inputs[k]);
    for (const std::string& name : means) {
      const auto runs = rows_of(name);
      const auto m = observable_means(runs, blocks);
      for (std::size_t k = 0; k < m.size(); ++k)
        run.out.scalar({component_name(name, k, m.size()), m[k].value, m[k].error, runs.front().units,
                        "mean of the observable " + name + (m.size() > 1 ? " (component " + std::to_string(k) + ")" : "") +
                            " over the window's rows (units of the run's observable)",
                        details});
    }
    for (const std::string& name : drifts) {
      const auto runs = rows_of(name);
      const auto d = observable_drifts(runs, blocks);
      const double span = runs.front().time.back() - runs.front().time.front();
      for (std::size_t k = 0; k < d.size(); ++k) {
        const std::string base = component_name(name, k, d.size());
        const std::string& units = runs.front().units;
        run.out.scalar({base + "_drift", d[k].value, d[k].error, units.empty() ? "1/tau" : units + "/tau",
                        "least-squares slope of " + name + " against time over the window (units of the observable per tau)", details});
        run.out.scalar({base + "_change", d[k].value * span, d[k].error * span, units,
                        "the slope times the window's span (" + std::to_string(span) + " tau): the drift over the window", details});
      }
    }
  });
}
