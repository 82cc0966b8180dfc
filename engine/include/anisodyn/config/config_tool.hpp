#pragma once
// The anisodyn-config stage: reads its JSON configuration (and optionally an existing state to
// insert into) and returns the new state. Kept out of main() so tests can call it directly.
#include <optional>
#include <string>

#include "anisodyn/tool/json_config.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

/// Builds the configuration described by `cfg`. With `existing`, the new particles are inserted
/// randomly into that state (its box and species are kept; new species are appended).
/// Every problem with the request is reported as an InputError naming the JSON path.
/// With diffusion_origins given, it receives {species name: where its diffusion coefficients came
/// from} for the species the configuration defines (see parse_species). With liquid_record given,
/// placement "colloids_in_liquid" records its counts there (liquid_particles, colloids, density, …).
State build_configuration(tool::ConfigNode& cfg, const std::optional<State>& existing, std::uint64_t seed, std::uint64_t replica = 0,
                          nlohmann::json* diffusion_origins = nullptr, nlohmann::json* liquid_record = nullptr);

}  // namespace anisodyn
