#pragma once
// The production loop every engine shares (docs/architecture.md): the field schedule, the frame
// rules, the observation cadence, the cursor and its checkpoint, H5MD streaming and the progress
// line, written once. An engine plugs in as a ProductionClient: it advances its state by one step
// and says what it observes; the runner decides when.
//
// Each step is the shared StepLoop's (run/step_loop.hpp): advance, count, observe, per-step
// records, frame. The runner adds the field schedule, a frame at the start, and at the end a last
// observation row over any steps after the previous one and the final frame.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/io/h5md.hpp"
#include "anisodyn/run/checkpoint_clock.hpp"
#include "anisodyn/run/frame_rules.hpp"
#include "anisodyn/run/schedule.hpp"
#include "anisodyn/run/step_loop.hpp"
#include "anisodyn/run/step_unit.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn::run {

/// What an engine provides to the production runner: the step loop's client, plus the field switch.
class ProductionClient : public StepClient {
 public:
  /// Switches the field on or off at `step`; returns the field direction in force afterwards.
  virtual Vec3 switch_field(bool on, std::int64_t step) = 0;
  virtual bool field_on() const = 0;
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

  std::int64_t step() const { return loop_.step(); }
  double time() const { return loop_.time(); }
  /// The field switches so far: [{step unit: …, "time", "field": "on" | "off"}, …].
  const nlohmann::json& switches() const { return switches_; }

  nlohmann::json checkpoint_state() const;
  /// Also sets the state's step and time to the checkpoint's.
  void restore(const nlohmann::json& j);

 private:
  void start_segment(io::H5mdWriter& out);
  void switch_field(io::H5mdWriter& out, bool on);

  ProductionClient& client_;
  std::string label_;
  StepUnit unit_;
  bool quiet_;
  ScheduleClock schedule_;
  StepLoop loop_;
  nlohmann::json switches_ = nlohmann::json::array();
};

}  // namespace anisodyn::run
