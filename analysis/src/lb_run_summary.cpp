#include "anisodyn/analysis/lb_run_summary.hpp"

#include "anisodyn/core/error.hpp"

namespace anisodyn::analysis {

LbRunSummary read_lb_run_summary(const io::H5mdReader& reader, const std::string& path, const std::string& needs) {
  const auto engine = reader.checkpoint();
  if (!engine || !engine->contains("runner") || !engine->at("runner").contains("summary") ||
      !engine->at("runner").at("summary").contains("raspberries"))
    throw InputError(path, "/anisodyn/checkpoint/engine_state", "an anisodyn-lb run (its final state has no summary of raspberries)");
  LbRunSummary out;
  out.summary = engine->at("runner").at("summary");
  if (!needs.empty() && !out.summary.contains(needs))
    throw InputError(path, "/anisodyn/checkpoint/engine_state", "an anisodyn-lb run with a " + needs + " (its summary has none)");
  const nlohmann::json& bodies = out.summary.at("raspberries").at("bodies");
  if (bodies.size() != 1) throw InputError(path, "/particles/all", "one raspberry species");
  out.body = bodies.begin().value();
  return out;
}

}  // namespace anisodyn::analysis
