#pragma once
// The production loop every engine shares (docs/architecture.md): the field schedule, the frame
// rules, the observation cadence, the cursor and its checkpoint, H5MD streaming and the progress
// line, written once. An engine plugs in as a ProductionClient: it advances its state by one step
// and says what it observes; the runner decides when.
//
// Per step, in this order: the client advances the state; the runner counts the step and its time
// (State::step, State::time); an observation row if the step is a multiple of observe_every; the
// client's per-step records; a frame if a frame rule fires. A frame is always written at the start
// and at the end of production, and a last observation row covers any steps after the previous one.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/io/h5md.hpp"
#include "anisodyn/run/checkpoint_clock.hpp"
#include "anisodyn/run/frame_rules.hpp"
#include "anisodyn/run/schedule.hpp"
#include "anisodyn/run/step_unit.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn::run {

/// What an engine provides to the production runner.
class ProductionClient {
 public:
  virtual ~ProductionClient() = default;
  /// Advances the state by one step (DMC: one cycle); returns the time the step covered.
  virtual double advance() = 0;
  /// Writes one row of observables, over the steps since the previous row, at (step, time).
  virtual void observe(io::H5mdWriter& out, std::int64_t step, double time) = 0;
  /// Per-step records after the step was counted (e.g. the pulled tracer's position).
  virtual void after_step(io::H5mdWriter&, std::int64_t /*step*/, double /*time*/) {}
  /// Switches the field on or off at `step`; returns the field direction in force afterwards.
  virtual Vec3 switch_field(bool on, std::int64_t step) = 0;
  virtual bool field_on() const = 0;
  /// Engine-specific per-particle data written with every frame (pointers valid until the next call).
  virtual std::vector<io::ParticleElement> frame_elements() const { return {}; }
};

struct ProductionSettings {
  std::vector<FieldSegment> schedule;  // the whole run (parse_schedule)
  FrameRules frames;
  std::int64_t observe_every = 1;
  StepUnit unit = StepUnit::steps();
  std::string label = "production";    // progress line
};

class ProductionRunner {
 public:
  ProductionRunner(State& state, ProductionClient& client, ProductionSettings settings, bool quiet);

  /// Runs from the cursor to the end of the schedule. `steps_before` counts the steps of earlier
  /// stages of the same run (e.g. DMC's preliminary balancing), so that checkpoints keep their
  /// cadence over the whole run.
  void run(io::H5mdWriter& out, CheckpointClock& checkpoints, std::int64_t steps_before);

  std::int64_t step() const { return step_; }
  double time() const { return time_; }
  /// The field switches so far: [{step unit: …, "time", "field": "on" | "off"}, …].
  const nlohmann::json& switches() const { return switches_; }

  nlohmann::json checkpoint_state() const;
  /// Also sets the state's step and time to the checkpoint's.
  void restore(const nlohmann::json& j);

 private:
  void start_segment(io::H5mdWriter& out);
  void switch_field(io::H5mdWriter& out, bool on);
  void one_step(io::H5mdWriter& out);
  void observe(io::H5mdWriter& out);
  void write_frame(io::H5mdWriter& out);

  State& state_;
  ProductionClient& client_;
  ProductionSettings settings_;
  bool quiet_;
  ScheduleClock schedule_;
  FrameClock frames_;
  std::int64_t step_ = 0;
  double time_ = 0.0;
  std::int64_t last_switch_step_ = 0;
  std::int64_t steps_since_observation_ = 0;
  nlohmann::json switches_ = nlohmann::json::array();
};

}  // namespace anisodyn::run
