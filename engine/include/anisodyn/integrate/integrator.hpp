#pragma once
// The one interface every engine's time stepping implements, so that a shared runner can drive
// MC, DMC, BD, DPD and LB alike.
#include <stdexcept>

#include "anisodyn/system/state.hpp"

namespace anisodyn {

/// One engine's way of advancing a state by one step (MC/DMC: a cycle of trial moves; BD, DPD, LB: a time step).
class Integrator {
 public:
  virtual ~Integrator() = default;
  /// Advances the state by one step; returns the time the step covers: 0 where the integrator
  /// cannot tell (MC has no time; a DMC cycle's Brownian time is assigned by the run's time balance).
  /// The caller owns State::step and State::time: it adds the returned time and counts the step.
  virtual double step(State& state) = 0;
};

/// An engine whose step is one cycle() of the state it was built on (MC, DMC: their neighbour
/// structures follow that state), seen as an Integrator. The engines themselves stay free of a
/// virtual table: an object pointer more at their head cost MC 0.6% per trial (docs/performance.md).
/// Stepping another state is a programming error.
template <class Engine>
class CycleIntegrator final : public Integrator {
 public:
  explicit CycleIntegrator(Engine& engine) : engine_(engine) {}
  /// One cycle; returns 0: MC has no time, and a DMC cycle's Brownian time is assigned by the run's time balance.
  double step(State& state) override {
    if (&state != &engine_.state()) throw std::logic_error("an engine's cycle was asked to step a state other than its own");
    engine_.cycle();
    return 0.0;
  }

 private:
  Engine& engine_;
};

}  // namespace anisodyn
