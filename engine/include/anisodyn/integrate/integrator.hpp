#pragma once
// The one interface every engine's time stepping implements, so that a shared runner can drive
// MC, DMC, BD, DPD and LB alike.
#include "anisodyn/system/state.hpp"

namespace anisodyn {

/// One engine's way of advancing a state by one step (MC/DMC: a cycle of trial moves; BD, DPD, LB: a time step).
class Integrator {
 public:
  virtual ~Integrator() = default;
  /// Advances the state by one step; returns the time the step covers (0 for MC).
  /// The caller owns State::step and State::time: it adds the returned time and counts the step.
  virtual double step(State& state) = 0;
};

}  // namespace anisodyn
