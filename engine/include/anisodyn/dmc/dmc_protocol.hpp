#pragma once
// What an anisodyn-dmc run does, as parsed from its JSON configuration (docs/dmc.md): time steps
// and their balancing, the field schedule, the pulled tracer, frame spacing and observables. The
// field, schedule and frame blocks follow the schema every engine shares (run/, docs/run.md).
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "anisodyn/dmc/dmc_engine.hpp"
#include "anisodyn/dmc/time_balance.hpp"
#include "anisodyn/io/diffusion_overrides.hpp"
#include "anisodyn/run/field_config.hpp"
#include "anisodyn/run/frame_rules.hpp"
#include "anisodyn/run/pulled_tracer.hpp"
#include "anisodyn/run/schedule.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn {

/// The pulled tracer (run/pulled_tracer.hpp) with DMC's choice of the bath acceptance A_0.
struct TracerSettings : run::PulledTracerSpec {
  TracerBathAcceptance a0 = TracerBathAcceptance::OverlapPass;
  double a0_value = 1.0;
};

struct DmcProtocol {
  std::uint64_t seed = 1;
  std::uint64_t replica = 0;
  DmcMoveOptions moves;
  std::map<std::string, double> time_steps;  // δt_MC per species name (the reference's is required)
  BalanceMode balance = BalanceMode::Equilibrium;
  std::string reference, clock;              // species names ("" → defaults)
  std::int64_t preliminary_cycles = 10000;
  int preliminary_iterations = 3;
  double preliminary_tolerance = 1e-3;
  double smoothing_cycles = 10.0;
  std::vector<run::FieldSegment> segments;   // the whole run, in order
  run::FieldConfig field;
  std::optional<TracerSettings> tracer;
  run::FrameRules frames;
  std::int64_t observe_every = 1;
  /// Diffusion coefficients replacing those of the input's species table ("species").
  io::DiffusionOverrides diffusion;
  // Keys whose effect depends on the input's species (checked by check_protocol_species): the path
  // of the first preliminary-run key given and of the first rotation-move key given.
  std::string preliminary_key, rotation_move_key;
};

/// Parses the configuration. Names of species are checked later against the input state
/// (check_protocol_species), when the species table is known.
DmcProtocol parse_dmc_protocol(tool::ConfigNode& cfg);
/// Checks species names and the tracer against the state; InputError(file, path, …) otherwise.
void check_protocol_species(const DmcProtocol& p, const State& state, const std::string& config_file);

}  // namespace anisodyn
