#pragma once
// What the LB analysis stages read of an anisodyn-lb run: the summary its final engine state keeps
// (runner.summary: fluid, kT, raspberries with their bodies, pore) and its one raspberry body.
#include <string>

#include <nlohmann/json.hpp>

#include "anisodyn/io/h5md.hpp"

namespace anisodyn::analysis {

struct LbRunSummary {
  nlohmann::json summary;  ///< runner.summary
  nlohmann::json body;     ///< the one raspberry species' entry of summary.raspberries.bodies
};

/// InputError naming the file unless it is an anisodyn-lb run of one raspberry species; `needs`
/// (e.g. "pore") must be a key of its summary when given.
LbRunSummary read_lb_run_summary(const io::H5mdReader& reader, const std::string& path, const std::string& needs = "");

}  // namespace anisodyn::analysis
