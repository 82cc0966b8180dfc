#pragma once
// The pulled tracer of active microrheology (spec 10 §4.5), as every engine takes it: one sphere
// (a species with exactly one particle) under a constant force F along a box axis with
// βF = Pe/a, a its radius, and its unwrapped centre recorded as the observable `tracer_position`
// every `record_every` steps or cycles, which anisodyn-microrheology reads. DMC turns the force
// into a biased move (dmc/dmc_engine.hpp), BD into a force (bd/bd_runner.hpp).
//
//   "tracer": {"species": "tracer", "pe": 1.0, "axis": "z", "record_every": 1}
#include <cstddef>
#include <cstdint>
#include <string>

#include "anisodyn/io/h5md.hpp"
#include "anisodyn/system/state.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::run {

struct PulledTracerSpec {
  std::string species;
  double peclet = 0.0;
  int axis = 2;  // box axis of the force: 0, 1, 2 = x, y, z
  std::int64_t record_every = 1;
};

/// Reads species, pe (≥ 0), axis ("x", "y", "z"; default z) and record_every of a `tracer` block;
/// an engine reads its own further keys from the same node.
PulledTracerSpec parse_pulled_tracer(tool::ConfigNode& node);

/// The tracer's particle index. InputError(file, "tracer.species") unless the species exists, has
/// exactly one particle, and is a sphere (the tracer does not rotate).
std::size_t find_pulled_tracer(const PulledTracerSpec& spec, const State& state, const std::string& file);

/// βF = Pe / a, a the tracer's radius (spec 10 §4.5).
double pulled_tracer_beta_force(const PulledTracerSpec& spec, const State& state, std::size_t particle);

/// Appends the tracer's unwrapped centre to the observable `tracer_position`.
void record_tracer_position(io::H5mdWriter& out, const State& state, std::size_t particle, std::int64_t step, double time);
/// The units and definition of `tracer_position` (once the observable exists).
void describe_tracer_position(io::H5mdWriter& out);

}  // namespace anisodyn::run
