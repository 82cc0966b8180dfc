#pragma once
// The step every run shares (docs/run.md): the engine advances its state by one step; the loop
// counts the step and its time (State::step, State::time), writes an observation row every
// `observe_every` steps, lets the engine record per-step data, and writes a frame when a frame
// rule fires. The production runner drives it through a field schedule, MC preparation through
// its phases; either way counting, observing, framing and their checkpointed cursor are written once.
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/io/h5md.hpp"
#include "anisodyn/run/frame_rules.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn::run {

/// What an engine provides to the step loop.
class StepClient {
 public:
  virtual ~StepClient() = default;
  /// Advances the state by one step (MC, DMC: one cycle); returns the time the step covered.
  virtual double advance() = 0;
  /// Advances the state by `k` steps at once, for clients that run several steps faster together
  /// (StepLoop::steps); returns the time each step covered. Only called by steps() for k > 1.
  virtual double advance_steps(std::int64_t /*k*/) { throw std::logic_error("this engine does not run steps in batches"); }
  /// Writes one row of observables, over the steps since the previous row, at (step, time).
  virtual void observe(io::H5mdWriter& out, std::int64_t step, double time) = 0;
  /// Per-step records after the step was counted (e.g. the pulled tracer's position).
  virtual void after_step(io::H5mdWriter&, std::int64_t /*step*/, double /*time*/) {}
  /// Engine-specific per-particle data written with every frame (pointers valid until the next call).
  virtual std::vector<io::ParticleElement> frame_elements() const { return {}; }
  /// The state a frame shows: the full one, or a part of it (DPD's colloids without the liquid).
  virtual const State& frame_state(const State& full) { return full; }
};

class StepLoop {
 public:
  StepLoop(State& state, StepClient& client, FrameRules frames, std::int64_t observe_every);

  /// One step: advance, count, observe if due, the client's per-step records, a frame if due.
  void step(io::H5mdWriter& out);
  /// How many of the next `wanted` steps, each `dt` long, can run as one batch: up to and
  /// including the first one at which an observation or a frame falls due (nothing else reads the
  /// state in between).
  std::int64_t quiet_steps(std::int64_t wanted, double dt) const;
  /// `k` steps (k ≤ quiet_steps(k, dt)) as one batch (StepClient::advance_steps), counted as step()
  /// counts them; the observation or frame, if any, comes after the last. For clients without
  /// per-step records (after_step).
  void steps(io::H5mdWriter& out, std::int64_t k);
  /// The end of a run: a last observation row over the steps since the previous one (when
  /// `remainder_row`), and the final frame unless the last step already wrote it.
  void finish(io::H5mdWriter& out, bool remainder_row);
  void write_frame(io::H5mdWriter& out);
  /// Frame rules that count from a field switch (after_switch, log_cycles) count from this step.
  void mark_switch() { last_switch_step_ = step_; }

  std::int64_t step() const { return step_; }
  double time() const { return time_; }

  nlohmann::json checkpoint_state() const;
  /// Also sets the state's step and time to the checkpoint's.
  void restore(const nlohmann::json& j);

 private:
  void observe(io::H5mdWriter& out);
  /// Counts one step of `dt` already taken: observation, per-step records and frame when due.
  void count_step(io::H5mdWriter& out, double dt);

  State& state_;
  StepClient& client_;
  FrameClock frames_;
  std::int64_t observe_every_;
  std::int64_t step_ = 0;
  double time_ = 0.0;
  std::int64_t last_switch_step_ = 0;
  std::int64_t steps_since_observation_ = 0;
};

}  // namespace anisodyn::run
