#pragma once
// What an anisodyn-dmc run does, as parsed from its JSON configuration (docs/dmc.md): time steps
// and their balancing, the field schedule, the pulled tracer, frame spacing and observables.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "anisodyn/dmc/dmc_engine.hpp"
#include "anisodyn/dmc/time_balance.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn {

/// One stretch of the run with the field on or off. Its end is given as a duration from the
/// segment's start (cycles or Brownian time) or as an absolute instant (from a `switches` list).
struct FieldSegment {
  bool field_on = false;
  enum class Unit { Cycles, Time } unit = Unit::Cycles;
  bool absolute = false;
  double length = 0.0;  // duration (or end instant when absolute) in cycles or τ
};

/// Frame spacing: a frame is written at the end of any cycle where one of the rules fires, plus
/// always at the start and at the end of production.
struct FrameRules {
  std::int64_t every_cycles = 0;        // linear in cycles
  double every_time = 0.0;              // linear in Brownian time
  double log_first_time = 0.0;          // logarithmic in Brownian time: t_k = first · 10^(k/per_decade)
  double log_per_decade = 0.0;
  std::int64_t after_switch_every = 0;  // denser frames for a while after each field switch
  std::int64_t after_switch_for = 0;
  double log_cycles_per_decade = 0.0;   // logarithmic in cycles after each switch (and the start) …
  std::int64_t log_cycles_restart = 0;  // … restarted every this many cycles (0: once per switch)

  /// Whether the logarithmic cycle rule writes a frame `since_switch` cycles after the last switch:
  /// m = since_switch (mod restart) is 0 or one of round(10^(k/per_decade)), k = 0, 1, … (1, 2, 3,
  /// 4, 6, 7, 10, … cycles at 5 per decade), so that every restart block holds lags from one cycle
  /// up, wherever a time window later cuts the run.
  bool log_cycle_due(std::int64_t since_switch) const;
};

struct TracerSettings {
  std::string species;
  double peclet = 0.0;
  int axis = 2;
  TracerBathAcceptance a0 = TracerBathAcceptance::OverlapPass;
  double a0_value = 1.0;
  std::int64_t record_every = 1;
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
  std::vector<FieldSegment> segments;        // the whole run, in order
  OrientationalField field;                  // strength 0: none
  bool check_field_direction = true;
  double dipole_gamma = 0.0;
  std::vector<std::string> dipole_species;
  double ewald_accuracy = 1e-5;
  bool ewald_minimum_image_only = false;
  std::optional<TracerSettings> tracer;
  FrameRules frames;
  std::int64_t observe_every = 1;
  /// Diffusion coefficients replacing those of the input's species table.
  std::map<std::string, std::pair<std::optional<Vec3>, std::optional<Vec3>>> diffusion;
  std::map<std::string, Shape> diffusion_shape;  // shapes of entries taken from species files (checked against the input)
  nlohmann::json diffusion_origins = nlohmann::json::object();  // species name → where its override came from
  // Keys whose effect depends on the input's species (checked by check_protocol_species): the path
  // of the first preliminary-run key given, of the first rotation-move key given, and of each
  // species' rotational diffusion given.
  std::string preliminary_key, rotation_move_key;
  std::map<std::string, std::string> rotational_diffusion_keys;
};

/// Parses the configuration. Names of species are checked later against the input state
/// (check_protocol_species), when the species table is known.
DmcProtocol parse_dmc_protocol(tool::ConfigNode& cfg);
/// Checks species names and the tracer against the state; InputError(file, path, …) otherwise.
void check_protocol_species(const DmcProtocol& p, const State& state, const std::string& config_file);

}  // namespace anisodyn
