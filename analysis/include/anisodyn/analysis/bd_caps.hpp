#pragma once
// anisodyn-bd's `capped` observable (particle-steps with a capped force, and torque, per row): the
// BD stages report how often the caps changed the dynamics they measure.
#include <optional>

#include "anisodyn/analysis/trajectory.hpp"

namespace anisodyn::analysis {

inline constexpr const char* kCappedObservable = "capped";

/// Particle-steps with a capped torque over the loaded rows; none if the run has no such record.
std::optional<double> capped_torque_steps(const Trajectory& t);

}  // namespace anisodyn::analysis
